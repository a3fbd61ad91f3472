// One overlap of the hybrid yarn (doc/hybrid.md sections 2.2 and 3.1):
// where its FE nodes and DEM spheres are, its constraint, and the step's
// coupling.

#include <yarn_impact/coupling/hybrid_parts.h>
#include <yarn_impact/coupling/overlap.h>
#include <yarn_impact/dem/dem_model.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>

namespace YarnImpact
{
  namespace Coupling
  {
    using namespace dealii;


    void
    Overlap::set_up(ImpactModel &fe_model,
                    const Triangulation<2> &section,
                    const HybridLayout &layout,
                    const YarnImpact::Parameters::Yarn &yarn,
                    const MPI_Comm communicator)
    {
      const unsigned int n_vertices = section.n_vertices();
      const unsigned int n_layers   = layout.overlap_cells + 1;
      const unsigned int n_coupled  = n_layers * n_vertices;
      const double h                = layout.cell_length;
      const double semi_axis =
        std::min(yarn.thickness_semi_axis, yarn.width_semi_axis);

      // The owned FE nodes of the overlap's layers, by (layer, vertex).
      const FE::CouplingView fe = FE::coupling_view(fe_model);
      owned_nodes               = layer_nodes(fe_model,
                                section,
                                x_begin,
                                h,
                                n_layers,
                                semi_axis,
                                communicator);
      std::vector<double> node_mass(n_coupled, 0.);
      for (const auto &[c, node] : owned_nodes)
        node_mass[c] = fe.mass[node[0]];
      Utilities::MPI::sum(node_mass, communicator, node_mass);
      constraint = BridgingConstraint(n_coupled);
      for (unsigned int c = 0; c < n_coupled; ++c)
        constraint.set_node_mass(c, node_mass[c]);
      if (z_symmetry)
        for (unsigned int v = 0; v < n_vertices; ++v)
          if (std::abs(section.get_vertices()[v][1]) < 1e-9 * semi_axis)
            for (unsigned int layer = 0; layer < n_layers; ++layer)
              constraint.fix_component(layer * n_vertices + v, 2);

      // The overlap's spheres: fibre f of station s is particle
      // (s - station_begin) n_f + f, tied to the trilinear field at its
      // reference position (the FE cells are extruded: linear in x times
      // bilinear in the section).
      const DEM::CouplingView dem = DEM::coupling_view(*dem_part);
      n_fibres                    = dem.n_fibres;
      std::vector<std::array<unsigned int, 4>> fibre_vertices(n_fibres);
      std::vector<std::array<double, 4>> fibre_values(n_fibres);
      for (unsigned int f = 0; f < n_fibres; ++f)
        {
          unsigned int cell;
          locate_in_section(section,
                            Point<2>((*dem.fibre_y)[f], (*dem.fibre_z)[f]),
                            cell,
                            fibre_vertices[f],
                            fibre_values[f]);
        }
      // The coarse transverse tie (section 2.5) on the same shape values:
      // rows per node layer and section mode.
      if (transverse_modes > 0)
        {
          section_tie = SectionTie(n_coupled, n_layers, transverse_modes);
          for (unsigned int c = 0; c < n_coupled; ++c)
            section_tie.set_node_mass(c, node_mass[c]);
          if (z_symmetry)
            for (unsigned int v = 0; v < n_vertices; ++v)
              if (std::abs(section.get_vertices()[v][1]) < 1e-9 * semi_axis)
                for (unsigned int layer = 0; layer < n_layers; ++layer)
                  section_tie.fix_component(layer * n_vertices + v, 2);
        }
      for (unsigned int q = 0; q < station_end - station_begin; ++q)
        {
          const unsigned int s = station_of(q);
          const double x       = x_sign() * (*dem.station_x)[s];
          const double t       = (x - x_begin) / h;
          const unsigned int cell =
            std::min<unsigned int>(layout.overlap_cells - 1,
                                   t <= 0. ? 0u : unsigned(std::floor(t)));
          const double xi = std::clamp(t - cell, 0., 1.);
          for (unsigned int f = 0; f < n_fibres; ++f)
            {
              std::vector<unsigned int> nodes;
              std::vector<double> values;
              for (unsigned int side = 0; side < 2; ++side)
                for (unsigned int v = 0; v < 4; ++v)
                  {
                    const double value =
                      (side == 0 ? 1. - xi : xi) * fibre_values[f][v];
                    if (value != 0.)
                      {
                        nodes.push_back((cell + side) * n_vertices +
                                        fibre_vertices[f][v]);
                        values.push_back(value);
                      }
                  }
              constraint.add_particle(1. / dem.inverse_mass(s, f),
                                      nodes,
                                      values);
              // The affine modes in the reference section coordinates,
              // scaled by the smaller semi-axis (for the system's scale
              // only).
              if (transverse_modes > 0)
                section_tie.add_particle(1. / dem.inverse_mass(s, f),
                                         cell,
                                         xi,
                                         {{1.,
                                           (*dem.fibre_y)[f] / semi_axis,
                                           (*dem.fibre_z)[f] / semi_axis}},
                                         nodes,
                                         values);
            }
        }
      constraint.factorize();
      if (transverse_modes > 0)
        section_tie.factorize();
      if (bars != nullptr)
        set_up_axial_ties(layout, dem);
      const unsigned int n_p = constraint.n_particles();
      node_force.assign(3 * n_coupled, 0.);
      node_acceleration.assign(3 * n_coupled, 0.);
      node_velocity.assign(3 * n_coupled, 0.);
      node_multipliers.assign(3 * n_coupled, 0.);
      previous_node_multipliers.assign(3 * n_coupled, 0.);
      zero_node_force.assign(3 * n_coupled, 0.);
      particle_force.assign(3 * n_p, 0.);
      particle_acceleration.assign(3 * n_p, 0.);
      multipliers.assign(3 * n_p, 0.);
      // The initial forces, as every step leaves them.
      couple(fe_model, 0., communicator);
    }


    void
    Overlap::couple(ImpactModel &fe_model,
                    const double dt,
                    const MPI_Comm communicator)
    {
      const FE::CouplingView fe   = FE::coupling_view(fe_model);
      const DEM::CouplingView dem = DEM::coupling_view(*dem_part);
      std::fill(node_force.begin(), node_force.end(), 0.);
      std::fill(particle_force.begin(), particle_force.end(), 0.);
      // Gather: each entry has one owner and the others add zeros, so the
      // sums are exact and the same on every rank and partition.
      std::fill(node_velocity.begin(), node_velocity.end(), 0.);
      for (const auto &[c, dofs] : owned_nodes)
        for (unsigned int d = 0; d < 3; ++d)
          {
            node_force[3 * c + d]    = fe.force[dofs[d]];
            node_velocity[3 * c + d] = fe.velocity[dofs[d]];
          }
      const unsigned int s_begin = std::max(station_begin, dem.station_begin);
      const unsigned int s_end   = std::min(station_end, dem.station_end);
      // The x components' factor (1, or -1 into a mirrored FE part's
      // frame: exact either way).
      const double sign[3] = {x_sign(), 1., 1.};
      for (unsigned int s = s_begin; s < s_end; ++s)
        for (unsigned int f = 0; f < n_fibres; ++f)
          {
            const std::size_t i = dem.local_index(s, f);
            const std::size_t p =
              std::size_t(coupled_station(s)) * n_fibres + f;
            for (unsigned int d = 0; d < 3; ++d)
              particle_force[3 * p + d] = sign[d] * dem.force[3 * i + d];
          }
      Utilities::MPI::sum(node_force, communicator, node_force);
      Utilities::MPI::sum(node_velocity, communicator, node_velocity);
      Utilities::MPI::sum(particle_force, communicator, particle_force);

      if (transverse_modes > 0)
        section_tie.accelerations(node_force.data(),
                                  particle_force.data(),
                                  node_acceleration.data(),
                                  particle_acceleration.data(),
                                  multipliers.data(),
                                  node_multipliers.data());
      else
        constraint.accelerations(node_force.data(),
                                 particle_force.data(),
                                 node_acceleration.data(),
                                 particle_acceleration.data(),
                                 multipliers.data());
      if (bars != nullptr)
        work += dt * tie_axially();
      // The multipliers' power on the spheres, sum_i lambda_i . v_i: the
      // constraints hold, so it is (N^T lambda) . v on the overlap's
      // nodes (G_f^T mu under the section tie), the same sum in the same
      // order on every rank.
      if (transverse_modes == 0)
        constraint.generalised_force(zero_node_force.data(),
                                     multipliers.data(),
                                     node_multipliers.data());
      // Over the step, velocity Verlet applies the multipliers of its two
      // ends half each at the mid-step velocity: their mean's power is
      // the work each part's kinetic energy receives (the last step's
      // alone would miss half the change, a bias of order
      // lambda^2 dt^2 / m that the light debris of broken fibres makes
      // large).
      double power = 0.;
      for (unsigned int k = 0; k < node_velocity.size(); ++k)
        power += 0.5 * (node_multipliers[k] + previous_node_multipliers[k]) *
                 node_velocity[k];
      work += dt * power;
      previous_node_multipliers = node_multipliers;

      // Scatter: the force that gives each its coupled acceleration
      // through its own kick.
      for (const auto &[c, dofs] : owned_nodes)
        for (unsigned int d = 0; d < 3; ++d)
          fe.force[dofs[d]] = node_acceleration[3 * c + d] * fe.mass[dofs[d]];
      // The continuum's axial motion is held under fibre bars.
      if (bars != nullptr)
        for (const auto &[c, dofs] : owned_nodes)
          fe.force[dofs[0]] = 0.;
      for (unsigned int s = s_begin; s < s_end; ++s)
        for (unsigned int f = 0; f < n_fibres; ++f)
          {
            const std::size_t i = dem.local_index(s, f);
            const std::size_t p =
              std::size_t(coupled_station(s)) * n_fibres + f;
            const double m = 1. / dem.inverse_mass(s, f);
            for (unsigned int d = 0; d < 3; ++d)
              dem.force[3 * i + d] =
                sign[d] * (particle_acceleration[3 * p + d] * m);
          }
    }


    void
    Overlap::set_up_axial_ties(const HybridLayout &layout,
                               const DEM::CouplingView &dem)
    {
      // The overlap's bar nodes are the bars' first ones by the nose, their
      // last ones at the clamp; sphere (s, f) is tied to fibre f's bar
      // nodes at its reference x, linearly between the two around it (on
      // one node when the bars are the DEM's trusses).
      const unsigned int n_tied =
        layout.overlap_cells * bars->bars_per_cell + 1;
      const unsigned int n_stations = station_end - station_begin;
      const double h_b              = layout.cell_length / bars->bars_per_cell;
      bar_offset = std::lround((x_begin - bars->node_x(0)) / h_b);
      AssertThrow(bar_offset + n_tied <= bars->n_nodes, ExcInternalError());
      fibre_constraints.assign(n_fibres, ChainConstraint(n_tied));
      previous_bar_multipliers.assign(std::size_t(n_fibres) * n_tied, 0.);
      for (unsigned int f = 0; f < n_fibres; ++f)
        {
          ChainConstraint &tie = fibre_constraints[f];
          for (unsigned int j = 0; j < n_tied; ++j)
            tie.set_node_mass(j, bars->mass[bars->index(f, bar_offset + j)]);
          for (unsigned int q = 0; q < n_stations; ++q)
            {
              const unsigned int s = station_of(q);
              const double t = (x_sign() * (*dem.station_x)[s] - x_begin) / h_b;
              unsigned int j = std::lround(t);
              double xi      = 0.;
              if (std::abs(t - j) > 1e-9)
                {
                  j  = std::min<unsigned int>(n_tied - 2,
                                             t <= 0. ? 0u : unsigned(t));
                  xi = std::clamp(t - j, 0., 1.);
                }
              tie.add_particle(1. / dem.inverse_mass(s, f),
                               std::min(j, n_tied - 1),
                               xi);
            }
          tie.factorize();
        }
      bar_force.assign(n_tied, 0.);
      bar_acceleration.assign(n_tied, 0.);
      sphere_force.assign(n_stations, 0.);
      sphere_acceleration.assign(n_stations, 0.);
      sphere_multipliers.assign(n_stations, 0.);
      gathered_bar_force.assign(std::size_t(n_fibres) * n_tied, 0.);
    }


    double
    Overlap::largest_generalised_force() const
    {
      std::vector<double> generalised(node_force.size());
      constraint.generalised_force(node_force.data(),
                                   particle_force.data(),
                                   generalised.data());
      double largest = 0.;
      // Under fibre bars the continuum's x is held and the bars take it.
      for (unsigned int k = 0; k < generalised.size(); ++k)
        if (bars == nullptr || k % 3 != 0)
          largest = std::max(largest, std::abs(generalised[k]));
      if (bars == nullptr)
        return largest;
      const unsigned int n_tied     = bar_force.size();
      const unsigned int n_stations = station_end - station_begin;
      std::vector<double> spheres(n_stations), out(n_tied);
      for (unsigned int f = 0; f < n_fibres; ++f)
        {
          for (unsigned int q = 0; q < n_stations; ++q)
            spheres[q] = particle_force[3 * (std::size_t(q) * n_fibres + f)];
          fibre_constraints[f].generalised_force(
            &gathered_bar_force[std::size_t(f) * n_tied],
            spheres.data(),
            out.data());
          for (const double g : out)
            largest = std::max(largest, std::abs(g));
        }
      return largest;
    }


    double
    Overlap::tie_axially()
    {
      const unsigned int n_tied     = bar_force.size();
      const unsigned int n_stations = station_end - station_begin;
      double power                  = 0.;
      for (unsigned int f = 0; f < n_fibres; ++f)
        {
          for (unsigned int j = 0; j < n_tied; ++j)
            {
              bar_force[j] = bars->force[bars->index(f, bar_offset + j)];
              gathered_bar_force[std::size_t(f) * n_tied + j] = bar_force[j];
            }
          for (unsigned int q = 0; q < n_stations; ++q)
            sphere_force[q] =
              particle_force[3 * (std::size_t(q) * n_fibres + f)];
          const ChainConstraint &tie = fibre_constraints[f];
          tie.accelerations(bar_force.data(),
                            sphere_force.data(),
                            bar_acceleration.data(),
                            sphere_acceleration.data(),
                            sphere_multipliers.data());
          for (unsigned int j = 0; j < n_tied; ++j)
            {
              const std::size_t i = bars->index(f, bar_offset + j);
              bars->force[i]      = bar_acceleration[j] * bars->mass[i];
            }
          // The multipliers' power on the spheres, lambda . v: the
          // constraints hold, so the spheres' velocities are the bars'
          // interpolated (the step's two ends averaged, as in couple()).
          tie.generalised_force(zero_force(n_tied),
                                sphere_multipliers.data(),
                                bar_force.data());
          for (unsigned int q = 0; q < n_stations; ++q)
            particle_acceleration[3 * (std::size_t(q) * n_fibres + f)] =
              sphere_acceleration[q];
          double *previous = &previous_bar_multipliers[std::size_t(f) * n_tied];
          for (unsigned int j = 0; j < n_tied; ++j)
            {
              power += 0.5 * (bar_force[j] + previous[j]) *
                       bars->velocity[bars->index(f, bar_offset + j)];
              previous[j] = bar_force[j];
            }
        }
      return power;
    }
  } // namespace Coupling
} // namespace YarnImpact
