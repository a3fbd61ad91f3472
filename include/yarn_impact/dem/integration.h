#ifndef yarn_impact_dem_integration_h
#define yarn_impact_dem_integration_h

#include <yarn_impact/dem/decomposition.h>
#include <yarn_impact/dem/fibre_chains.h>
#include <yarn_impact/dem/neighbour_lists.h>
#include <yarn_impact/dem/spheres.h>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      /**
       * Velocity Verlet of the owned spheres, with the kick fused into the
       * drift: apply the pending kick (Spheres::pending_kick [s]) of the
       * forces, clear them, move the spheres over @p dt [s], record the
       * extents of each station and add the displacements to the rebuild
       * criteria of @p lists. Spheres on a symmetry plane keep a zero
       * velocity normal to it; clamped stations do not move.
       */
      void
      drift(const FibreChains &chains,
            const Decomposition &decomposition,
            NeighbourLists &lists,
            Spheres &spheres,
            const double dt);

      /**
       * Clear the ghost forces before a force evaluation, and the owned ones
       * unless a drift has done so (a force evaluation without a drift in
       * between starts afresh).
       */
      void
      clear_forces(const Decomposition &decomposition, Spheres &spheres);

      /** Set the extents of station @p s (Spheres::st_xlo etc.) from the
       * positions; the drift updates them afterwards. */
      void
      compute_station_extents(const FibreChains &chains,
                              const Decomposition &decomposition,
                              Spheres &spheres,
                              const unsigned int s);

      /** Velocity component @p c [m/s] of local sphere @p i with the
       * pending kick applied (velocity Verlet's synchronous velocity). */
      inline double
      kicked_velocity(const FibreChains &chains,
                      const Decomposition &decomposition,
                      const Spheres &spheres,
                      const std::size_t i,
                      const unsigned int c)
      {
        const unsigned int s = decomposition.station_of(i), f = i % chains.nf;
        const double mask =
          (c == 0 ? chains.xmask[s] : (c == 2 ? chains.zmask[f] : 1.));
        return spheres.vel[3 * i + c] +
               spheres.pending_kick * chains.station_inverse_mass_factor[s] *
                 chains.fibre_inverse_mass[f] * mask * spheres.force[3 * i + c];
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
