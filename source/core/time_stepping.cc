#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/core/time_stepping.h>

#include <deal.II/base/timer.h>

namespace YarnImpact
{
  namespace
  {
    /** A timer section when there is a timer (the benchmarks run
     * without). */
    class OptionalScope
    {
    public:
      OptionalScope(dealii::TimerOutput *timer, const char *section)
        : timer(timer)
      {
        if (timer)
          timer->enter_subsection(section);
      }

      ~OptionalScope()
      {
        // As deal.II's Scope: a destructor must not throw (it may run
        // while a model's RunError unwinds).
        try
          {
            if (timer)
              timer->leave_subsection();
          }
        catch (...)
          {}
      }

      OptionalScope(const OptionalScope &) = delete;
      OptionalScope &
      operator=(const OptionalScope &) = delete;

    private:
      dealii::TimerOutput *const timer;
    };
  } // namespace


  double
  advance(ImpactModel &model,
          Projectile &projectile,
          const double force,
          const double dt,
          dealii::TimerOutput *timer)
  {
    {
      OptionalScope scope(timer, "time integration");
      model.kick(0.5 * dt);
      projectile.kick(0.5 * dt, force);
      model.drift(dt);
      projectile.drift(dt);
    }
    double new_force;
    {
      OptionalScope scope(timer, "forces");
      new_force = model.compute_forces(projectile, dt);
    }
    {
      OptionalScope scope(timer, "time integration");
      model.kick(0.5 * dt);
      projectile.kick(0.5 * dt, new_force);
    }
    return new_force;
  }
} // namespace YarnImpact
