#include <yarn_impact/analysis/smith_theory.h>
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/core/projectile.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace YarnImpact
{
  using namespace dealii;

  namespace
  {
    /** Linear interpolation of a history quantity at time t. */
    template <typename Getter>
    double
    interpolate(const std::vector<HistoryRow> &rows,
                const double t,
                const Getter &get)
    {
      if (rows.empty())
        return 0.;
      if (t <= rows.front().time)
        return get(rows.front());
      for (unsigned int i = 1; i < rows.size(); ++i)
        if (rows[i].time >= t)
          {
            const double a =
              (t - rows[i - 1].time) / (rows[i].time - rows[i - 1].time);
            return (1. - a) * get(rows[i - 1]) + a * get(rows[i]);
          }
      return get(rows.back());
    }

    /** Least-squares slope of a history quantity over [t0, t1]. */
    template <typename Getter>
    double
    fitted_rate(const std::vector<HistoryRow> &rows,
                const double t0,
                const double t1,
                const Getter &get)
    {
      double st = 0., sy = 0., stt = 0., sty = 0.;
      unsigned int n = 0;
      for (const auto &r : rows)
        if (r.time >= t0 - 1e-15 && r.time <= t1 + 1e-15)
          {
            st += r.time;
            sy += get(r);
            stt += r.time * r.time;
            sty += r.time * get(r);
            ++n;
          }
      const double det = n * stt - st * st;
      return (n >= 2 && det > 0. ? (n * sty - st * sy) / det : 0.);
    }

    std::string
    format_check(const std::string &name,
                 const double measured,
                 const double reference,
                 const double scale,
                 const std::string &unit,
                 const double tolerance,
                 bool &passed,
                 std::vector<std::string> &brief)
    {
      const double error = (measured - reference) / std::abs(reference);
      const bool ok      = std::abs(error) <= tolerance;
      passed             = passed && ok;
      std::ostringstream b;
      b << std::fixed << std::setprecision(2) << name
        << " against Smith theory within " << 100. * tolerance
        << " %: " << (ok ? "PASSED" : "FAILED");
      brief.push_back(b.str());
      std::ostringstream s;
      s << std::fixed << std::setprecision(4) << name << ": measured "
        << measured * scale << " " << unit << ", Smith " << reference * scale
        << " " << unit << ", relative error " << std::setprecision(2)
        << 100. * error << " % (tolerance " << 100. * tolerance << " %) "
        << (ok ? "PASSED" : "FAILED");
      return s.str();
    }
  } // namespace


  class ImpactSimulation::Implementation
  {
  public:
    Implementation(const Parameters::Shared &parameters,
                   std::unique_ptr<ImpactModel> model,
                   const MPI_Comm communicator,
                   std::ostream &out)
      : parameters(parameters)
      , model(std::move(model))
      , communicator(communicator)
      , is_root(Utilities::MPI::this_mpi_process(communicator) == 0)
      , out(out, is_root)
      , projectile(parameters.projectile, parameters.yarn.thickness_semi_axis)
    {}

    RunSummary
    run();

    /** The run, timed by @p timer. */
    RunSummary
    run_timed(TimerOutput &timer);

    HistoryRow
    make_row(const double time,
             const unsigned long step,
             const double dt,
             const double force) const;

    void
    write_snapshot(const double time);

    /** Add @p row to the history; an OutputError on any rank stops all. */
    void
    add_history_row(const HistoryRow &row);

    const Parameters::Shared &parameters;
    std::unique_ptr<ImpactModel> model;
    MPI_Comm communicator;
    bool is_root;
    ConditionalOStream out;
    Projectile projectile;
    std::unique_ptr<History> history;
    std::vector<std::pair<double, std::string>> snapshots;
    double initial_energy = 0.;
  };


  HistoryRow
  ImpactSimulation::Implementation::make_row(const double time,
                                             const unsigned long step,
                                             const double dt,
                                             const double force) const
  {
    HistoryRow row;
    row.time                      = time;
    row.step                      = step;
    row.time_step                 = dt;
    row.projectile_displacement   = projectile.displacement();
    row.projectile_velocity       = projectile.impact_speed();
    row.contact_force             = force;
    row.projectile_kinetic_energy = projectile.kinetic_energy();
    row.external_work             = projectile.external_work();
    row.model                     = model->observables();
    const auto &m                 = row.model;
    const double total            = m.kinetic_energy + m.elastic_energy +
                         m.contact_energy + row.projectile_kinetic_energy;
    row.energy_error =
      (initial_energy > 0.
         ? (total + m.dissipated_energy - row.external_work - initial_energy) /
             initial_energy
         : 0.);
    return row;
  }


  void
  ImpactSimulation::Implementation::write_snapshot(const double time)
  {
    const std::string &dir = parameters.output.directory;
    std::string record;
    // Each snapshot, and then the PVD that lists it, appears whole or not at
    // all; a failure on any rank stops every rank with the same message.
    collective_output(communicator, [&] {
      record = model->write_snapshot(dir, snapshots.size(), time);
    });
    snapshots.emplace_back(time * 1e6, record);
    collective_output(communicator, [&] {
      if (is_root)
        {
          AtomicFile pvd(dir + "/" + model->name() + ".pvd");
          DataOutBase::write_pvd_record(pvd.stream(), snapshots);
          pvd.commit();
        }
    });
  }


  void
  ImpactSimulation::Implementation::add_history_row(const HistoryRow &row)
  {
    collective_output(communicator, [&] { history->add(row); });
  }


  RunSummary
  ImpactSimulation::Implementation::run()
  {
    const bool verbose =
      parameters.output.verbosity == Parameters::Verbosity::normal;
    std::ostringstream timer_sink;
    // The timing table once, from rank 0 (a plain stream would have every
    // rank print it).
    ConditionalOStream timer_stream(verbose ? out.get_stream() : timer_sink,
                                    verbose && is_root);
    std::exception_ptr failure;
    RunSummary summary;
    {
      TimerOutput timer(communicator,
                        timer_stream,
                        verbose ? TimerOutput::summary : TimerOutput::never,
                        TimerOutput::wall_times);
      try
        {
          summary = run_timed(timer);
        }
      catch (...)
        {
          // A failed run's one-line error must not come after a timing
          // table, nor after deal.II's note on timers destroyed during an
          // exception: the timer ends here, silently, and the error is
          // thrown again after it.
          failure = std::current_exception();
          timer.disable_output();
        }
    }
    if (failure)
      std::rethrow_exception(failure);
    return summary;
  }


  RunSummary
  ImpactSimulation::Implementation::run_timed(TimerOutput &timer)
  {
    const auto &p      = parameters;
    const bool verbose = p.output.verbosity == Parameters::Verbosity::normal;
    const bool testing = p.output.verbosity == Parameters::Verbosity::test;
    Timer wall_timer;
    std::ostringstream setup_sink;

    {
      TimerOutput::Scope scope(timer, "set-up");
      // The set-up report once, from rank 0, whatever the model does.
      model->setup(projectile,
                   (testing || !is_root) ? setup_sink : out.get_stream());
      projectile.place_on(model->yarn_top());
    }
    const std::string name = model->name();
    collective_output(communicator, [&] {
      history = std::make_unique<History>(p.output.directory, name, is_root);
    });

    const auto axial = model->axial_properties();
    const auto smith = Analysis::smith_solution(axial,
                                                p.projectile.initial_velocity,
                                                p.projectile.mass);
    double dt        = p.time.safety_factor * model->stable_time_step();
    if (!(dt > 0.) || p.time.end_time / dt > double(p.time.max_steps))
      {
        std::ostringstream s;
        s << "the " << name << " model's stable time step " << dt
          << " s would need " << p.time.end_time / dt
          << " steps to reach Time/End time = " << p.time.end_time
          << " s, more than Time/Maximum number of steps = " << p.time.max_steps
          << " (a modulus, density or penalty with wrong units, or an impact "
             "velocity no explicit model can follow?)";
        throw InputError(s.str());
      }
    if (!testing)
      out << std::setprecision(5) << "[" << name << "] yarn mass "
          << model->mass() * 1e6 << " mg, mass per length "
          << axial.mass_per_length() * 1e6 << " mg/m, EA "
          << axial.axial_stiffness() << " N, bar wave speed "
          << std::sqrt(axial.modulus / axial.density) << " m/s\n"
          << "[" << name << "] stable time step "
          << dt / p.time.safety_factor * 1e9 << " ns, used " << dt * 1e9
          << " ns (safety factor " << p.time.safety_factor << ")\n"
          << "[" << name << "] Smith theory at "
          << p.projectile.initial_velocity << " m/s: strain " << smith.strain
          << ", transverse wave " << smith.lab_speed << " m/s, deceleration "
          << smith.deceleration << " m/s^2\n";

    double force       = model->compute_forces(projectile, dt);
    double t           = 0.;
    unsigned long step = 0;
    initial_energy     = 0.;
    {
      const auto r0  = make_row(0., 0, dt, force);
      initial_energy = r0.projectile_kinetic_energy + r0.model.kinetic_energy +
                       r0.model.elastic_energy + r0.model.contact_energy;
    }
    add_history_row(make_row(0., 0, dt, force));
    const bool snapshots_on = p.output.snapshot_interval > 0.;
    if (snapshots_on)
      {
        TimerOutput::Scope scope(timer, "output");
        write_snapshot(0.);
      }

    RunSummary summary;
    summary.model_name        = name;
    summary.regression_format = testing;
    summary.mass_per_length   = model->mass() / p.yarn.length;
    summary.axial_stiffness   = axial.axial_stiffness();
    double next_history       = p.output.history_interval;
    double next_snapshot      = p.output.snapshot_interval;
    double last_progress      = 0.;
    const double end_time     = p.time.end_time;
    const double eps_t        = 1e-9 * end_time;

    const auto fail = [&](const std::string &cause) {
      std::ostringstream s;
      s << "numerical failure in the " << name << " model at step " << step
        << ", t = " << t * 1e6 << " us: " << cause
        << ". The last good snapshot and the history up to it are kept in "
        << p.output.directory << ".";
      throw RunError(s.str());
    };

    std::string stop_reason = "end time reached";
    while (t < end_time - eps_t)
      {
        if (step % p.time.time_step_update_interval == 0)
          {
            const double critical = model->stable_time_step();
            if (!std::isfinite(critical) || !(critical > 0.))
              fail("the stable time step is not a positive number (a "
                   "collapsed or inverted element?)");
            dt = p.time.safety_factor * critical;
          }
        const double h = std::min(dt, end_time - t);

        {
          TimerOutput::Scope scope(timer, "time integration");
          model->kick(0.5 * h);
          projectile.kick(0.5 * h, force);
          model->drift(h);
          projectile.drift(h);
        }
        {
          TimerOutput::Scope scope(timer, "forces");
          force = model->compute_forces(projectile, h);
        }
        {
          TimerOutput::Scope scope(timer, "time integration");
          model->kick(0.5 * h);
          projectile.kick(0.5 * h, force);
        }
        t += h;
        ++step;
        if (step > p.time.max_steps)
          {
            std::ostringstream s;
            s << "Time/Maximum number of steps = " << p.time.max_steps
              << " reached (the stable time step fell to " << h << " s)";
            fail(s.str());
          }
        if (!std::isfinite(force) || !std::isfinite(projectile.velocity()))
          fail("the contact force is not a number");

        const bool at_end      = t >= end_time - eps_t;
        const bool history_due = t >= next_history - eps_t || at_end;
        const bool snapshot_due =
          snapshots_on && (t >= next_snapshot - eps_t || at_end);
        if (history_due || snapshot_due)
          {
            HistoryRow row;
            {
              TimerOutput::Scope scope(timer, "observables");
              row = make_row(t, step, h, force);
            }
            const auto &m = row.model;
            if (!std::isfinite(m.kinetic_energy) ||
                !std::isfinite(m.elastic_energy) ||
                !std::isfinite(m.contact_energy) ||
                !std::isfinite(m.dissipated_energy))
              fail("an energy is not a number (an inverted cell or a blow-up)");
            if (std::abs(row.energy_error) > p.time.energy_error_limit)
              {
                std::ostringstream s;
                s << "the energy balance error " << 100. * row.energy_error
                  << " % exceeds Time/Energy error limit = "
                  << 100. * p.time.energy_error_limit
                  << " % (time step too large or contact penalty too stiff?)";
                fail(s.str());
              }
            add_history_row(row);
            summary.max_energy_error =
              std::max(summary.max_energy_error, std::abs(row.energy_error));
            if (summary.first_failure_time < 0. && m.n_failed > 0)
              summary.first_failure_time = t;
            while (next_history <= t + eps_t)
              next_history += p.output.history_interval;

            if (snapshot_due)
              {
                TimerOutput::Scope scope(timer, "output");
                write_snapshot(t);
                while (next_snapshot <= t + eps_t)
                  next_snapshot += p.output.snapshot_interval;
              }
            if (summary.cut_through_time < 0. && m.n_failed > 0 &&
                model->yarn_cut_through())
              summary.cut_through_time = t;
            if (p.time.stop_at_cut_through && summary.cut_through_time >= 0. &&
                t >= summary.cut_through_time + p.time.time_after_cut_through -
                       eps_t)
              {
                stop_reason = "the yarn is cut through";
                break;
              }
            if (!projectile.prescribed() && projectile.impact_speed() <= 0.)
              {
                stop_reason = "the projectile stopped";
                break;
              }
          }

        if (verbose && is_root &&
            wall_timer.wall_time() - last_progress > p.output.progress_interval)
          {
            last_progress    = wall_timer.wall_time();
            const double eta = last_progress * (end_time - t) / t;
            out << "[" << name << "] t = " << std::fixed << std::setprecision(3)
                << t * 1e6 << " us, step " << step << ", dt "
                << std::defaultfloat << std::setprecision(4) << h * 1e9
                << std::fixed << " ns, v = " << std::setprecision(3)
                << projectile.impact_speed() << " m/s, ETA "
                << std::setprecision(1) << eta << " s" << std::defaultfloat
                << std::endl;
          }
      }

    summary.model_remarks  = model->remarks();
    summary.n_steps        = step;
    summary.end_time       = t;
    summary.wall_time      = wall_timer.wall_time();
    summary.final_velocity = projectile.impact_speed();

    const auto &rows = history->rows();
    for (unsigned int k = 1; k <= 10; ++k)
      {
        const double ts = 0.1 * k * t;
        auto it         = std::lower_bound(rows.begin(),
                                   rows.end(),
                                   ts - eps_t,
                                   [](const HistoryRow &r, const double x) {
                                     return r.time < x;
                                   });
        if (it != rows.end())
          summary.samples.push_back(*it);
      }

    // Smith-theory quantities in the verification window.
    const double t0 = p.verification.window_start;
    const double t1 = std::min(p.verification.window_end, t);
    if (t1 > t0)
      {
        const auto v = [](const HistoryRow &r) {
          return r.projectile_velocity;
        };
        summary.mean_deceleration =
          (interpolate(rows, t0, v) - interpolate(rows, t1, v)) / (t1 - t0);
        // The longitudinal front stops at the clamp: its speed is fitted
        // only while it runs (up to 95 % of the half-length).
        double t1_front = t1;
        for (const auto &r : rows)
          if (r.time > t0 &&
              r.model.fronts.longitudinal >= 0.95 * 0.5 * p.yarn.length)
            {
              t1_front = std::min(t1, r.time);
              break;
            }
        if (t1_front < t1)
          summary.front_at_clamp_time = t1_front;
        // Too short a run to the clamp (a tenth of the window) gives no
        // speed worth reporting.
        summary.longitudinal_speed =
          (t1_front - t0 > 0.1 * (t1 - t0)
             ? fitted_rate(rows,
                           t0,
                           t1_front,
                           [](const HistoryRow &r) {
                             return r.model.fronts.longitudinal;
                           })
             : 0.);
        summary.transverse_speed =
          fitted_rate(rows, t0, t1, [](const HistoryRow &r) {
            return r.model.fronts.transverse;
          });
        double sum     = 0.;
        unsigned int n = 0;
        for (const auto &r : rows)
          if (r.time >= t0 && r.time <= t1)
            {
              sum += r.model.fronts.plateau_strain;
              ++n;
            }
        summary.plateau_strain = (n > 0 ? sum / n : 0.);
      }

    const auto &v    = p.verification;
    const double tol = v.tolerance;
    bool &ok         = summary.checks_passed;
    if (v.check_deceleration)
      summary.checks.push_back(format_check("mean deceleration",
                                            summary.mean_deceleration,
                                            smith.deceleration,
                                            1e-5,
                                            "1e5 m/s^2",
                                            tol,
                                            ok,
                                            summary.brief_checks));
    if (v.check_plateau_strain)
      summary.checks.push_back(format_check("strain behind the front",
                                            summary.plateau_strain,
                                            smith.strain,
                                            1e2,
                                            "%",
                                            tol,
                                            ok,
                                            summary.brief_checks));
    if (v.check_longitudinal_speed)
      summary.checks.push_back(format_check("longitudinal front speed",
                                            summary.longitudinal_speed,
                                            smith.wave_speed,
                                            1.,
                                            "m/s",
                                            tol,
                                            ok,
                                            summary.brief_checks));
    if (v.check_transverse_speed)
      summary.checks.push_back(format_check("transverse front speed",
                                            summary.transverse_speed,
                                            smith.lab_speed,
                                            1.,
                                            "m/s",
                                            tol,
                                            ok,
                                            summary.brief_checks));
    if (v.check_energy)
      {
        const bool e_ok = summary.max_energy_error <= v.energy_tolerance;
        std::ostringstream s;
        s << std::fixed << std::setprecision(4)
          << "energy balance: largest error " << 100. * summary.max_energy_error
          << " % of the initial energy "
          << "(tolerance " << 100. * v.energy_tolerance << " %) "
          << (e_ok ? "PASSED" : "FAILED");
        summary.checks.push_back(s.str());
        std::ostringstream b;
        b << std::fixed << std::setprecision(2) << "energy balance within "
          << 100. * v.energy_tolerance
          << " % of the initial energy: " << (e_ok ? "PASSED" : "FAILED");
        summary.brief_checks.push_back(b.str());
        ok = ok && e_ok;
      }

    if (!testing)
      out << "[" << name << "] stopped: " << stop_reason << '\n';
    return summary;
  }


  ImpactSimulation::ImpactSimulation(const Parameters::Shared &parameters,
                                     std::unique_ptr<ImpactModel> model,
                                     const MPI_Comm communicator,
                                     std::ostream &out)
    : impl(std::make_unique<Implementation>(parameters,
                                            std::move(model),
                                            communicator,
                                            out))
  {}

  ImpactSimulation::~ImpactSimulation() = default;

  RunSummary
  ImpactSimulation::run()
  {
    return impl->run();
  }

  const std::vector<HistoryRow> &
  ImpactSimulation::history() const
  {
    static const std::vector<HistoryRow> none;
    return impl->history ? impl->history->rows() : none;
  }

  const ImpactModel &
  ImpactSimulation::model() const
  {
    return *impl->model;
  }


  void
  print_summary(const RunSummary &s, std::ostream &out)
  {
    out << std::fixed << "Summary (" << s.model_name << " model)\n"
        << std::setprecision(4)
        << "  end time:                   " << s.end_time * 1e6 << " us\n";
    if (!s.regression_format)
      out << "  final projectile velocity:  " << s.final_velocity << " m/s\n"
          << "  largest energy error:       " << 100. * s.max_energy_error
          << " % of the initial energy\n";
    out << "  first failure:              ";
    if (s.first_failure_time >= 0.)
      out << s.first_failure_time * 1e6 << " us\n";
    else
      out << "none\n";
    out << "  yarn cut through:           ";
    if (s.cut_through_time >= 0.)
      out << s.cut_through_time * 1e6 << " us\n";
    else
      out << "no\n";
    out << "  window: mean deceleration   " << s.mean_deceleration * 1e-5
        << " 1e5 m/s^2\n"
        << "  window: plateau strain      " << s.plateau_strain * 1e2 << " %\n"
        << "  window: longitudinal speed  ";
    if (s.front_at_clamp_time > 0. && s.longitudinal_speed == 0.)
      out << "not measured (the front reached the clamp at "
          << s.front_at_clamp_time * 1e6 << " us)";
    else
      out << s.longitudinal_speed << " m/s";
    if (s.front_at_clamp_time > 0. && s.longitudinal_speed != 0.)
      out << " (fitted up to " << s.front_at_clamp_time * 1e6
          << " us, when the front reached the clamp)";
    out << "\n  window: transverse speed    " << s.transverse_speed << " m/s\n";
    // The contact force jitters as surface nodes touch and leave the
    // projectile: the regression format leaves it out.
    out << "  history samples: t [us], v [m/s], "
        << (s.regression_format ? "" : "force [N], ")
        << "max strain [%], energy error [%], transverse front [mm], "
           "spreading front [mm]\n";
    for (const auto &r : s.samples)
      if (!s.regression_format || r.time <= 16e-6 * (1. + 1e-9))
        {
          out << "   " << std::setprecision(3) << std::setw(8) << r.time * 1e6
              << std::setprecision(4) << std::setw(10) << r.projectile_velocity;
          if (!s.regression_format)
            out << std::setprecision(3) << std::setw(9) << r.contact_force;
          out << std::setprecision(4) << std::setw(8)
              << 100. * r.model.max_strain << std::setw(9)
              << 100. * r.energy_error << std::setprecision(3) << std::setw(8)
              << 1e3 * r.model.fronts.transverse << std::setw(8)
              << 1e3 * r.model.fronts.spreading << '\n';
        }
    for (const auto &c : (s.regression_format ? s.brief_checks : s.checks))
      out << "  check " << c << '\n';
    if (!s.model_remarks.empty())
      out << "  " << s.model_remarks << '\n';
    out << std::defaultfloat;
  }
} // namespace YarnImpact
