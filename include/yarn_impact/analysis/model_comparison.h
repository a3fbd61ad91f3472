#ifndef yarn_impact_analysis_model_comparison_h
#define yarn_impact_analysis_model_comparison_h

#include <yarn_impact/core/history.h>

#include <iosfwd>
#include <string>
#include <vector>

namespace YarnImpact
{
  namespace Analysis
  {
    /** One model's run, as the comparison takes it. */
    struct ComparedRun
    {
      /** The model's name as the columns and the summary give it ("FE",
       * "DEM", "hybrid"; model_label()). */
      std::string label;
      /** Its history. */
      std::vector<HistoryRow> history;
      /** Its mass per length as discretised [kg/m]. */
      double mass_per_length = 0.;
      /** Its axial stiffness EA as discretised [N]. */
      double axial_stiffness = 0.;
      /** The wall-clock time of its run, set-up included [s]; negative
       * where not measured (the deterministic summaries of the tests). */
      double wall_time = -1.;
    };

    /** The label of the model @p name (ImpactModel::name()) in the
     * comparison: "FE" for fe, "DEM" for dem, the name itself otherwise. */
    std::string
    model_label(const std::string &name);

    /** What the comparison of one run with the reference (DEM) run of the
     * same problem found. */
    struct ComparisonSummary
    {
      /** Largest |v - v_DEM| up to the first DEM fibre break (or the end
       * when no fibre broke) [m/s]. */
      double max_velocity_difference = 0.;
      /** Time of that largest difference [s]. */
      double time_of_max_difference = 0.;
      /** Time up to which the velocities were compared [s]. */
      double compared_until = 0.;
      /** Time of the first DEM fibre (truss) break [s], -1 if none. */
      double first_dem_break = -1.;
      /** Time of the first failure (cell, truss or fibre bar) of the
       * compared run [s], -1 if none. */
      double first_fe_failure = -1.;
    };

    /**
     * Compare every run of @p runs with the reference @p runs[reference]
     * (the DEM) on the same problem: interpolate all on the times of the
     * first run, write `comparison.csv` into @p directory (time; each
     * model's projectile velocity, then each one's difference to the
     * reference's; each front of every model: columns `v FE [m/s]`,
     * `v FE - v DEM [m/s]`, `transverse front hybrid [mm]`, ...), and
     * return the summary of each run (that of the reference empty).
     */
    std::vector<ComparisonSummary>
    compare_models(const std::vector<ComparedRun> &runs,
                   const unsigned int reference,
                   const std::string &directory);

    /**
     * Write, for every run of @p runs other than the reference, its
     * summary of @p summaries, its mass per length and axial stiffness
     * next to the reference's (doc/theory.md section 1.7), and the
     * end-of-run energy budgets of both.
     */
    void
    print_comparison(const std::vector<ComparisonSummary> &summaries,
                     const std::vector<ComparedRun> &runs,
                     const unsigned int reference,
                     std::ostream &out);
  } // namespace Analysis
} // namespace YarnImpact

#endif
