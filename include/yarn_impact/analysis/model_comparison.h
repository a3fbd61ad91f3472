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
    /** What the comparison of the FE and DEM runs of one problem found. */
    struct ComparisonSummary
    {
      /** Largest |v_FE - v_DEM| up to the first DEM fibre break (or the end
       * when no fibre broke) [m/s]. */
      double max_velocity_difference = 0.;
      /** Time of that largest difference [s]. */
      double time_of_max_difference = 0.;
      /** Time up to which the velocities were compared [s]. */
      double compared_until = 0.;
      /** Time of the first DEM fibre (truss) break [s], -1 if none. */
      double first_dem_break = -1.;
      /** Time of the first FE cell failure [s], -1 if none. */
      double first_fe_failure = -1.;
    };

    /**
     * Compare two histories of the same problem: interpolate both on the
     * times of @p fe, write `comparison.csv` (time; FE and DEM projectile
     * velocity and their difference; the three fronts of both) into
     * @p directory, and return the summary.
     */
    ComparisonSummary
    compare_models(const std::vector<HistoryRow> &fe,
                   const std::vector<HistoryRow> &dem,
                   const std::string &directory);

    /**
     * Write @p summary, the two models' mass per length and axial stiffness
     * side by side (doc/theory.md section 1.7), and the end-of-run energy
     * budgets of both models.
     */
    void
    print_comparison(const ComparisonSummary &summary,
                     const double (&mass_per_length)[2],
                     const double (&axial_stiffness)[2],
                     const std::vector<HistoryRow> &fe,
                     const std::vector<HistoryRow> &dem,
                     std::ostream &out);
  } // namespace Analysis
} // namespace YarnImpact

#endif
