#ifndef yarn_impact_dem_spheres_h
#define yarn_impact_dem_spheres_h

#include <yarn_impact/core/checkpoint.h>

#include <cstdint>
#include <vector>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      /**
       * The state of the local spheres of the DEM impact model
       * (cross-section-major, in the local numbering of Decomposition), for
       * every step to read and write as plain contiguous arrays.
       */
      struct Spheres
      {
        /** Position [m], velocity [m/s] and the force on each sphere [N]
         * (the sum of truss, contact and projectile forces of the last
         * evaluation), 3 per sphere. The velocity lags the force by the
         * pending kick. */
        std::vector<double> pos, vel, force;
        /** Whether the truss to the same fibre's sphere at the next station
         * has failed. */
        std::vector<std::uint8_t> broken;
        /** Tangential history xi_t of each sphere's contact with the
         * projectile: the elastic tangential displacement of its
         * Cundall-Strack spring [m], 3 per sphere; and the force evaluation
         * at which that contact was last active. */
        std::vector<double> projectile_tangential_displacement;
        std::vector<std::uint64_t> proj_step;
        /** Energy dissipated so far [J] by the contacts and trusses that
         * sphere i heads (set for owned spheres only): a pair's by its lower
         * sphere (the row of its list), a truss's by its sphere at the lower
         * station, a projectile contact's by its sphere. Each rank adds to
         * its own spheres in the order of the forces, so every sphere's sum,
         * and their reproducible total, are the same on any number of
         * ranks. */
        std::vector<double> dissipated;
        /** Time at which the truss to the same fibre's sphere at the next
         * station broke [s] (where `broken`). */
        std::vector<double> break_time;
        /** Time of the positions: the sum of the drifts' steps [s]. */
        double time = 0.;
        /** Per station of the model (owned ones set): x-range and highest y
         * of its spheres after the last drift [m]. */
        std::vector<double> st_xlo, st_xhi, st_ymax;
        /** Kick [s] not yet applied to the velocities: it is fused with the
         * next drift (one pass over memory instead of two). */
        double pending_kick = 0.;
        /** Whether the drift has applied (and cleared) the owned forces. */
        bool forces_consumed = true;
        /** Force evaluations so far. */
        std::uint64_t step_count = 0;

        /** Write everything above to a checkpoint (dem/checkpoint.cc). */
        void
        save(Checkpoint::Writer &out) const;
        /** Read what save() wrote; the arrays keep the sizes the set-up
         * gave them. */
        void
        load(Checkpoint::Reader &in);
      };


      /** The elastic energy stored in the projectile contacts at the last
       * force evaluation needs where the projectile was. */
      struct ProjectileContactState
      {
        /** Projectile axis y [m] and contact distance R + r [m]. */
        double yc = 0., Rr = 0.;
      };
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
