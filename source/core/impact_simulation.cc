// The time loop of ImpactSimulation and its output (history, snapshots).

#include "impact_simulation_implementation.h"

namespace YarnImpact
{

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
    if (hooks.measure_fronts)
      row.fronts = hooks.measure_fronts(row.model.profile);
    // The history keeps every row: not their profiles.
    row.model.profile  = StationProfile();
    const auto &m      = row.model;
    const double total = m.kinetic_energy + m.elastic_energy +
                         m.contact_energy + row.projectile_kinetic_energy;
    row.energy_error =
      (initial_energy > 0.
         ? (total + m.dissipated_energy - row.external_work - initial_energy) /
             initial_energy
         : 0.);
    return row;
  }


  void
  ImpactSimulation::Implementation::write_pvd() const
  {
    collective_output(communicator, [&] {
      if (is_root)
        {
          AtomicFile pvd(parameters.output.directory + "/" + model->name() +
                         ".pvd");
          DataOutBase::write_pvd_record(pvd.stream(), snapshots);
          pvd.commit();
        }
    });
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
    write_pvd();
  }


  void
  ImpactSimulation::Implementation::add_history_row(const HistoryRow &row)
  {
    collective_output(communicator, [&] { history->add(row); });
  }


  RunResult
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
    RunResult summary;
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


  RunResult
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
    const std::string &dir = p.output.directory;
    // The checkpoint is verified whole (or the older one taken) before the
    // run changes anything in the directory.
    std::string saved_state;
    if (checkpoints.restart)
      checkpoint_info = Checkpoint::read(dir, name, communicator, saved_state);
    const bool restarted = checkpoint_info.generation > 0;
    if (!restarted)
      collective_output(communicator, [&] {
        history = std::make_unique<History>(dir, name, is_root);
      });

    Schedule schedule(p.time, p.output);
    schedule.set_critical_step(model->stable_time_step());
    const auto axial = model->axial_properties();
    {
      const double dt = schedule.time_step();
      if (!(dt > 0.) || p.time.end_time / dt > double(p.time.max_steps))
        {
          std::ostringstream s;
          s << "the " << name << " model's stable time step " << dt
            << " s would need " << p.time.end_time / dt
            << " steps to reach Time/End time = " << p.time.end_time
            << " s, more than Time/Maximum number of steps = "
            << p.time.max_steps
            << " (a modulus, density or penalty with wrong units, or an "
               "impact velocity no explicit model can follow?)";
          throw InputError(s.str());
        }
    }
    if (!testing)
      {
        const double dt = schedule.time_step();
        out << std::setprecision(5) << "[" << name << "] yarn mass "
            << model->mass() * 1e6 << " mg, mass per length "
            << axial.mass_per_length() * 1e6 << " mg/m, EA "
            << axial.axial_stiffness() << " N, bar wave speed "
            << std::sqrt(axial.modulus / axial.density) << " m/s\n"
            << "[" << name << "] stable time step "
            << dt / p.time.safety_factor * 1e9 << " ns, used " << dt * 1e9
            << " ns (safety factor " << p.time.safety_factor << ")\n";
        if (hooks.report_setup)
          hooks.report_setup(*model, is_root ? out.get_stream() : setup_sink);
      }

    const auto fail = [&](const std::string &cause) {
      std::ostringstream s;
      s << "numerical failure in the " << name << " model at step "
        << schedule.step() << ", t = " << schedule.time() * 1e6
        << " us: " << cause
        << ". The last good snapshot and the history up to it are kept in "
        << p.output.directory << ".";
      throw RunError(s.str());
    };
    // Every energy of a row finite before it is written, or the run stops.
    const auto check_finite = [&](const HistoryRow &row) {
      const auto &m = row.model;
      if (!std::isfinite(m.kinetic_energy) ||
          !std::isfinite(m.elastic_energy) ||
          !std::isfinite(m.contact_energy) ||
          !std::isfinite(m.dissipated_energy))
        fail("an energy is not a number (an inverted cell or a blow-up)");
      if (!std::isfinite(row.projectile_kinetic_energy) ||
          !std::isfinite(row.external_work) || !std::isfinite(row.energy_error))
        fail("the projectile's kinetic energy, its work or the energy "
             "balance error is not a finite number (Projectile/Mass or "
             "Projectile/Impact velocity too large?)");
    };

    RunResult result;
    std::string stop_reason = "end time reached";
    double force            = 0.;
    if (restarted)
      {
        TimerOutput::Scope scope(timer, "checkpoint");
        Checkpoint::Reader in(
          Checkpoint::rank_file(dir,
                                name,
                                checkpoint_info.slot,
                                Utilities::MPI::this_mpi_process(communicator)),
          std::move(saved_state));
        load_checkpoint(in, schedule, force, result, stop_reason);
        if (!testing)
          out << "[" << name << "] restarted from its checkpoint at t = "
              << schedule.time() * 1e6 << " us, step " << schedule.step()
              << (checkpoint_info.completed ? " (its run had finished)" : "")
              << '\n';
      }
    else
      {
        force = model->compute_forces(projectile, schedule.time_step());
        initial_energy = 0.;
        {
          const auto r0  = make_row(0., 0, schedule.time_step(), force);
          initial_energy = r0.projectile_kinetic_energy +
                           r0.model.kinetic_energy + r0.model.elastic_energy +
                           r0.model.contact_energy;
        }
        {
          const auto row0 = make_row(0., 0, schedule.time_step(), force);
          check_finite(row0);
          add_history_row(row0);
        }
        if (schedule.snapshots_on())
          {
            TimerOutput::Scope scope(timer, "output");
            write_snapshot(0.);
          }
        next_checkpoint = p.output.checkpoint_interval;
      }

    result.model_name      = name;
    result.mass_per_length = model->mass() / p.yarn.length;
    result.axial_stiffness = axial.axial_stiffness();
    double last_progress   = 0.;
    double last_checkpoint = 0.;
    const double eps_t     = schedule.epsilon();
    const double t_start   = schedule.time();
    const bool finished    = restarted && checkpoint_info.completed;
    // What a checkpoint at a history row writes, and when it is due.
    const auto write_checkpoint = [&](const bool completed) {
      TimerOutput::Scope scope(timer, "checkpoint");
      const double t = schedule.time();
      if (p.output.checkpoint_interval > 0.)
        advance_past(next_checkpoint, p.output.checkpoint_interval, t, eps_t);
      checkpoint_info = Checkpoint::write(
        dir,
        name,
        communicator,
        checkpoint_info,
        t,
        schedule.step(),
        completed,
        checkpoint_state(schedule, force, result, stop_reason));
      last_checkpoint = wall_timer.wall_time();
    };

    // The stop on a signal, after its checkpoint.
    const auto stop_on = [&](const int signal) {
      std::ostringstream s;
      s << "the " << name << " run was stopped by "
        << (signal == SIGINT ? "SIGINT" : "SIGTERM")
        << " at t = " << schedule.time() * 1e6 << " us (step "
        << schedule.step() << "); its state is saved in "
        << Checkpoint::info_file(dir, name);
      throw Interrupted(s.str());
    };
    Checkpoint::SignalPoll signal_poll(communicator);

    while (!finished && schedule.running())
      {
        if (schedule.time_step_update_due())
          {
            double critical;
            {
              TimerOutput::Scope scope(timer, "stable time step");
              critical = model->stable_time_step();
            }
            if (!std::isfinite(critical) || !(critical > 0.))
              fail("the stable time step is not a positive number (a "
                   "collapsed or inverted element?)");
            schedule.set_critical_step(critical);
          }
        const double h = schedule.next_step();
        force          = advance(*model, projectile, force, h, &timer);
        schedule.advance(h);
        const double t = schedule.time();
        if (schedule.step() > p.time.max_steps)
          {
            std::ostringstream s;
            s << "Time/Maximum number of steps = " << p.time.max_steps
              << " reached (the stable time step fell to " << h << " s)";
            fail(s.str());
          }
        if (!std::isfinite(force))
          fail("the contact force is not a number");
        if (!std::isfinite(projectile.velocity()) ||
            !std::isfinite(projectile.displacement()))
          fail("the projectile's velocity or displacement is not a number");

        const bool snapshot_due = schedule.snapshot_due();
        if (schedule.history_due() || snapshot_due)
          {
            HistoryRow row;
            {
              TimerOutput::Scope scope(timer, "observables");
              row = make_row(t, schedule.step(), h, force);
            }
            const auto &m = row.model;
            check_finite(row);
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
            result.max_energy_error =
              std::max(result.max_energy_error, std::abs(row.energy_error));
            // The first fibre break: a failed cell or truss, or the first
            // cell whose progressive fibre damage has started. Erosion is
            // not failure.
            if (result.first_failure_time < 0. &&
                (m.n_failed > 0 || m.n_damaged > 0))
              result.first_failure_time = t;
            if (result.first_erosion_time < 0. && m.n_eroded > 0)
              result.first_erosion_time = t;
            result.n_eroded = m.n_eroded;
            schedule.history_written();

            if (snapshot_due)
              {
                TimerOutput::Scope scope(timer, "output");
                write_snapshot(t);
                schedule.snapshot_written();
              }
            if (result.cut_through_time < 0. && m.cut_through)
              result.cut_through_time = t;
            if (p.time.stop_at_cut_through && result.cut_through_time >= 0. &&
                t >= result.cut_through_time + p.time.time_after_cut_through -
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

            // Checkpoints: at their interval, and when a signal asks the
            // run to stop. The signal may reach the ranks at different
            // steps: they agree here, at the same row.
            Checkpoint::internal::inject_signal();
            int due[2] = {Checkpoint::signal_received(),
                          is_root && p.output.checkpoint_wall_interval > 0. &&
                            wall_timer.wall_time() - last_checkpoint >=
                              p.output.checkpoint_wall_interval};
            MPI_Allreduce(MPI_IN_PLACE, due, 2, MPI_INT, MPI_MAX, communicator);
            if (due[0] != 0 || due[1] != 0 ||
                (p.output.checkpoint_interval > 0. &&
                 t >= next_checkpoint - eps_t))
              write_checkpoint(false);
            if (due[0] != 0)
              stop_on(due[0]);
          }
        // A signal between rows: agreed within a few steps, however long
        // the history interval (the run's state is saved as it is).
        if (const int signal = signal_poll.poll(); signal != 0)
          {
            write_checkpoint(false);
            stop_on(signal);
          }

        if (verbose && is_root &&
            wall_timer.wall_time() - last_progress > p.output.progress_interval)
          {
            last_progress = wall_timer.wall_time();
            const double eta =
              last_progress * (p.time.end_time - t) / (t - t_start);
            out << "[" << name << "] t = " << std::fixed << std::setprecision(3)
                << t * 1e6 << " us, step " << schedule.step() << ", dt "
                << std::defaultfloat << std::setprecision(4) << h * 1e9
                << std::fixed << " ns, v = " << std::setprecision(3)
                << projectile.impact_speed() << " m/s, ETA "
                << std::setprecision(1) << eta << " s" << std::defaultfloat
                << std::endl;
          }
      }

    if (checkpoints.keep_final_state && !finished)
      write_checkpoint(true);

    result.model_remarks  = model->remarks();
    result.n_steps        = schedule.step();
    result.end_time       = schedule.time();
    result.wall_time      = wall_timer.wall_time();
    result.final_velocity = projectile.impact_speed();

    if (!testing)
      out << "[" << name << "] stopped: " << stop_reason << '\n';
    return result;
  }


  ImpactSimulation::ImpactSimulation(const Parameters::Shared &parameters,
                                     std::unique_ptr<ImpactModel> model,
                                     const MPI_Comm communicator,
                                     std::ostream &out,
                                     RunHooks hooks,
                                     CheckpointOptions checkpoints)
    : impl(std::make_unique<Implementation>(parameters,
                                            std::move(model),
                                            communicator,
                                            out,
                                            std::move(hooks),
                                            checkpoints))
  {}

  ImpactSimulation::~ImpactSimulation() = default;

  RunResult
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


} // namespace YarnImpact
