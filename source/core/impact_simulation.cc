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
    write_fibre_breaks();
  }


  void
  ImpactSimulation::Implementation::write_fibre_breaks() const
  {
    const std::optional<std::vector<FibreBreak>> breaks = model->fibre_breaks();
    if (!breaks)
      return;
    collective_output(communicator, [&] {
      if (is_root)
        {
          AtomicFile csv(parameters.output.directory + "/breaks_" +
                         model->name() + ".csv");
          std::ostream &o = csv.stream();
          o << "time [us],part,fibre,reference x [mm],reference y [mm],"
               "reference z [mm]\n"
            << std::setprecision(10);
          for (const FibreBreak &b : *breaks)
            o << b.time * 1e6 << ',' << b.part << ',' << b.fibre << ','
              << b.x * 1e3 << ',' << b.y * 1e3 << ',' << b.z * 1e3 << '\n';
          csv.commit();
        }
    });
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
    Loop loop(parameters.time, parameters.output);
    std::string saved_state = set_up(loop, timer);
    start(loop, timer, std::move(saved_state));
    Checkpoint::SignalPoll signal_poll(communicator);
    while (!loop.finished && loop.schedule.running())
      {
        start_step(loop, timer);
        const double h          = advance_step(loop, timer);
        const bool snapshot_due = loop.schedule.snapshot_due();
        if (loop.schedule.history_due() || snapshot_due)
          {
            const HistoryRow row = check_row(loop, timer, h);
            if (post_process(loop, timer, row, snapshot_due))
              break;
            maybe_checkpoint(loop, timer);
          }
        checkpoint_on_signal(loop, timer, signal_poll);
        report_progress(loop, h);
      }
    return finish(loop, timer);
  }


  std::string
  ImpactSimulation::Implementation::set_up(Loop &loop, TimerOutput &timer)
  {
    const auto &p      = parameters;
    const bool testing = Parameters::deterministic(p.output.verbosity);
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
    if (checkpoint_info.generation == 0)
      collective_output(communicator, [&] {
        history = std::make_unique<History>(dir,
                                            name,
                                            is_root,
                                            model->extra_column_names());
      });

    Schedule &schedule         = loop.schedule;
    loop.initial_critical_step = model->stable_time_step();
    schedule.set_critical_step(loop.initial_critical_step);
    loop.axial      = model->axial_properties();
    const double dt = schedule.time_step();
    if (!(dt > 0.) || p.time.end_time / dt > double(p.time.max_steps))
      {
        std::ostringstream s;
        s << "the " << name << " model's stable time step " << dt
          << " s would need " << p.time.end_time / dt
          << " steps to reach Time/End time = " << p.time.end_time
          << " s, more than Time/Maximum number of steps = " << p.time.max_steps
          << " (a modulus, density or penalty with wrong units, or an "
             "impact velocity no explicit model can follow?)";
        throw InputError(s.str());
      }
    if (!testing)
      {
        const auto &axial = loop.axial;
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
    return saved_state;
  }


  void
  ImpactSimulation::Implementation::start(Loop &loop,
                                          TimerOutput &timer,
                                          std::string saved_state)
  {
    const auto &p          = parameters;
    const std::string name = model->name();
    Schedule &schedule     = loop.schedule;
    if (checkpoint_info.generation > 0)
      {
        TimerOutput::Scope scope(timer, "checkpoint");
        Checkpoint::Reader in(
          Checkpoint::rank_file(p.output.directory,
                                name,
                                checkpoint_info.slot,
                                Utilities::MPI::this_mpi_process(communicator)),
          std::move(saved_state));
        load_checkpoint(in,
                        schedule,
                        loop.force,
                        loop.result,
                        loop.stop_reason);
        if (!Parameters::deterministic(p.output.verbosity))
          out << "[" << name << "] restarted from its checkpoint at t = "
              << schedule.time() * 1e6 << " us, step " << schedule.step()
              << (checkpoint_info.completed ? " (its run had finished)" : "")
              << '\n';
        loop.finished = checkpoint_info.completed;
      }
    else
      {
        loop.force = model->compute_forces(projectile, schedule.time_step());
        initial_energy = 0.;
        {
          const auto r0  = make_row(0., 0, schedule.time_step(), loop.force);
          initial_energy = r0.projectile_kinetic_energy +
                           r0.model.kinetic_energy + r0.model.elastic_energy +
                           r0.model.contact_energy;
        }
        {
          const auto row0 = make_row(0., 0, schedule.time_step(), loop.force);
          check_finite(loop, row0);
          add_history_row(row0);
        }
        if (schedule.snapshots_on())
          {
            TimerOutput::Scope scope(timer, "output");
            write_snapshot(0.);
          }
        next_checkpoint = p.output.checkpoint_interval;
      }
    loop.result.model_name      = name;
    loop.result.erodes_cells    = model->erodes_cells();
    loop.result.single_yarn     = model->single_yarn();
    loop.result.mass_per_length = model->mass() / p.yarn.length;
    loop.result.axial_stiffness = loop.axial.axial_stiffness();
    loop.t_start                = schedule.time();
  }


  void
  ImpactSimulation::Implementation::start_step(Loop &loop, TimerOutput &timer)
  {
    if (!loop.schedule.time_step_update_due())
      return;
    double critical;
    {
      TimerOutput::Scope scope(timer, "stable time step");
      critical = model->stable_time_step();
    }
    if (!std::isfinite(critical) || !(critical > 0.))
      fail(loop,
           "the stable time step is not a positive number (a collapsed or "
           "inverted element?)");
    // A step a million times below the set-up's would only crawl on (a
    // degenerate element sets it): stop with the cause rather than run on
    // without end.
    if (critical < 1e-6 * loop.initial_critical_step)
      {
        std::ostringstream cause;
        cause << "the stable time step fell to " << critical * 1e9
              << " ns, below a millionth of its "
              << loop.initial_critical_step * 1e9
              << " ns at the start (an element has degenerated)";
        fail(loop, cause.str());
      }
    loop.schedule.set_critical_step(critical);
  }


  double
  ImpactSimulation::Implementation::advance_step(Loop &loop, TimerOutput &timer)
  {
    Schedule &schedule = loop.schedule;
    const double h     = schedule.next_step();
    loop.force         = advance(*model, projectile, loop.force, h, &timer);
    schedule.advance(h);
    const auto max_steps = parameters.time.max_steps;
    if (schedule.step() > max_steps)
      {
        std::ostringstream s;
        s << "Time/Maximum number of steps = " << max_steps
          << " reached (the stable time step fell to " << h << " s)";
        fail(loop, s.str());
      }
    if (!std::isfinite(loop.force))
      fail(loop, "the contact force is not a number");
    if (!std::isfinite(projectile.velocity()) ||
        !std::isfinite(projectile.displacement()))
      fail(loop, "the projectile's velocity or displacement is not a number");
    return h;
  }


  HistoryRow
  ImpactSimulation::Implementation::check_row(Loop &loop,
                                              TimerOutput &timer,
                                              const double h)
  {
    HistoryRow row;
    {
      TimerOutput::Scope scope(timer, "observables");
      row = make_row(loop.schedule.time(), loop.schedule.step(), h, loop.force);
    }
    check_finite(loop, row);
    const double limit = parameters.time.energy_error_limit;
    if (std::abs(row.energy_error) > limit)
      {
        std::ostringstream s;
        s << "the energy balance error " << 100. * row.energy_error
          << " % exceeds Time/Energy error limit = " << 100. * limit
          << " % (time step too large or contact penalty too stiff?)";
        fail(loop, s.str());
      }
    return row;
  }


  bool
  ImpactSimulation::Implementation::post_process(Loop &loop,
                                                 TimerOutput &timer,
                                                 const HistoryRow &row,
                                                 const bool snapshot_due)
  {
    const auto &time  = parameters.time;
    const double t    = loop.schedule.time();
    const auto &m     = row.model;
    RunResult &result = loop.result;
    add_history_row(row);
    result.max_energy_error =
      std::max(result.max_energy_error, std::abs(row.energy_error));
    // The first fibre break: a failed cell or truss, or the first cell whose
    // progressive fibre damage has started. Erosion is not failure.
    if (result.first_failure_time < 0. && (m.n_failed > 0 || m.n_damaged > 0))
      result.first_failure_time = t;
    if (result.first_erosion_time < 0. && m.n_eroded > 0)
      result.first_erosion_time = t;
    result.n_eroded = m.n_eroded;
    loop.schedule.history_written();

    if (snapshot_due)
      {
        TimerOutput::Scope scope(timer, "output");
        write_snapshot(t);
        loop.schedule.snapshot_written();
      }
    if (result.cut_through_time < 0. && m.cut_through)
      result.cut_through_time = t;
    if (time.stop_at_cut_through && result.cut_through_time >= 0. &&
        t >= result.cut_through_time + time.time_after_cut_through -
               loop.schedule.epsilon())
      {
        loop.stop_reason = "the yarn is cut through";
        return true;
      }
    if (!projectile.prescribed() && projectile.impact_speed() <= 0.)
      {
        loop.stop_reason = "the projectile stopped";
        return true;
      }
    return false;
  }


  void
  ImpactSimulation::Implementation::maybe_checkpoint(Loop &loop,
                                                     TimerOutput &timer)
  {
    const auto &output = parameters.output;
    // The signal may reach the ranks at different steps: they agree here,
    // at the same row.
    Checkpoint::internal::inject_signal();
    int due[2] = {Checkpoint::signal_received(),
                  is_root && output.checkpoint_wall_interval > 0. &&
                    loop.wall_timer.wall_time() - loop.last_checkpoint >=
                      output.checkpoint_wall_interval};
    MPI_Allreduce(MPI_IN_PLACE, due, 2, MPI_INT, MPI_MAX, communicator);
    if (due[0] != 0 || due[1] != 0 ||
        (output.checkpoint_interval > 0. &&
         loop.schedule.time() >= next_checkpoint - loop.schedule.epsilon()))
      write_checkpoint(loop, timer, false);
    if (due[0] != 0)
      stop_on(loop, due[0]);
  }


  void
  ImpactSimulation::Implementation::checkpoint_on_signal(
    Loop &loop,
    TimerOutput &timer,
    Checkpoint::SignalPoll &signal_poll)
  {
    // Agreed within a few steps, however long the history interval (the
    // run's state is saved as it is).
    if (const int signal = signal_poll.poll(); signal != 0)
      {
        write_checkpoint(loop, timer, false);
        stop_on(loop, signal);
      }
  }


  void
  ImpactSimulation::Implementation::report_progress(Loop &loop, const double h)
  {
    const auto &p = parameters;
    if (p.output.verbosity != Parameters::Verbosity::normal || !is_root ||
        !(loop.wall_timer.wall_time() - loop.last_progress >
          p.output.progress_interval))
      return;
    const double t     = loop.schedule.time();
    loop.last_progress = loop.wall_timer.wall_time();
    const double eta =
      loop.last_progress * (p.time.end_time - t) / (t - loop.t_start);
    out << "[" << model->name() << "] t = " << std::fixed
        << std::setprecision(3) << t * 1e6 << " us, step "
        << loop.schedule.step() << ", dt " << std::defaultfloat
        << std::setprecision(4) << h * 1e9 << std::fixed
        << " ns, v = " << std::setprecision(3) << projectile.impact_speed()
        << " m/s, ETA " << std::setprecision(1) << eta << " s"
        << std::defaultfloat << std::endl;
  }


  RunResult
  ImpactSimulation::Implementation::finish(Loop &loop, TimerOutput &timer)
  {
    if (checkpoints.keep_final_state && !loop.finished)
      write_checkpoint(loop, timer, true);
    write_fibre_breaks();
    RunResult &result     = loop.result;
    result.model_remarks  = model->remarks();
    result.n_steps        = loop.schedule.step();
    result.end_time       = loop.schedule.time();
    result.wall_time      = loop.wall_timer.wall_time();
    result.final_velocity = projectile.impact_speed();
    if (!Parameters::deterministic(parameters.output.verbosity))
      out << "[" << model->name() << "] stopped: " << loop.stop_reason << '\n';
    return result;
  }


  void
  ImpactSimulation::Implementation::write_checkpoint(Loop &loop,
                                                     TimerOutput &timer,
                                                     const bool completed)
  {
    TimerOutput::Scope scope(timer, "checkpoint");
    const double t = loop.schedule.time();
    if (parameters.output.checkpoint_interval > 0.)
      advance_past(next_checkpoint,
                   parameters.output.checkpoint_interval,
                   t,
                   loop.schedule.epsilon());
    checkpoint_info      = Checkpoint::write(parameters.output.directory,
                                        model->name(),
                                        communicator,
                                        checkpoint_info,
                                        t,
                                        loop.schedule.step(),
                                        completed,
                                        checkpoint_state(loop.schedule,
                                                         loop.force,
                                                         loop.result,
                                                         loop.stop_reason));
    loop.last_checkpoint = loop.wall_timer.wall_time();
  }


  void
  ImpactSimulation::Implementation::stop_on(const Loop &loop,
                                            const int signal) const
  {
    std::ostringstream s;
    s << "the " << model->name() << " run was stopped by "
      << (signal == SIGINT ? "SIGINT" : "SIGTERM")
      << " at t = " << loop.schedule.time() * 1e6 << " us (step "
      << loop.schedule.step() << "); its state is saved in "
      << Checkpoint::info_file(parameters.output.directory, model->name());
    throw Interrupted(s.str());
  }


  void
  ImpactSimulation::Implementation::fail(const Loop &loop,
                                         const std::string &cause) const
  {
    std::ostringstream s;
    s << "numerical failure in the " << model->name() << " model at step "
      << loop.schedule.step() << ", t = " << loop.schedule.time() * 1e6
      << " us: " << cause
      << ". The last good snapshot and the history up to it are kept in "
      << parameters.output.directory << ".";
    throw RunError(s.str());
  }


  void
  ImpactSimulation::Implementation::check_finite(const Loop &loop,
                                                 const HistoryRow &row) const
  {
    // Every energy of a row finite before it is written, or the run stops.
    const auto &m = row.model;
    if (!std::isfinite(m.kinetic_energy) || !std::isfinite(m.elastic_energy) ||
        !std::isfinite(m.contact_energy) || !std::isfinite(m.dissipated_energy))
      fail(loop, "an energy is not a number (an inverted cell or a blow-up)");
    if (!std::isfinite(row.projectile_kinetic_energy) ||
        !std::isfinite(row.external_work) || !std::isfinite(row.energy_error))
      fail(loop,
           "the projectile's kinetic energy, its work or the energy balance "
           "error is not a finite number (Projectile/Mass or "
           "Projectile/Impact velocity too large?)");
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
