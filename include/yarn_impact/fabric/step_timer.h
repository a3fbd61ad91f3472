#ifndef yarn_impact_fabric_step_timer_h
#define yarn_impact_fabric_step_timer_h

#include <mpi.h>

#include <chrono>
#include <string>
#include <time.h>

namespace YarnImpact
{
  namespace Fabric
  {
    /**
     * Wall time of the parts of the fabric's step (`Fabric/Step timing`,
     * doc/fabric.md section 9): the yarn contact's list checks, list
     * builds, exchange of positions and forces, the FE model's forces
     * with its projectile contact, the integration, the stable step, the
     * history rows' observables and the snapshots. It only reads clocks:
     * the motion and the history do not depend on it.
     */
    class StepTimer
    {
    public:
      /** The parts of a run that are timed. */
      enum Part
      {
        /** Yarn contact: whether a node has moved half the skin, with the
         * reduction of the answer over the ranks (a rank waiting for a
         * slower one waits here). */
        contact_list_checks,
        /** Yarn contact: a rebuild, the gather of every node, the bins,
         * the slots and the exchange's set-up. */
        contact_list_builds,
        /** Yarn contact: between rebuilds, the positions and velocities
         * of the nodes a rank's contacts need, from their owners. */
        contact_exchange,
        /** Yarn contact: the slots' projections and forces. */
        contact_forces,
        /** The FE model's forces without the yarn contact: the ghost
         * update, the cells, the projectile contact and the reaction's
         * reduction. */
        fe_forces,
        /** The kicks and the drift. */
        integration,
        /** The stable step (its reductions over the ranks included). */
        stable_step,
        /** The history rows' observables (reductions included). */
        observables,
        /** The snapshots. */
        output,
        n_parts
      };

      /** Whether anything is timed (`Fabric/Step timing`). */
      explicit StepTimer(const bool enabled)
        : enabled(enabled)
      {}

      /** Time one part from construction to destruction. */
      class Scope
      {
      public:
        /** @p timer may be null: nothing is timed. */
        Scope(StepTimer *timer, const Part part)
          : timer(timer && timer->enabled ? timer : nullptr)
          , part(part)
        {
          if (this->timer)
            {
              start     = std::chrono::steady_clock::now();
              cpu_start = thread_cpu_seconds();
            }
        }
        ~Scope()
        {
          if (timer)
            {
              timer->seconds[part] +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                              start)
                  .count();
              timer->cpu_seconds[part] += thread_cpu_seconds() - cpu_start;
            }
        }
        Scope(const Scope &) = delete;
        Scope &
        operator=(const Scope &) = delete;

      private:
        StepTimer *const timer;
        const Part part;
        std::chrono::steady_clock::time_point start;
        double cpu_start = 0.;
      };

      /** The calling thread's CPU time [s]: on a machine shared with other
       * jobs the wall time also counts the time they held the core, the
       * CPU time does not. */
      static double
      thread_cpu_seconds()
      {
        timespec t;
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
        return t.tv_sec + 1e-9 * t.tv_nsec;
      }

      /** Wall [s] (@p cpu false) or CPU seconds so far of the yarn
       * contact's four parts together. */
      double
      yarn_contact_seconds(const bool cpu = false) const
      {
        const double *t = cpu ? cpu_seconds : seconds;
        return t[contact_list_checks] + t[contact_list_builds] +
               t[contact_exchange] + t[contact_forces];
      }

      /** Add @p wall [s] and @p cpu [s] to part @p part (a part measured
       * as a difference). */
      void
      add(const Part part, const double wall, const double cpu)
      {
        if (enabled)
          {
            seconds[part] += wall;
            cpu_seconds[part] += cpu;
          }
      }

      /** One force evaluation [-]. */
      void
      count_step()
      {
        ++steps;
      }

      /** The table, the same on every rank (collective): per part, the
       * largest over the ranks of its wall seconds [s], its milliseconds
       * per step [ms] and its share of the sum of the parts [%], the same
       * of its CPU seconds, and the yarn contact's four parts together. */
      std::string
      report(const MPI_Comm comm) const;

      /** Whether anything is timed. */
      const bool enabled;

    private:
      double seconds[n_parts]     = {};
      double cpu_seconds[n_parts] = {};
      unsigned long steps         = 0;
    };
  } // namespace Fabric
} // namespace YarnImpact

#endif
