// The patch test of the hybrid yarn (doc/hybrid.md section 4.2): the
// coupled system at rest under a uniform axial stretch must feel no force.

#include "hybrid_model_implementation.h"

namespace YarnImpact
{
  namespace Coupling
  {
    using namespace dealii;


    namespace internal
    {
      double
      HybridModel::patch_test(const double strain)
      {
        double largest                       = 0.;
        std::vector<ImpactModel *> dem_parts = {dem_model.get()};
        if (clamp_model)
          dem_parts.push_back(clamp_model.get());
        // The FE parts with their bars (a whole yarn's side x < 0 is the
        // mirror image of x > 0: the same stretch in its frame).
        std::vector<std::pair<ImpactModel *, FibreBars *>> sides = {
          {fe_model.get(), &bars}};
        if (left_fe_model)
          sides.emplace_back(left_fe_model.get(), &left_bars);
        {
          for (const auto &side : sides)
            {
              const FE::CouplingView fe = FE::coupling_view(*side.first);
              for (const auto &node : *fe.nodes)
                for (unsigned int d = 0; d < 3; ++d)
                  {
                    fe.displacement[node[d]] =
                      d == 0 && !layout.fibre_bars
                        ? strain * (*fe.reference_coordinate)[node[0]]
                        : 0.;
                    fe.velocity[node[d]] = 0.;
                  }
            }
          for (ImpactModel *part : dem_parts)
            {
              const DEM::CouplingView dem = DEM::coupling_view(*part);
              for (unsigned int s = dem.station_begin; s < dem.station_end; ++s)
                for (unsigned int f = 0; f < dem.n_fibres; ++f)
                  {
                    const std::size_t i = dem.local_index(s, f);
                    dem.position[3 * i] = (1. + strain) * (*dem.station_x)[s];
                    dem.velocity[3 * i] = 0.;
                    dem.velocity[3 * i + 1] = dem.velocity[3 * i + 2] = 0.;
                  }
            }
        }
        Projectile far(shared.projectile, shared.yarn.thickness_semi_axis);
        far.place_on(1.);
        // Under fibre bars the bars take the stretch, the continuum's axial
        // motion is held.
        for (const auto &[fe_part, b] : sides)
          {
            if (layout.fibre_bars)
              for (unsigned int f = 0; f < b->n_fibres; ++f)
                for (unsigned int j = 0; j < b->n_nodes; ++j)
                  {
                    const std::size_t i = b->index(f, j);
                    b->displacement[i]  = strain * b->node_x(j);
                    b->velocity[i]      = 0.;
                  }
            // The models' own forces, then the generalised ones of the
            // coupled system (couple() replaces the overlaps').
            if (layout.fibre_bars)
              b->set_continuum_axial(*fe_part);
            fe_part->compute_forces(far, 0.);
            if (layout.fibre_bars)
              {
                b->compute_forces(*fe_part, far, 0., communicator);
                // The own fibres' bar nodes outside the overlap but the
                // clamped one.
                for (unsigned int f = b->fibre_begin; f < b->fibre_end; ++f)
                  for (unsigned int j =
                         layout.overlap_cells * b->bars_per_cell + 1;
                       j + 1 < b->n_nodes;
                       ++j)
                    largest =
                      std::max(largest, std::abs(b->force[b->index(f, j)]));
              }
          }
        for (ImpactModel *part : dem_parts)
          part->compute_forces(far, 0.);
        for (const auto &side : sides)
          {
            const FE::CouplingView fe = FE::coupling_view(*side.first);
            std::vector<bool> coupled(fe.reference_coordinate->size(), false);
            for (const Overlap *o : overlaps())
              if ((o == &left) == (side.first == left_fe_model.get()))
                for (const auto &[c, dofs] : o->owned_nodes)
                  for (unsigned int d = 0; d < 3; ++d)
                    coupled[dofs[d]] = true;
            for (const auto &node : *fe.nodes)
              for (unsigned int d = 0; d < 3; ++d)
                if (!coupled[node[d]] && fe.inverse_mass[node[d]] != 0.)
                  largest = std::max(largest, std::abs(fe.force[node[d]]));
          }
        // The free spheres outside the overlaps: the DEM part's by the nose
        // (x normal to the plane x = 0 is held there; a whole yarn's
        // DEM-only zone lies between its two overlaps), the one's at the
        // clamp but the clamped station.
        {
          const DEM::CouplingView dem = DEM::coupling_view(*dem_model);
          const bool plane            = !left_fe_model;
          for (unsigned int s =
                 std::max(dem.station_begin, plane ? 0u : left.station_end);
               s < std::min(dem.station_end, nose.station_begin);
               ++s)
            for (unsigned int f = 0; f < dem.n_fibres; ++f)
              for (unsigned int d = (plane && s == 0 ? 1 : 0); d < 3; ++d)
                largest =
                  std::max(largest,
                           std::abs(dem.force[3 * dem.local_index(s, f) + d]));
        }
        if (clamp_model)
          {
            const DEM::CouplingView dem = DEM::coupling_view(*clamp_model);
            for (unsigned int s =
                   std::max(dem.station_begin, clamp.station_end);
                 s < std::min(dem.station_end, dem.n_stations - 1);
                 ++s)
              for (unsigned int f = 0; f < dem.n_fibres; ++f)
                for (unsigned int d = 0; d < 3; ++d)
                  largest =
                    std::max(largest,
                             std::abs(
                               dem.force[3 * dem.local_index(s, f) + d]));
          }
        nose.couple(*fe_model, 0., communicator);
        if (left_fe_model)
          left.couple(*left_fe_model, 0., communicator);
        if (clamp_model)
          clamp.couple(*fe_model, 0., communicator);
        for (const Overlap *o : overlaps())
          largest = std::max(largest, o->largest_generalised_force());
        largest              = Utilities::MPI::max(largest, communicator);
        const double tension = shared.yarn.fibre_modulus * M_PI * 0.25 *
                               shared.yarn.fibre_diameter *
                               shared.yarn.fibre_diameter * strain;
        return largest / tension;
      }

    } // namespace internal


    double
    patch_test(const YarnImpact::Parameters::Shared &shared,
               const FE::Parameters &fe,
               const DEM::Parameters &dem,
               const HybridParameters &hybrid,
               const double strain,
               const MPI_Comm communicator)
    {
      validate(shared, fe, dem, hybrid);
      internal::HybridModel model(shared, fe, dem, hybrid, communicator);
      std::ostringstream quiet;
      Projectile far(shared.projectile, shared.yarn.thickness_semi_axis);
      far.place_on(1.);
      model.setup(far, quiet);
      return model.patch_test(strain);
    }


  } // namespace Coupling
} // namespace YarnImpact
