#ifndef yarn_impact_analysis_run_summary_h
#define yarn_impact_analysis_run_summary_h

#include <yarn_impact/analysis/parameters.h>
#include <yarn_impact/core/history.h>
#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/parameters.h>

#include <iosfwd>
#include <string>
#include <vector>

namespace YarnImpact
{
  /** What a finished run measured, for the summary and the checks: the
   * time loop's RunResult and what analysis measures on its history. */
  struct RunSummary : RunResult
  {
    /** Quantities in the verification window. */
    double mean_deceleration  = 0.; ///< [m/s^2]
    double plateau_strain     = 0.; ///< [-]
    double longitudinal_speed = 0.; ///< [m/s]
    double transverse_speed   = 0.; ///< [m/s]
    /** Time at which the longitudinal front reached the clamp inside the
     * window, where its speed fit stops [s]; -1 if it did not. */
    double front_at_clamp_time = -1.;
    /** History rows at ten evenly spaced times (interpolated). */
    std::vector<HistoryRow> samples;
    /** Lines "name: measured, reference, relative error, PASSED/FAILED". */
    std::vector<std::string> checks;
    /** The same lines without the measured numbers. */
    std::vector<std::string> brief_checks;
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

  namespace Analysis
  {
    /**
     * What analysis adds to a run of the time loop: the wave fronts of each
     * history row, measured on the model's station profile with the
     * thresholds of @p analysis (Wave fronts), and Smith's solution for the
     * projectile of @p shared in the set-up report.
     */
    RunHooks
    run_hooks(const YarnImpact::Parameters::Shared &shared,
              const Parameters &analysis);

    /**
     * Summarise a finished run: the history samples, the Smith-theory
     * quantities in the verification window and the checks that
     * @p analysis (Verification) asks for.
     * @param result what the time loop returned
     * @param rows its history
     * @param axial the model's axial properties (Smith's solution)
     * @param shared the shared parameters of the run
     * @param analysis its window and checks
     */
    RunSummary
    summarise_run(const RunResult &result,
                  const std::vector<HistoryRow> &rows,
                  const AxialProperties &axial,
                  const YarnImpact::Parameters::Shared &shared,
                  const Parameters &analysis);
  } // namespace Analysis

  /** Write @p summary (and the Smith references it quotes) as text. */
  void
  print_summary(const RunSummary &summary, std::ostream &out);
} // namespace YarnImpact

#endif
