#ifndef yarn_impact_dem_phase_timer_h
#define yarn_impact_dem_phase_timer_h

#include <mpi.h>

#include <chrono>
#include <string>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      /**
       * Wall time of the parts of the DEM step in the four phases of an
       * impact (`DEM/Phase timing`, doc/performance-dem.md): before contact,
       * from the impact to the first broken truss, from there to the cut,
       * after the cut. The list maintenance dominates after the fibres break,
       * and a whole-run table hides when; this one says which part costs
       * what in which phase, with the rebuild counts. It only reads clocks:
       * the motion does not depend on it.
       */
      class PhaseTimer
      {
      public:
        /** The parts of a step that are timed. */
        enum Part
        {
          /** Truss forces and failure. */
          trusses,
          /** Fibre-fibre and mirror-image contact forces. */
          pair_contacts,
          /** Sphere-projectile contact forces. */
          projectile_contact,
          /** List maintenance without the builds: the criteria, the halo
           * and ghost-layer checks (and the sweep of `Check lists`). */
          list_checks,
          /** List maintenance: the builds (with the joint-rebuild flag's
           * reduction). */
          list_rebuilds,
          /** Ghost exchanges, the extents' and the reaction's reductions
           * (a rank waiting for a slower one waits here). */
          communication,
          /** The fused kick and drift, with the owned spheres' part of the
           * list criterion. */
          integration,
          /** The bound of `Stable time step = contacts`. */
          stable_step,
          n_parts
        };
        static constexpr unsigned int n_phases = 4;

        /** Whether anything is timed (`DEM/Phase timing`). */
        explicit PhaseTimer(const bool enabled)
          : enabled(enabled)
        {}

        /** Time one part from construction to destruction. */
        class Scope
        {
        public:
          Scope(PhaseTimer &timer, const Part part)
            : timer(timer)
            , part(part)
          {
            if (timer.enabled)
              start = std::chrono::steady_clock::now();
          }
          ~Scope()
          {
            if (timer.enabled)
              timer.seconds[timer.phase][part] +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                              start)
                  .count();
          }
          Scope(const Scope &) = delete;
          Scope &
          operator=(const Scope &) = delete;

        private:
          PhaseTimer &timer;
          const Part part;
          std::chrono::steady_clock::time_point start;
        };

        /** One force evaluation of step @p dt [s] in the current phase. */
        void
        count_step(const double dt)
        {
          ++steps[phase];
          simulated[phase] += dt;
        }

        /** Block rebuilds and rebuilt spheres, partial searches and the
         * fast spheres they searched [-] of the current phase. */
        void
        count_rebuilds(const unsigned long blocks,
                       const unsigned long spheres,
                       const unsigned long partial,
                       const unsigned long fast)
        {
          rebuilds[phase] += blocks;
          rebuilt_spheres[phase] += spheres;
          partial_searches[phase] += partial;
          searched_spheres[phase] += fast;
        }

        /** Enter phase @p p (0-3) if it is later than the current one; the
         * caller knows it on every rank alike (a reduced value). */
        void
        advance_to(const unsigned int p)
        {
          if (p > phase && p < n_phases)
            phase = p;
        }

        /** The phase now. */
        unsigned int
        current() const
        {
          return phase;
        }

        /** The table of the phases, the same on every rank (collective):
         * per step, the largest over the ranks of each part and of their
         * sum [ms]; block rebuilds, rebuilt spheres, partial searches and
         * the spheres they searched summed over the ranks. */
        std::string
        report(const MPI_Comm comm) const;

        /** Whether anything is timed. */
        const bool enabled;

      private:
        unsigned int phase                       = 0;
        double seconds[n_phases][n_parts]        = {};
        unsigned long steps[n_phases]            = {};
        double simulated[n_phases]               = {};
        unsigned long rebuilds[n_phases]         = {};
        unsigned long rebuilt_spheres[n_phases]  = {};
        unsigned long partial_searches[n_phases] = {};
        unsigned long searched_spheres[n_phases] = {};
      };
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
