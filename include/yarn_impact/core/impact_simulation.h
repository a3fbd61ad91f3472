#ifndef yarn_impact_core_impact_simulation_h
#define yarn_impact_core_impact_simulation_h

#include <yarn_impact/core/history.h>
#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/parameters.h>

#include <mpi.h>

#include <iosfwd>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
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

  /** What a finished run measured, for the summary and the checks. */
  struct RunSummary
  {
    std::string model_name;
    /** Mass per length of the yarn as discretised [kg/m]. */
    double mass_per_length = 0.;
    /** Axial stiffness EA of the yarn as discretised [N]. */
    double axial_stiffness    = 0.;
    unsigned long n_steps     = 0;
    double end_time           = 0.;  ///< [s]
    double wall_time          = 0.;  ///< [s]
    double max_energy_error   = 0.;  ///< fraction of initial energy
    double first_failure_time = -1.; ///< [s], -1 if none
    double final_velocity     = 0.;  ///< [m/s]
    /** Quantities in the verification window. */
    double mean_deceleration  = 0.; ///< [m/s^2]
    double plateau_strain     = 0.; ///< [-]
    double longitudinal_speed = 0.; ///< [m/s]
    double transverse_speed   = 0.; ///< [m/s]
    /** Time at which the longitudinal front reached the clamp inside the
     * window, where its speed fit stops [s]; -1 if it did not. */
    double front_at_clamp_time = -1.;
    /** Time at which the yarn was cut through [s], -1 if it was not. */
    double cut_through_time = -1.;
    /** History rows at ten evenly spaced times (interpolated). */
    std::vector<HistoryRow> samples;
    /** Lines "name: measured, reference, relative error, PASSED/FAILED". */
    std::vector<std::string> checks;
    /** The same lines without the measured numbers. */
    std::vector<std::string> brief_checks;
    /** The model's remarks (ImpactModel::remarks()), printed in every
     * format. */
    std::string model_remarks;
    /**
     * Print the regression format (Output/Verbosity = test): only what does
     * not depend on round-off. Contact makes late times of a run sensitive
     * to the last bits (different summation orders change the velocity at
     * 20 us by about 1e-4 m/s), so the numbers printed are the early
     * history samples (t <= 16 us) and the window measurements; checks
     * print their verdict only.
     */
    bool regression_format = false;
    /** Whether every requested check passed. */
    bool checks_passed = true;
  };

  /**
   * The time loop shared by all models (doc/theory.md section 3.1): owns
   * the clock, the projectile, the history, the snapshots and the progress
   * line, and drives one ImpactModel with velocity Verlet (central
   * difference).
   */
  class ImpactSimulation
  {
  public:
    /**
     * @param parameters the shared parameters
     * @param model the model to drive
     * @param communicator the model's MPI communicator
     * @param out screen stream (written on rank 0 only)
     */
    ImpactSimulation(const Parameters::Shared &parameters,
                     std::unique_ptr<ImpactModel> model,
                     const MPI_Comm communicator,
                     std::ostream &out);

    ~ImpactSimulation();

    /**
     * Set the model up and run to the end time. Writes the history, the
     * snapshots and their PVD record into the output directory.
     * @throws RunError on a numerical blow-up (after keeping the last good
     * snapshot and the history up to it)
     */
    RunSummary
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

  /** Write @p summary (and the Smith references it quotes) as text. */
  void
  print_summary(const RunSummary &summary, std::ostream &out);
} // namespace YarnImpact

#endif
