#ifndef yarn_impact_core_impact_simulation_h
#define yarn_impact_core_impact_simulation_h

#include <yarn_impact/core/history.h>
#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/parameters.h>

#include <mpi.h>

#include <functional>
#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace YarnImpact
{
  /**
   * A numerical failure during a run (NaN, energy blow-up): the message
   * names the step, the time and the cause.
   */
  class RunError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /**
   * The run was asked to stop by a signal (SIGTERM, SIGINT) and stopped
   * within a few steps, after writing a checkpoint (an elementary test:
   * without); the message says when and where. The program exits with
   * code 6.
   */
  class Interrupted : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /** How a run starts and keeps checkpoints (Checkpoint namespace). */
  struct CheckpointOptions
  {
    /** Continue from the model's checkpoint in Output/Directory, if it has
     * one (yarn-impact --restart). */
    bool restart = false;
    /** Write a checkpoint of the finished model at its end (with
     * Model = both, the FE part, so that a restart in the DEM part has
     * its history for the comparison). */
    bool keep_final_state = false;
  };

  /** What the time loop knows of a finished run (analysis adds the
   * verification window and the checks: analysis/run_summary.h). */
  struct RunResult
  {
    /** The model's name (ImpactModel::name()). */
    std::string model_name;
    /** ImpactModel::erodes_cells() of the model. */
    bool erodes_cells = false;
    /** ImpactModel::single_yarn() of the model. */
    bool single_yarn = true;
    /** Mass per length of the yarn as discretised [kg/m]. */
    double mass_per_length = 0.;
    /** Axial stiffness EA of the yarn as discretised [N]. */
    double axial_stiffness = 0.;
    /** Steps made [-]. */
    unsigned long n_steps = 0;
    /** Simulated time reached [s]. */
    double end_time = 0.;
    /** Wall time of the run, set-up included [s]. */
    double wall_time = 0.;
    /** Largest energy balance error of the history rows, as a fraction of
     * the initial energy [-]. */
    double max_energy_error = 0.;
    /** Time of the first history row with a failed cell or truss, or a
     * cell whose progressive fibre damage has started [s], -1 if none. */
    double first_failure_time = -1.;
    /** Time of the first history row with an eroded FE cell [s], -1 if
     * none (erosion is not failure: Observables::n_eroded). */
    double first_erosion_time = -1.;
    /** Eroded FE cells at the last history row, whole yarn [-]. */
    unsigned long n_eroded = 0;
    /** Impact speed of the projectile at the end [m/s]. */
    double final_velocity = 0.;
    /** Time at which the yarn was cut through [s], -1 if it was not. */
    double cut_through_time = -1.;
    /** The model's remarks (ImpactModel::remarks()), printed in every
     * format. */
    std::string model_remarks;
  };

  /**
   * What a layer above core adds to a run without core knowing it (the
   * application passes Analysis::run_hooks()). Each hook may be empty.
   */
  struct RunHooks
  {
    /** The fronts and widths of a history row, measured on the model's
     * station profile; without it they stay 0. Called on every rank. */
    std::function<WaveFrontPositions(const StationProfile &)> measure_fronts;
    /** More lines for the set-up report on the screen, after the model's
     * mass and time step (not with Output/Verbosity = test). Called on
     * every rank; only rank 0's @p out reaches the screen. */
    std::function<void(const ImpactModel &model, std::ostream &out)>
      report_setup;
  };

  /**
   * The time loop shared by all models (doc/theory.md section 3.1): owns
   * the schedule (Schedule: clock and output cadence), the projectile, the
   * history, the snapshots and the progress line, and drives one
   * ImpactModel with velocity Verlet (advance()). It stops at the end
   * time, when the projectile stops, or after the cut-through when asked;
   * a numerical failure throws RunError.
   */
  class ImpactSimulation
  {
  public:
    /**
     * @param parameters the shared parameters
     * @param model the model to drive
     * @param communicator the model's MPI communicator
     * @param out screen stream (written on rank 0 only)
     * @param hooks what the layer above adds (fronts, set-up report)
     * @param checkpoints restart and final-state options
     */
    ImpactSimulation(const Parameters::Shared &parameters,
                     std::unique_ptr<ImpactModel> model,
                     const MPI_Comm communicator,
                     std::ostream &out,
                     RunHooks hooks                = {},
                     CheckpointOptions checkpoints = {});

    ~ImpactSimulation();

    /**
     * Set the model up and run to the end time. Writes the history, the
     * snapshots and their PVD record into the output directory.
     * With Output/Checkpoint interval or Output/Checkpoint wall-clock
     * interval, writes checkpoints at history rows; after a SIGTERM or
     * SIGINT (Checkpoint::install_signal_handlers()), writes one within a
     * few steps (Checkpoint::SignalPoll) and throws Interrupted. With
     * CheckpointOptions::restart, continues from the model's checkpoint.
     * @throws RunError on a numerical blow-up (after keeping the last good
     * snapshot and the history up to it)
     */
    RunResult
    run();

    /** The history rows recorded so far. */
    const std::vector<HistoryRow> &
    history() const;

    /** The driven model. */
    const ImpactModel &
    model() const;

  private:
    class Implementation;
    std::unique_ptr<Implementation> impl;
  };

} // namespace YarnImpact

#endif
