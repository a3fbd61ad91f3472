// The far field of the hybrid yarn as fibres (doc/hybrid.md section 3.4):
// each fibre a chain of bars between the FE part's node layers, axial
// unknowns of its own, the continuum's transverse motion.

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


    namespace
    {
      /** Sum of per-fibre values in fibre order, the same on any number of
       * ranks. */
      double
      sum_in_fibre_order(const std::vector<double> &values)
      {
        double sum = 0.;
        for (const double v : values)
          sum += v;
        return sum;
      }
    } // namespace


    void
    FibreBars::set_up(ImpactModel &fe_model,
                      const Triangulation<2> &section,
                      const HybridLayout &layout,
                      const YarnImpact::Parameters::Yarn &yarn,
                      const std::vector<double> &fibre_y_,
                      const std::vector<double> &fibre_z_,
                      const bool failure_,
                      const MPI_Comm communicator_)
    {
      communicator   = communicator_;
      fibre_y        = fibre_y_;
      fibre_z        = fibre_z_;
      n_fibres       = fibre_y.size();
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

      n_overlap_nodes = layout.overlap_cells * bars_per_cell + 1;
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
      mass.assign(n_all, 0.);
      for (unsigned int f = 0; f < n_fibres; ++f)
        for (unsigned int j = 0; j + 1 < n_nodes; ++j)
          {
            double xi;
            const double m =
              0.5 * cell_weight[cell_of(j, xi)] * linear_density * h;
            mass[index(f, j)] += m;
            mass[index(f, j + 1)] += m;
          }

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
      node_state.assign(3 * n_layers * n_vertices, 0.);
      set_up_projection();
      node_force.assign(2 * n_layers * n_vertices, 0.);
      layer_displacement.assign(2 * n_layers, 0.);
      layer_force.assign(2 * n_layers, 0.);
      fibre_record.assign(std::size_t(n_fibres) * record_size(), 0.);
      layer_axial.assign(std::size_t(n_fibres) * n_layers, 0.);
      fibre_elastic.assign(n_fibres, 0.);
      fibre_dissipated.assign(n_fibres, 0.);
      fibre_largest.assign(n_fibres, 0.);

      // Gershgorin: omega^2 <= 2 sum of the adjacent bars' stiffness over
      // the node's mass.
      double rate2 = 0.;
      for (unsigned int f = 0; f < n_fibres; ++f)
        for (unsigned int j = 0; j + 1 < n_nodes; ++j)
          {
            double xi;
            double k_sum = cell_weight[cell_of(j, xi)];
            if (j > 0)
              k_sum += cell_weight[cell_of(j - 1, xi)];
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


    void
    FibreBars::set_up_projection()
    {
      // G = Psi^T Psi (n_v x n_v) and Psi^T, then P = G^-1 Psi^T by
      // Cholesky, column by column.
      const unsigned int n = n_vertices;
      std::vector<double> G(std::size_t(n) * n, 0.);
      projection.assign(std::size_t(n) * n_fibres, 0.);
      for (unsigned int f = 0; f < n_fibres; ++f)
        for (unsigned int a = 0; a < 4; ++a)
          {
            const unsigned int va = fibre_vertices[f][a];
            projection[std::size_t(va) * n_fibres + f] += fibre_values[f][a];
            for (unsigned int b = 0; b < 4; ++b)
              G[std::size_t(va) * n + fibre_vertices[f][b]] +=
                fibre_values[f][a] * fibre_values[f][b];
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
        // The last node is held at the clamp.
        for (unsigned int j = 0; j + 1 < n_nodes; ++j)
          {
            const std::size_t i = index(f, j);
            velocity[i] += dt * force[i] / mass[i];
          }
    }


    void
    FibreBars::drift(const double dt)
    {
      for (std::size_t i = index(fibre_begin, 0); i < index(fibre_end, 0); ++i)
        displacement[i] += dt * velocity[i];
    }


    void
    FibreBars::compute_forces(ImpactModel &fe_model,
                              const MPI_Comm communicator)
    {
      const FE::CouplingView fe = FE::coupling_view(fe_model);
      // Gather: each entry has one owner and the others add zeros, so the
      // sums are exact and the same on every rank. The FE part's axial
      // forces go to the fibres (P^T f_x, below).
      std::fill(node_state.begin(), node_state.end(), 0.);
      for (const auto &[c, dofs] : owned_nodes)
        {
          for (unsigned int d = 0; d < 2; ++d)
            node_state[3 * c + d] = fe.displacement[dofs[1 + d]];
          node_state[3 * c + 2] = fe.force[dofs[0]];
          fe.force[dofs[0]]     = 0.;
        }
      Utilities::MPI::sum(node_state, communicator, node_state);

      const unsigned int n_record = record_size();
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        std::fill(force.begin() + index(f, 0),
                  force.begin() + index(f + 1, 0),
                  0.);
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        {
          const auto &vertex = fibre_vertices[f];
          const auto &value  = fibre_values[f];
          // The fibre's transverse displacement at each layer.
          for (unsigned int k = 0; k < n_layers; ++k)
            for (unsigned int d = 0; d < 2; ++d)
              {
                double s = 0.;
                for (unsigned int v = 0; v < 4; ++v)
                  s +=
                    value[v] * node_state[3 * (k * n_vertices + vertex[v]) + d];
                layer_displacement[2 * k + d] = s;
              }
          double *const record = &fibre_record[std::size_t(f) * n_record];
          double *const fibre_layer_force = record;
          std::fill(fibre_layer_force, fibre_layer_force + 2 * n_layers, 0.);
          double elastic = 0., largest = 0., n_breaking = 0.;
          // Bar node j's transverse displacement, linear between layers.
          auto transverse = [&](const unsigned int j,
                                const unsigned int d,
                                unsigned int &c,
                                double &xi) {
            c = cell_of(j, xi);
            return (1. - xi) * layer_displacement[2 * c + d] +
                   xi * layer_displacement[2 * (c + 1) + d];
          };
          unsigned int c0, c1;
          double xi0, xi1;
          double y0 = transverse(0, 0, c0, xi0), z0 = transverse(0, 1, c0, xi0);
          for (unsigned int j = 0; j + 1 < n_nodes; ++j)
            {
              const double y1     = transverse(j + 1, 0, c1, xi1),
                           z1     = transverse(j + 1, 1, c1, xi1);
              const std::size_t i = index(f, j);
              const double e[3]   = {h + displacement[i + 1] - displacement[i],
                                     y1 - y0,
                                     z1 - z0};
              const unsigned int ca = c0;
              const double xa       = xi0;
              y0                    = y1;
              z0                    = z1;
              c0                    = c1;
              xi0                   = xi1;
              strain[i]             = 0.;
              if (broken[i])
                continue;
              const double l =
                std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
              const double eps = l / h - 1.;
              // The bar lies in the cell of its first node.
              const double k_w = cell_weight[ca] * stiffness;
              if (failure && eps > failure_strain)
                {
                  broken[i] = 1;
                  n_breaking += 1.;
                  fibre_dissipated[f] += 0.5 * k_w * (l - h) * (l - h);
                  continue;
                }
              strain[i] = eps;
              largest   = std::max(largest, eps);
              elastic += 0.5 * k_w * (l - h) * (l - h);
              // The force on the bar's first node (the second gets its
              // opposite), as a DEM truss; the transverse parts go to the
              // layers by the nodes' linear shape values.
              const double s = k_w * (l - h) / l;
              force[i] += s * e[0];
              force[i + 1] -= s * e[0];
              for (unsigned int d = 0; d < 2; ++d)
                {
                  const double t = s * e[1 + d];
                  fibre_layer_force[2 * ca + d] += (1. - xa) * t;
                  fibre_layer_force[2 * (ca + 1) + d] += xa * t;
                  fibre_layer_force[2 * c1 + d] -= (1. - xi1) * t;
                  fibre_layer_force[2 * (c1 + 1) + d] -= xi1 * t;
                }
            }
          fibre_elastic[f] = elastic;
          fibre_largest[f] = largest;
          // The FE part's axial forces to the fibre, P^T f_x, layer by
          // layer.
          for (unsigned int k = 0; k < n_layers; ++k)
            for (unsigned int v = 0; v < n_vertices; ++v)
              {
                const double fx = node_state[3 * (k * n_vertices + v) + 2];
                if (fx != 0.)
                  force[index(f, k * bars_per_cell)] +=
                    projection[std::size_t(v) * n_fibres + f] * fx;
              }
          // What the other ranks need: the overlap's ties take every
          // fibre's nodes there.
          for (unsigned int j = 0; j < n_overlap_nodes; ++j)
            {
              record[2 * n_layers + j] = force[index(f, j)];
              record[2 * n_layers + n_overlap_nodes + j] =
                velocity[index(f, j)];
            }
          record[n_record - 1] = n_breaking;
        }
      gather_fibres(fibre_record, n_record);

      // The bars' transverse forces on the FE nodes, summed in fibre order.
      std::fill(node_force.begin(), node_force.end(), 0.);
      double n_breaking = 0.;
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
            for (unsigned int j = 0; j < n_overlap_nodes; ++j)
              {
                force[index(f, j)] = record[2 * n_layers + j];
                velocity[index(f, j)] =
                  record[2 * n_layers + n_overlap_nodes + j];
              }
          n_breaking += record[n_record - 1];
        }
      for (const auto &[c, dofs] : owned_nodes)
        for (unsigned int d = 0; d < 2; ++d)
          fe.force[dofs[1 + d]] += node_force[2 * c + d];
      // Every rank knows every broken bar.
      if (n_breaking > 0.)
        gather_fibres(broken, n_nodes);
    }


    double
    FibreBars::stable_time_step() const
    {
      return stable_step;
    }


    double
    FibreBars::kinetic_energy() const
    {
      std::vector<double> fibre_energy(n_fibres, 0.);
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        for (std::size_t i = index(f, 0); i < index(f + 1, 0); ++i)
          fibre_energy[f] += 0.5 * mass[i] * velocity[i] * velocity[i];
      gather_fibres(fibre_energy, 1);
      return sum_in_fibre_order(fibre_energy);
    }


    double
    FibreBars::elastic_energy() const
    {
      std::vector<double> e = fibre_elastic;
      gather_fibres(e, 1);
      return sum_in_fibre_order(e);
    }


    double
    FibreBars::dissipated_energy() const
    {
      std::vector<double> e = fibre_dissipated;
      gather_fibres(e, 1);
      return sum_in_fibre_order(e);
    }


    double
    FibreBars::largest_strain() const
    {
      double largest = 0.;
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        largest = std::max(largest, fibre_largest[f]);
      return Utilities::MPI::max(largest, communicator);
    }


    unsigned long
    FibreBars::n_broken() const
    {
      return std::count(broken.begin(), broken.end(), 1);
    }


    std::vector<unsigned long>
    FibreBars::broken_per_millimetre() const
    {
      std::vector<unsigned long> count;
      for (unsigned int f = 0; f < n_fibres; ++f)
        for (unsigned int j = 0; j + 1 < n_nodes; ++j)
          if (broken[index(f, j)])
            {
              const unsigned int mm = (node_x(j) + 0.5 * h) * 1e3;
              if (count.size() <= mm)
                count.resize(mm + 1, 0);
              ++count[mm];
            }
      return count;
    }


    bool
    FibreBars::fibre_broken(const unsigned int f) const
    {
      const auto b = broken.begin() + index(f, 0);
      return std::find(b, b + n_nodes, 1) != b + n_nodes;
    }


    std::vector<double>
    FibreBars::mean_strains() const
    {
      // Each fibre's strains of the bars j - 1 and j at each layer's node
      // j, where they exist and are intact (NaN elsewhere).
      std::vector<double> layer_strain(
        std::size_t(n_fibres) * 2 * n_layers,
        std::numeric_limits<double>::quiet_NaN());
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        for (unsigned int k = 0; k < n_layers; ++k)
          {
            const unsigned int j = k * bars_per_cell;
            for (unsigned int b = (j > 0 ? j - 1 : 0), q = (j > 0 ? 0 : 1);
                 b <= j && b + 1 < n_nodes;
                 ++b, ++q)
              if (!broken[index(f, b)])
                layer_strain[(std::size_t(f) * n_layers + k) * 2 + q] =
                  strain[index(f, b)];
          }
      gather_fibres(layer_strain, 2 * n_layers);
      std::vector<double> mean(n_layers, 0.);
      for (unsigned int k = 0; k < n_layers; ++k)
        {
          double sum = 0., count = 0.;
          for (unsigned int f = 0; f < n_fibres; ++f)
            for (unsigned int q = 0; q < 2; ++q)
              {
                const double e =
                  layer_strain[(std::size_t(f) * n_layers + k) * 2 + q];
                if (!std::isnan(e))
                  {
                    sum += e;
                    count += 1.;
                  }
              }
          mean[k] = count > 0. ? sum / count : 0.;
        }
      return mean;
    }


    void
    FibreBars::save_state(Checkpoint::Writer &out) const
    {
      // Every fibre's state, as one rank would hold it, so that a run may
      // go on with another number of ranks.
      auto gathered = [this](std::vector<double> values,
                             const unsigned int per_fibre) {
        gather_fibres(values, per_fibre);
        return values;
      };
      out.tag("fibre bars");
      out.put(gathered(displacement, n_nodes));
      out.put(gathered(velocity, n_nodes));
      out.put(gathered(force, n_nodes));
      out.put(gathered(strain, n_nodes));
      out.put(broken);
      out.put(gathered(fibre_elastic, 1));
      out.put(gathered(fibre_dissipated, 1));
      out.put(gathered(fibre_largest, 1));
    }


    void
    FibreBars::load_state(Checkpoint::Reader &in)
    {
      in.tag("fibre bars");
      in.get_same_size(displacement, "fibre bars' displacements");
      in.get_same_size(velocity, "fibre bars' velocities");
      in.get_same_size(force, "fibre bars' forces");
      in.get_same_size(strain, "fibre bars' strains");
      in.get_same_size(broken, "fibre bars' failure states");
      in.get_same_size(fibre_elastic, "fibre bars' strain energies");
      in.get_same_size(fibre_dissipated, "fibre bars' released energies");
      in.get_same_size(fibre_largest, "fibre bars' largest strains");
    }


    std::size_t
    FibreBars::memory_consumption() const
    {
      return displacement.size() * (5 * sizeof(double) + 1) +
             (node_state.size() + node_force.size()) * sizeof(double) +
             (fibre_record.size() + layer_axial.size()) * sizeof(double) +
             n_fibres * (4 * sizeof(unsigned int) + 9 * sizeof(double)) +
             projection.size() * sizeof(double);
    }
  } // namespace Coupling
} // namespace YarnImpact
