// The far field of the hybrid yarn as fibres (doc/hybrid.md section 3.4):
// each fibre a chain of bars between the FE part's node layers, axial
// unknowns of its own, the continuum's transverse motion.

#include <yarn_impact/contact/projectile_contact.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/coupling/fibre_bars.h>
#include <yarn_impact/coupling/hybrid_parts.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace YarnImpact
{
  namespace Coupling
  {
    using namespace dealii;


    void
    FibreBars::set_up(ImpactModel &fe_model,
                      const Triangulation<2> &section,
                      const HybridLayout &layout,
                      const YarnImpact::Parameters::Yarn &yarn,
                      const std::vector<double> &fibre_y_,
                      const std::vector<double> &fibre_z_,
                      const bool failure_,
                      const bool z_symmetry,
                      const MPI_Comm communicator_)
    {
      communicator = communicator_;
      fibre_y      = fibre_y_;
      fibre_z      = fibre_z_;
      n_fibres     = fibre_y.size();
      fibre_weight.resize(n_fibres);
      for (unsigned int f = 0; f < n_fibres; ++f)
        fibre_weight[f] = (z_symmetry && fibre_z[f] == 0.) ? 0.5 : 1.;
      n_layers       = layout.fe_cells + 1;
      bars_per_cell  = layout.bars_per_cell;
      n_nodes        = bars_per_cell * layout.fe_cells + 1;
      h              = layout.cell_length / bars_per_cell;
      x_begin        = layout.overlap_begin;
      failure        = failure_;
      failure_strain = yarn.failure_strain;
      const double area =
        numbers::PI * 0.25 * yarn.fibre_diameter * yarn.fibre_diameter;
      stiffness                   = yarn.fibre_modulus * area / h;
      const double linear_density = yarn.fibre_density * area;

      cell_weight.assign(layout.fe_cells, 1.);
      for (unsigned int k = 0; k < layout.overlap_cells; ++k)
        cell_weight[k] = 1. - layout.particle_weight(k);
      // With a DEM part at the clamp the bars end in its overlap, free,
      // weighted there as the FE part is.
      if (layout.clamp_cells > 0)
        for (unsigned int k = 0; k < layout.overlap_cells; ++k)
          cell_weight[layout.fe_cells - layout.overlap_cells + k] =
            1. - layout.clamp_particle_weight(k);

      n_overlap_nodes = layout.overlap_cells * bars_per_cell + 1;
      n_clamp_nodes   = layout.clamp_cells > 0 ? n_overlap_nodes : 0;
      // Contiguous fibre ranges, as even as they go.
      const unsigned int n_ranks =
        Utilities::MPI::n_mpi_processes(communicator);
      const unsigned int rank = Utilities::MPI::this_mpi_process(communicator);
      rank_fibres.resize(n_ranks + 1);
      for (unsigned int r = 0; r <= n_ranks; ++r)
        rank_fibres[r] = (std::size_t(n_fibres) * r) / n_ranks;
      fibre_begin = rank_fibres[rank];
      fibre_end   = rank_fibres[rank + 1];

      const std::size_t n_all = std::size_t(n_fibres) * n_nodes;
      displacement.assign(n_all, 0.);
      velocity.assign(n_all, 0.);
      force.assign(n_all, 0.);
      strain.assign(n_all, 0.);
      broken.assign(n_all, 0);
      break_time.assign(n_all, 0.);
      mass.assign(n_all, 0.);
      for (unsigned int f = 0; f < n_fibres; ++f)
        for (unsigned int j = 0; j + 1 < n_nodes; ++j)
          {
            double xi;
            const double m = 0.5 * fibre_weight[f] *
                             cell_weight[cell_of(j, xi)] * linear_density * h;
            mass[index(f, j)] += m;
            mass[index(f, j + 1)] += m;
          }

      inverse_mass.resize(n_all);
      for (std::size_t i = 0; i < n_all; ++i)
        inverse_mass[i] = 1. / mass[i];

      // Where each fibre lies in the section.
      fibre_vertices.resize(n_fibres);
      fibre_values.resize(n_fibres);
      for (unsigned int f = 0; f < n_fibres; ++f)
        {
          unsigned int cell;
          locate_in_section(section,
                            Point<2>(fibre_y[f], fibre_z[f]),
                            cell,
                            fibre_vertices[f],
                            fibre_values[f]);
        }

      // The owned FE nodes of the layers, by (layer, vertex).
      n_vertices = section.n_vertices();
      owned_nodes =
        layer_nodes(fe_model,
                    section,
                    x_begin,
                    layout.cell_length,
                    n_layers,
                    std::min(yarn.thickness_semi_axis, yarn.width_semi_axis),
                    communicator);
      node_state.assign(node_stride * n_layers * n_vertices, 0.);
      set_up_projection();
      node_force.assign(2 * n_layers * n_vertices, 0.);
      layer_displacement.assign(2 * n_layers, 0.);
      fibre_record.assign(std::size_t(n_fibres) * record_size(), 0.);
      layer_axial.assign(std::size_t(n_fibres) * n_layers, 0.);
      fibre_dissipated.assign(n_fibres, 0.);
      fibre_contact_dissipated.assign(n_fibres, 0.);
      contact_history.assign(3 * n_all, 0.);
      touching.assign(n_all, 0);
      axial_tension.assign(n_nodes, 0.);

      // Gershgorin: omega^2 <= 2 sum of the adjacent bars' stiffness over
      // the node's mass.
      double rate2 = 0.;
      for (unsigned int f = 0; f < n_fibres; ++f)
        for (unsigned int j = 0; j < n_free_nodes(); ++j)
          {
            double xi;
            double k_sum = j + 1 < n_nodes ? cell_weight[cell_of(j, xi)] : 0.;
            if (j > 0)
              k_sum += cell_weight[cell_of(j - 1, xi)];
            k_sum *= fibre_weight[f];
            rate2 = std::max(rate2, 2. * stiffness * k_sum / mass[index(f, j)]);
          }
      stable_step =
        rate2 > 0. ? 2. / std::sqrt(rate2) : std::numeric_limits<double>::max();
    }


    template <typename T>
    void
    FibreBars::gather_fibres(std::vector<T> &values,
                             const unsigned int per_fibre) const
    {
      const unsigned int n_ranks = rank_fibres.size() - 1;
      if (n_ranks == 1)
        return;
      AssertDimension(values.size(), std::size_t(n_fibres) * per_fibre);
      std::vector<int> counts(n_ranks), offsets(n_ranks);
      for (unsigned int r = 0; r < n_ranks; ++r)
        {
          counts[r]  = (rank_fibres[r + 1] - rank_fibres[r]) * per_fibre;
          offsets[r] = rank_fibres[r] * per_fibre;
        }
      const int ierr =
        MPI_Allgatherv(MPI_IN_PLACE,
                       0,
                       MPI_DATATYPE_NULL,
                       values.data(),
                       counts.data(),
                       offsets.data(),
                       std::is_same_v<T, double> ? MPI_DOUBLE : MPI_UINT8_T,
                       communicator);
      AssertThrowMPI(ierr);
    }


    // The gathers fibre_bars_observables.cc uses.
    template void
    FibreBars::gather_fibres(std::vector<double> &, const unsigned int) const;
    template void
    FibreBars::gather_fibres(std::vector<std::uint8_t> &,
                             const unsigned int) const;


    void
    FibreBars::set_up_projection()
    {
      // G = Psi^T W Psi (n_v x n_v) and Psi^T W, then P = G^-1 Psi^T W by
      // Cholesky, column by column; W: the fibres' weights (a half fibre
      // on z = 0 is half of a mirror pair).
      const unsigned int n = n_vertices;
      std::vector<double> G(std::size_t(n) * n, 0.);
      projection.assign(std::size_t(n) * n_fibres, 0.);
      for (unsigned int f = 0; f < n_fibres; ++f)
        for (unsigned int a = 0; a < 4; ++a)
          {
            const unsigned int va = fibre_vertices[f][a];
            const double w_psi    = fibre_weight[f] * fibre_values[f][a];
            projection[std::size_t(va) * n_fibres + f] += w_psi;
            for (unsigned int b = 0; b < 4; ++b)
              G[std::size_t(va) * n + fibre_vertices[f][b]] +=
                w_psi * fibre_values[f][b];
          }
      for (unsigned int j = 0; j < n; ++j)
        {
          double d = G[std::size_t(j) * n + j];
          for (unsigned int k = 0; k < j; ++k)
            d -= G[std::size_t(j) * n + k] * G[std::size_t(j) * n + k];
          AssertThrow(d > 1e-12 * n_fibres,
                      ExcMessage("Hybrid: too few fibres around a section "
                                 "vertex for the fibre bars' axial fit; "
                                 "lower FE/Section refinements"));
          G[std::size_t(j) * n + j] = std::sqrt(d);
          for (unsigned int i = j + 1; i < n; ++i)
            {
              double s = G[std::size_t(i) * n + j];
              for (unsigned int k = 0; k < j; ++k)
                s -= G[std::size_t(i) * n + k] * G[std::size_t(j) * n + k];
              G[std::size_t(i) * n + j] = s / G[std::size_t(j) * n + j];
            }
        }
      std::vector<double> b(n);
      for (unsigned int f = 0; f < n_fibres; ++f)
        {
          for (unsigned int i = 0; i < n; ++i)
            b[i] = projection[std::size_t(i) * n_fibres + f];
          for (unsigned int i = 0; i < n; ++i)
            {
              for (unsigned int k = 0; k < i; ++k)
                b[i] -= G[std::size_t(i) * n + k] * b[k];
              b[i] /= G[std::size_t(i) * n + i];
            }
          for (unsigned int i = n; i-- > 0;)
            {
              for (unsigned int k = i + 1; k < n; ++k)
                b[i] -= G[std::size_t(k) * n + i] * b[k];
              b[i] /= G[std::size_t(i) * n + i];
            }
          for (unsigned int i = 0; i < n; ++i)
            projection[std::size_t(i) * n_fibres + f] = b[i];
        }
    }


    void
    FibreBars::set_continuum_axial(ImpactModel &fe_model)
    {
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        for (unsigned int k = 0; k < n_layers; ++k)
          layer_axial[std::size_t(f) * n_layers + k] =
            displacement[index(f, k * bars_per_cell)];
      gather_fibres(layer_axial, n_layers);
      const FE::CouplingView fe = FE::coupling_view(fe_model);
      for (const auto &[c, dofs] : owned_nodes)
        {
          const unsigned int k = c / n_vertices, v = c % n_vertices;
          const double *p = &projection[std::size_t(v) * n_fibres];
          double u        = 0.;
          for (unsigned int f = 0; f < n_fibres; ++f)
            u += p[f] * layer_axial[std::size_t(f) * n_layers + k];
          fe.displacement[dofs[0]] = u;
          fe.velocity[dofs[0]]     = 0.;
        }
    }


    void
    FibreBars::kick(const double dt)
    {
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        // The last node is held at the clamp, unless a DEM part is there.
        for (unsigned int j = 0; j < n_free_nodes(); ++j)
          {
            const std::size_t i = index(f, j);
            velocity[i] += dt * force[i] * inverse_mass[i];
          }
    }


    void
    FibreBars::drift(const double dt)
    {
      for (std::size_t i = index(fibre_begin, 0); i < index(fibre_end, 0); ++i)
        displacement[i] += dt * velocity[i];
      time += dt;
    }


    double
    FibreBars::compute_forces(ImpactModel &fe_model,
                              const Projectile &projectile,
                              const double dt,
                              const MPI_Comm communicator)
    {
      const FE::CouplingView fe = FE::coupling_view(fe_model);
      // Gather: each entry has one owner and the others add zeros, so the
      // sums are exact and the same on every rank. The FE part's axial
      // forces go to the fibres (P^T f_x, below).
      std::fill(node_state.begin(), node_state.end(), 0.);
      for (const auto &[c, dofs] : owned_nodes)
        {
          double *const state = &node_state[node_stride * c];
          for (unsigned int d = 0; d < 2; ++d)
            {
              state[d]     = fe.displacement[dofs[1 + d]];
              state[3 + d] = fe.velocity[dofs[1 + d]];
            }
          state[2]          = fe.force[dofs[0]];
          fe.force[dofs[0]] = 0.;
        }
      Utilities::MPI::sum(node_state, communicator, node_state);

      const unsigned int n_record = record_size();
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        {
          // The fibre's transverse displacement at each layer.
          for (unsigned int k = 0; k < n_layers; ++k)
            for (unsigned int d = 0; d < 2; ++d)
              layer_displacement[2 * k + d] = at_fibre(f, k, d);
          double *const record = &fibre_record[std::size_t(f) * n_record];
          double *const fibre_layer_force = record;
          std::fill(fibre_layer_force, fibre_layer_force + 2 * n_layers, 0.);
          double n_breaking        = 0.;
          double *const u          = &displacement[index(f, 0)];
          double *const e          = &strain[index(f, 0)];
          double *const q          = axial_tension.data();
          std::uint8_t *const gone = &broken[index(f, 0)];
          const double inverse_h   = 1. / h;
          // Between two node layers the transverse displacement is linear
          // in x, so every bar of a cell has the same transverse chord
          // (dy, dz): per bar only its axial chord and length remain, in
          // loops without branches, and the cell's bars pull on its two
          // layers with the sum of their s = k (l - h) / l.
          for (unsigned int c = 0; c + 1 < n_layers; ++c)
            {
              const unsigned int j0 = c * bars_per_cell,
                                 j1 = std::min(j0 + bars_per_cell, n_nodes - 1);
              const double dy       = (layer_displacement[2 * (c + 1)] -
                                 layer_displacement[2 * c]) /
                                bars_per_cell,
                           dz = (layer_displacement[2 * (c + 1) + 1] -
                                 layer_displacement[2 * c + 1]) /
                                bars_per_cell;
              const double t2 = dy * dy + dz * dz;
              // The bar lies in the cell of its first node.
              const double k_w = cell_weight[c] * stiffness * fibre_weight[f];
              // The bars' lengths, kept in q until their tensions replace
              // them below.
              for (unsigned int j = j0; j < j1; ++j)
                {
                  const double ex = h + u[j + 1] - u[j];
                  q[j]            = std::sqrt(ex * ex + t2);
                }
              // e still holds the last step's strains here.
              if (failure)
                for (unsigned int j = j0; j < j1; ++j)
                  if (!gone[j] && q[j] * inverse_h - 1. > failure_strain)
                    {
                      // Broken for good. It releases what the integrator
                      // gave it: its energy at the last step plus the
                      // work its last tension did over the first half
                      // kick, 1/2 k h^2 eps_n (eps_n + (eps - eps_n)) =
                      // 1/2 k h^2 eps_n eps (not 1/2 k (eps h)^2 at the
                      // new strain, which overshoots the failure strain
                      // by up to its own size in one step where broken
                      // pieces recoil, and made energy).
                      const double strain = q[j] * inverse_h - 1.;
                      fibre_dissipated[f] +=
                        std::max(0.5 * k_w * h * h * e[j] * strain, 0.);
                      gone[j]                 = 1;
                      break_time[index(f, j)] = time;
                      n_breaking += 1.;
                    }
              for (unsigned int j = j0; j < j1; ++j)
                e[j] = gone[j] ? 0. : q[j] * inverse_h - 1.;
              // Four partial sums in a fixed order: the same on any rank.
              double s_sum[4] = {0., 0., 0., 0.};
              for (unsigned int j = j0; j < j1; ++j)
                {
                  const double ex = h + u[j + 1] - u[j];
                  const double l  = q[j];
                  const double s  = gone[j] ? 0. : k_w * (l - h) / l;
                  q[j]            = s * ex;
                  s_sum[(j - j0) % 4] += s;
                }
              const double s_cell =
                ((s_sum[0] + s_sum[1]) + (s_sum[2] + s_sum[3])) / bars_per_cell;
              fibre_layer_force[2 * c] += s_cell * dy;
              fibre_layer_force[2 * c + 1] += s_cell * dz;
              fibre_layer_force[2 * (c + 1)] -= s_cell * dy;
              fibre_layer_force[2 * (c + 1) + 1] -= s_cell * dz;
            }
          // Each node: the axial tension of the bar after it less that of
          // the bar before it.
          double *const fibre_force = &force[index(f, 0)];
          fibre_force[0]            = q[0];
          for (unsigned int j = 1; j + 1 < n_nodes; ++j)
            fibre_force[j] = q[j] - q[j - 1];
          fibre_force[n_nodes - 1] = -q[n_nodes - 2];
          // The FE part's axial forces to the fibre, P^T f_x, layer by
          // layer; summed in a register, in the order of the vertices (the
          // compiler cannot: force may alias the projection).
          for (unsigned int k = 0; k < n_layers; ++k)
            {
              const double *const fx_k =
                &node_state[node_stride * std::size_t(k) * n_vertices + 2];
              double sum = fibre_force[k * bars_per_cell];
              for (unsigned int v = 0; v < n_vertices; ++v)
                if (fx_k[node_stride * v] != 0.)
                  sum += projection[std::size_t(v) * n_fibres + f] *
                         fx_k[node_stride * v];
              fibre_force[k * bars_per_cell] = sum;
            }
          // The projectile on the fibre's bar nodes.
          double contact_record[2] = {0., 0.};
          if (contact_radius > 0.)
            projectile_contact(f, projectile, dt, contact_record);
          record[n_record - 3] = contact_record[0];
          record[n_record - 2] = contact_record[1];
          // What the other ranks need: the overlaps' ties take every
          // fibre's nodes there.
          const unsigned int n_tied = n_overlap_nodes + n_clamp_nodes;
          for (unsigned int t = 0; t < n_tied; ++t)
            {
              record[2 * n_layers + t] = force[index(f, tied_node(t))];
              record[2 * n_layers + n_tied + t] =
                velocity[index(f, tied_node(t))];
            }
          record[n_record - 1] = n_breaking;
        }
      gather_fibres(fibre_record, n_record);

      // The bars' transverse forces on the FE nodes, summed in fibre order.
      std::fill(node_force.begin(), node_force.end(), 0.);
      double n_breaking = 0., reaction = 0., stored = 0.;
      for (unsigned int f = 0; f < n_fibres; ++f)
        {
          const double *const record = &fibre_record[std::size_t(f) * n_record];
          const auto &vertex         = fibre_vertices[f];
          const auto &value          = fibre_values[f];
          for (unsigned int k = 0; k < n_layers; ++k)
            for (unsigned int v = 0; v < 4; ++v)
              for (unsigned int d = 0; d < 2; ++d)
                node_force[2 * (k * n_vertices + vertex[v]) + d] +=
                  value[v] * record[2 * k + d];
          if (f < fibre_begin || f >= fibre_end)
            {
              const unsigned int n_tied = n_overlap_nodes + n_clamp_nodes;
              for (unsigned int t = 0; t < n_tied; ++t)
                {
                  force[index(f, tied_node(t))] = record[2 * n_layers + t];
                  velocity[index(f, tied_node(t))] =
                    record[2 * n_layers + n_tied + t];
                }
            }
          n_breaking += record[n_record - 1];
          reaction += record[n_record - 3];
          stored += record[n_record - 2];
        }
      contact_stored = stored;
      for (const auto &[c, dofs] : owned_nodes)
        for (unsigned int d = 0; d < 2; ++d)
          fe.force[dofs[1 + d]] += node_force[2 * c + d];
      // Every rank knows every broken bar.
      if (n_breaking > 0.)
        gather_fibres(broken, n_nodes);
      return reaction;
    }


    void
    FibreBars::set_projectile_contact(
      const Contact::LawType law,
      const Contact::ContactConstants &constants,
      const double radius)
    {
      contact_law       = law;
      contact_constants = constants;
      contact_radius    = radius;
    }


    void
    FibreBars::projectile_contact(const unsigned int f,
                                  const Projectile &projectile,
                                  const double dt,
                                  double *out)
    {
      const double yc       = projectile.axis_position();
      const double vp       = projectile.velocity();
      const double Rr       = projectile.radius() + contact_radius;
      const double *const u = &displacement[index(f, 0)];
      Contact::with_contact_law(contact_law, [&](auto tag) {
        using Law = typename decltype(tag)::type;
        static_assert(Law::history_size <= 3,
                      "a bar node keeps 3 doubles of projectile history");
        const Law law(contact_constants);
        // The last node is left out: clamped, it is not kicked; tied to a
        // DEM part at the clamp, the projectile must not reach it.
        for (unsigned int j = 0; j + 1 < n_nodes; ++j)
          {
            const std::size_t i = index(f, j);
            const double x      = node_x(j) + u[j];
            // Most nodes are farther along x than the reach: one test.
            if (std::abs(x) >= Rr)
              {
                touching[i] = 0;
                continue;
              }
            double xi;
            const unsigned int c = cell_of(j, xi);
            double delta, n[3];
            if (!Contact::projectile_overlap(
                  x,
                  fibre_y[f] + (1. - xi) * layer_displacement[2 * c] +
                    xi * layer_displacement[2 * (c + 1)],
                  yc,
                  Rr,
                  delta,
                  n))
              {
                touching[i] = 0;
                continue;
              }
            double *const history = &contact_history[3 * i];
            // A new contact starts without tangential history.
            if (!touching[i])
              for (unsigned int k = 0; k < 3; ++k)
                history[k] = 0.;
            touching[i] = 1;
            double v[3] = {velocity[i], 0., 0.};
            for (unsigned int d = 0; d < 2; ++d)
              v[1 + d] = (1. - xi) * at_fibre(f, c, 3 + d) +
                         xi * at_fibre(f, c + 1, 3 + d);
            double vr[3], fc[3], dissipated = 0.;
            Contact::relative_to_projectile(v, vp, vr);
            Contact::contact_force(law,
                                   delta,
                                   n,
                                   vr,
                                   dt,
                                   history,
                                   fc,
                                   dissipated);
            // Weighted as the node's mass: its fibre's weight and the mean
            // of its bars' continuum weights (an end node: half its bar's).
            double xj;
            const double w = fibre_weight[f] * 0.5 *
                             (cell_weight[cell_of(j, xj)] +
                              (j > 0 ? cell_weight[cell_of(j - 1, xj)] : 0.));
            force[i] += w * fc[0];
            // The transverse part to the two layers, as the node's
            // position is interpolated from them.
            double *const layer_force =
              &fibre_record[std::size_t(f) * record_size()];
            for (unsigned int d = 0; d < 2; ++d)
              {
                layer_force[2 * c + d] += (1. - xi) * w * fc[1 + d];
                layer_force[2 * (c + 1) + d] += xi * w * fc[1 + d];
              }
            out[0] -= w * fc[1];
            out[1] += w * law.energy(delta, history);
            fibre_contact_dissipated[f] += w * dissipated;
          }
      });
    }


    double
    FibreBars::stable_time_step() const
    {
      return stable_step;
    }
  } // namespace Coupling
} // namespace YarnImpact
