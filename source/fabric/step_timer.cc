// The table of the fabric's step by part (Fabric/Step timing,
// doc/fabric.md section 9).

#include <yarn_impact/fabric/step_timer.h>

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace YarnImpact
{
  namespace Fabric
  {
    std::string
    StepTimer::report(const MPI_Comm comm) const
    {
      // The largest over the ranks of each part, of the yarn contact's
      // parts together and of each rank's sum, of the wall and of the CPU
      // seconds: the ranks meet at every step, so the slowest sets the
      // pace.
      constexpr unsigned int n_values = n_parts + 2;
      double local[2][n_values], largest[2][n_values];
      for (unsigned int c = 0; c < 2; ++c)
        {
          const double *t = c ? cpu_seconds : seconds;
          double sum      = 0.;
          for (unsigned int k = 0; k < n_parts; ++k)
            {
              local[c][k] = t[k];
              sum += t[k];
            }
          local[c][n_parts]     = yarn_contact_seconds(c == 1);
          local[c][n_parts + 1] = sum;
        }
      MPI_Allreduce(&local[0][0],
                    &largest[0][0],
                    2 * n_values,
                    MPI_DOUBLE,
                    MPI_MAX,
                    comm);
      static const char *const names[n_parts] = {
        "yarn contact: list checks",
        "yarn contact: list builds",
        "yarn contact: exchange",
        "yarn contact: forces",
        "FE forces and projectile contact",
        "integration",
        "stable step",
        "observables",
        "output"};
      const double per = 1e3 / std::max(1ul, steps);
      std::ostringstream s;
      s << "fabric step by part (" << steps
        << " steps; largest over the ranks): part | wall s | wall ms per step "
           "| % of the wall sum | CPU s | CPU ms per step | % of the CPU sum\n"
        << std::fixed;
      const auto line = [&](const char *name, const unsigned int k) {
        s << "  " << name;
        for (unsigned int c = 0; c < 2; ++c)
          {
            const double t = largest[c][k];
            s << " | " << std::setprecision(3) << t << " | "
              << std::setprecision(4) << t * per << " | "
              << std::setprecision(1)
              << 100. * t / std::max(largest[c][n_parts + 1], 1e-300);
          }
        s << "\n";
      };
      for (unsigned int k = 0; k < n_parts; ++k)
        line(names[k], k);
      line("yarn contact (its four parts)", n_parts);
      line("timed sum (largest rank)", n_parts + 1);
      std::string out = s.str();
      out.pop_back(); // the run summary ends the line
      return out;
    }
  } // namespace Fabric
} // namespace YarnImpact
