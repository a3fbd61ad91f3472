#ifndef yarn_impact_core_time_stepping_h
#define yarn_impact_core_time_stepping_h

#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/parameters.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dealii
{
  class TimerOutput;
}

namespace YarnImpact
{
  /**
   * Move an output time @p next [s] that is due (next <= t + eps) to the
   * first multiple of @p interval [s] after it that lies beyond @p t + @p
   * eps [s]. An interval far below the step (or below the round-off of
   * @p next, where next + interval == next) would make that a loop of
   * billions of turns or an endless one: after 64 turns @p next jumps to
   * just past t + eps, so that the output is due again at the next step,
   * as it would be on the grid.
   */
  inline void
  advance_past(double &next,
               const double interval,
               const double t,
               const double eps)
  {
    for (unsigned int turns = 0; next <= t + eps; ++turns)
      {
        if (turns == 64)
          {
            next =
              std::nextafter(t + eps, std::numeric_limits<double>::infinity());
            return;
          }
        next += interval;
      }
  }

  class ImpactModel;
  class Projectile;

  /**
   * One velocity-Verlet step of @p model with @p projectile beside it, the
   * only place that calls the model's step phases (their contract is in
   * ImpactModel):
   *
   * @code
   * model.kick(dt/2);  projectile.kick(dt/2, force)
   * model.drift(dt);   projectile.drift(dt)
   * F = model.compute_forces(projectile, dt)
   * model.kick(dt/2);  projectile.kick(dt/2, F)
   * @endcode
   *
   * @param force force of the yarn on the projectile at the start of the
   * step, as the last compute_forces() returned it [N]
   * @param dt the step [s]
   * @param timer if given, the phases are timed in its sections "time
   * integration" and "forces"
   * @return the force of the yarn on the projectile at the end of the step
   * [N]
   */
  double
  advance(ImpactModel &model,
          Projectile &projectile,
          const double force,
          const double dt,
          dealii::TimerOutput *timer = nullptr);


  /**
   * The clock of a run and its output cadence: time, step number and time
   * step, when the next history row and snapshot are due, and the end
   * time. Times are compared with a tolerance of 1e-9 of the end time, so
   * that output intervals that do not divide into whole steps in binary
   * still fall on the step that reaches them.
   */
  class Schedule
  {
  public:
    /** A clock at t = 0, step 0, with the first row and snapshot due one
     * interval later. */
    Schedule(const Parameters::Time &time, const Parameters::Output &output)
      : time_parameters(time)
      , output(output)
      , eps(1e-9 * time.end_time)
      , next_history(output.history_interval)
      , next_snapshot(output.snapshot_interval)
    {}

    /** Simulated time [s]. */
    double
    time() const
    {
      return t;
    }

    /** Steps made so far [-]. */
    unsigned long
    step() const
    {
      return n_steps;
    }

    /** The current time step: the safety factor times the last critical
     * step given to set_critical_step() [s]. */
    double
    time_step() const
    {
      return dt;
    }

    /** Tolerance of the time comparisons [s]. */
    double
    epsilon() const
    {
      return eps;
    }

    /** Whether the end time is not reached yet. */
    bool
    running() const
    {
      return t < time_parameters.end_time - eps;
    }

    /** Whether the end time is reached. */
    bool
    at_end() const
    {
      return t >= time_parameters.end_time - eps;
    }

    /** Whether the critical step is to be recomputed before the next step
     * (every Time/Time step update interval steps, the first one
     * included). */
    bool
    time_step_update_due() const
    {
      return n_steps % time_parameters.time_step_update_interval == 0;
    }

    /** Set the time step from the model's critical step @p critical [s]. */
    void
    set_critical_step(const double critical)
    {
      dt = time_parameters.safety_factor * critical;
    }

    /** The next step: the time step, shortened to land on the end time
     * [s]. */
    double
    next_step() const
    {
      return std::min(dt, time_parameters.end_time - t);
    }

    /** Count a step of @p h [s] (next_step()) as made. */
    void
    advance(const double h)
    {
      t += h;
      ++n_steps;
    }

    /** Whether a history row is due now (at its interval or at the end). */
    bool
    history_due() const
    {
      return t >= next_history - eps || at_end();
    }

    /** Whether a snapshot is due now (at its interval or at the end, and
     * snapshots are on). */
    bool
    snapshot_due() const
    {
      return snapshots_on() && (t >= next_snapshot - eps || at_end());
    }

    /** Whether snapshots are written at all (Output/Snapshot interval >
     * 0). */
    bool
    snapshots_on() const
    {
      return output.snapshot_interval > 0.;
    }

    /** A history row was written now: the next one is due at the first
     * interval after now. */
    void
    history_written()
    {
      advance_past(next_history, output.history_interval, t, eps);
    }

    /** A snapshot was written now: the next one is due at the first
     * interval after now. */
    void
    snapshot_written()
    {
      advance_past(next_snapshot, output.snapshot_interval, t, eps);
    }

    /** Write the clock (time, step, time step, next output times) to a
     * checkpoint. */
    void
    save(Checkpoint::Writer &out) const
    {
      out.tag("schedule");
      out.put(t);
      out.put(n_steps);
      out.put(dt);
      out.put(next_history);
      out.put(next_snapshot);
    }

    /** Read what save() wrote. */
    void
    load(Checkpoint::Reader &in)
    {
      in.tag("schedule");
      in.get(t);
      in.get(n_steps);
      in.get(dt);
      in.get(next_history);
      in.get(next_snapshot);
    }

  private:
    const Parameters::Time time_parameters;
    const Parameters::Output output;
    const double eps;
    double t              = 0.;
    unsigned long n_steps = 0;
    double dt             = 0.;
    double next_history;
    double next_snapshot;
  };
} // namespace YarnImpact

#endif
