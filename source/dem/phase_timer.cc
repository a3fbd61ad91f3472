// The table of the DEM step's parts in the four phases of an impact
// (DEM/Phase timing, doc/performance-dem.md).

#include <yarn_impact/dem/phase_timer.h>

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      std::string
      PhaseTimer::report(const MPI_Comm comm) const
      {
        // Per rank and phase: the parts and their sum [s]; the largest over
        // the ranks of each (the ranks meet at every step, so the slowest
        // sets the pace). Counts are summed.
        constexpr unsigned int n_values = n_parts + 1;
        double local[n_phases][n_values], largest[n_phases][n_values];
        for (unsigned int p = 0; p < n_phases; ++p)
          {
            double sum = 0.;
            for (unsigned int k = 0; k < n_parts; ++k)
              {
                local[p][k] = seconds[p][k];
                sum += seconds[p][k];
              }
            local[p][n_parts] = sum;
          }
        MPI_Allreduce(&local[0][0],
                      &largest[0][0],
                      n_phases * n_values,
                      MPI_DOUBLE,
                      MPI_MAX,
                      comm);
        unsigned long counts[4][n_phases], totals[4][n_phases];
        for (unsigned int p = 0; p < n_phases; ++p)
          {
            counts[0][p] = rebuilds[p];
            counts[1][p] = rebuilt_spheres[p];
            counts[2][p] = partial_searches[p];
            counts[3][p] = searched_spheres[p];
          }
        MPI_Allreduce(&counts[0][0],
                      &totals[0][0],
                      4 * n_phases,
                      MPI_UNSIGNED_LONG,
                      MPI_SUM,
                      comm);
        static const char *const phase_names[n_phases] = {
          "before contact",
          "impact to first break",
          "first break to cut",
          "after the cut"};
        std::ostringstream s;
        s << "DEM step by phase (ms per step, largest over the ranks; "
             "rebuilds summed over the ranks):\n"
          << "  phase | steps | simulated us | step | trusses | pair "
             "contacts | projectile | list checks | list rebuilds | "
             "communication | integration | stable step | block rebuilds | "
             "rebuilt spheres | partial searches | searched spheres\n";
        s << std::fixed;
        for (unsigned int p = 0; p < n_phases; ++p)
          {
            const double per = 1e3 / std::max(1ul, steps[p]);
            s << "  " << phase_names[p] << " | " << steps[p] << " | "
              << std::setprecision(3) << simulated[p] * 1e6 << " | "
              << largest[p][n_parts] * per;
            for (unsigned int k = 0; k < n_parts; ++k)
              s << " | " << largest[p][k] * per;
            for (unsigned int c = 0; c < 4; ++c)
              s << " | " << totals[c][p];
            s << "\n";
          }
        std::string out = s.str();
        out.pop_back(); // the run summary ends the line
        return out;
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
