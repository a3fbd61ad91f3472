// The private implementation of ImpactSimulation (core/impact_simulation.h),
// shared by impact_simulation.cc (the loop and its output) and
// impact_simulation_checkpoint.cc (the checkpoint of the loop's state).
#ifndef yarn_impact_core_impact_simulation_implementation_h
#define yarn_impact_core_impact_simulation_implementation_h

#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/core/time_stepping.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <exception>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace YarnImpact
{
  using namespace dealii;

  class ImpactSimulation::Implementation
  {
  public:
    Implementation(const Parameters::Shared &parameters,
                   std::unique_ptr<ImpactModel> model,
                   const MPI_Comm communicator,
                   std::ostream &out,
                   RunHooks hooks,
                   CheckpointOptions checkpoints)
      : parameters(parameters)
      , model(std::move(model))
      , hooks(std::move(hooks))
      , checkpoints(checkpoints)
      , communicator(communicator)
      , is_root(Utilities::MPI::this_mpi_process(communicator) == 0)
      , out(out, is_root)
      , projectile(parameters.projectile, parameters.yarn.thickness_semi_axis)
    {}

    RunResult
    run();

    /** The run, timed by @p timer: set-up, start, then each step as the
     * list of its named parts (ASPECT's Simulator::run), and the end. */
    RunResult
    run_timed(TimerOutput &timer);

    /** What the time loop carries from one step to the next. */
    struct Loop
    {
      Loop(const Parameters::Time &time, const Parameters::Output &output)
        : schedule(time, output)
      {}

      /** Wall-clock time since the run began (progress lines, wall-clock
       * checkpoints, RunResult::wall_time). */
      Timer wall_timer;
      /** The clock: time, step, time step and what is due. */
      Schedule schedule;
      /** The model's axial properties, once set up. */
      AxialProperties axial;
      /** What the run returns, filled as it goes. */
      RunResult result;
      /** Why the loop ended (the run's last line). */
      std::string stop_reason = "end time reached";
      /** Contact force on the projectile after the last step [N]. */
      double force = 0.;
      /** Simulated time at which this run (or restart) began [s]. */
      double t_start = 0.;
      /** Wall-clock times of the last progress line and checkpoint [s]. */
      double last_progress = 0., last_checkpoint = 0.;
      /** A restart of a run that had already finished: no step left. */
      bool finished = false;
      /** The model's stable step at set-up (or at the restart) [s]: the
       * reference against which a collapsing step stops the run. */
      double initial_critical_step = 0.;
    };

    // The named parts of run_timed(), in their order.

    /** Set up the model and the projectile, verify a restart's checkpoint
     * (returned: this rank's saved state), open the history, take the
     * first stable step and report the set-up. */
    std::string
    set_up(Loop &loop, TimerOutput &timer);

    /** Start the run: from the checkpoint @p saved_state, or at t = 0 with
     * the first forces, history row and snapshot. */
    void
    start(Loop &loop, TimerOutput &timer, std::string saved_state);

    /** Start a step: the stable time step, when it is due. */
    void
    start_step(Loop &loop, TimerOutput &timer);

    /** Advance the model and the projectile by one step and check that
     * they stay finite; returns the step taken [s]. */
    double
    advance_step(Loop &loop, TimerOutput &timer);

    /** The history row at the step @p h [s] just taken, checked (finite
     * energies, energy balance within Time/Energy error limit). */
    HistoryRow
    check_row(Loop &loop, TimerOutput &timer, const double h);

    /** Post-process a row: the history, the run's records, a due snapshot
     * (@p snapshot_due); returns whether a stop rule ends the run. */
    bool
    post_process(Loop &loop,
                 TimerOutput &timer,
                 const HistoryRow &row,
                 const bool snapshot_due);

    /** At a history row: the checkpoint when its interval, its wall-clock
     * interval or a signal (agreed by all ranks) asks for one; a signal
     * then stops the run (Interrupted). */
    void
    maybe_checkpoint(Loop &loop, TimerOutput &timer);

    /** Between rows: a signal agreed through @p signal_poll saves the state
     * and stops the run (Interrupted). */
    void
    checkpoint_on_signal(Loop &loop,
                         TimerOutput &timer,
                         Checkpoint::SignalPoll &signal_poll);

    /** The progress line, every Output/Progress interval (normal
     * verbosity, rank 0); @p h the last step [s]. */
    void
    report_progress(Loop &loop, const double h);

    /** End the run: the final state's checkpoint if asked for, the
     * result. */
    RunResult
    finish(Loop &loop, TimerOutput &timer);

    /** Write a checkpoint of the loop's state now; @p completed: the run
     * has finished. */
    void
    write_checkpoint(Loop &loop, TimerOutput &timer, const bool completed);

    /** Stop the run after a signal (Interrupted), its state saved. */
    [[noreturn]] void
    stop_on(const Loop &loop, const int signal) const;

    /** Stop the run on a numerical failure (RunError) naming @p cause. */
    [[noreturn]] void
    fail(const Loop &loop, const std::string &cause) const;

    /** fail() unless every energy of @p row is finite. */
    void
    check_finite(const Loop &loop, const HistoryRow &row) const;

    HistoryRow
    make_row(const double time,
             const unsigned long step,
             const double dt,
             const double force) const;

    void
    write_snapshot(const double time);

    /** Write `<model>.pvd` listing #snapshots, whole or not at all
     * (collective). */
    void
    write_pvd() const;
    /** If the model records its fibre breaks: all of them so far to
     * `breaks_<name>.csv`, whole or not at all (collective). */
    void
    write_fibre_breaks() const;

    /** Add @p row to the history; an OutputError on any rank stops all. */
    void
    add_history_row(const HistoryRow &row);

    /** The checkpoint of everything the loop needs to go on: the clock,
     * the projectile, the history, the snapshot list, the loop's own
     * records and the model's state (this rank's part). */
    std::string
    checkpoint_state(const Schedule &schedule,
                     const double force,
                     const RunResult &result,
                     const std::string &stop_reason) const;

    /** Read what checkpoint_state() wrote into the same places. */
    void
    load_checkpoint(Checkpoint::Reader &in,
                    Schedule &schedule,
                    double &force,
                    RunResult &result,
                    std::string &stop_reason);

    const Parameters::Shared &parameters;
    std::unique_ptr<ImpactModel> model;
    RunHooks hooks;
    CheckpointOptions checkpoints;
    /** The last checkpoint written or read (generation 0: none). */
    Checkpoint::Info checkpoint_info;
    /** Simulated time of the next periodic checkpoint [s]. */
    double next_checkpoint = 0.;
    MPI_Comm communicator;
    bool is_root;
    ConditionalOStream out;
    Projectile projectile;
    std::unique_ptr<History> history;
    std::vector<std::pair<double, std::string>> snapshots;
    double initial_energy = 0.;
  };
} // namespace YarnImpact

#endif
