#include <yarn_impact/core/observables.h>

#include <deal.II/base/mpi.h>

#include <algorithm>

namespace YarnImpact
{
  void
  StationProfile::resize(const unsigned int n)
  {
    for (auto *v : {&position,
                    &axial_strain,
                    &deflection,
                    &width,
                    &initial_width,
                    &rms_width})
      v->assign(n, 0.);
  }


  std::vector<FibreBreak>
  gather_fibre_breaks(const std::vector<FibreBreak> &own,
                      const char *part,
                      const MPI_Comm communicator)
  {
    // Five doubles per break: one array to exchange.
    std::vector<double> local;
    for (const FibreBreak &b : own)
      local.insert(local.end(), {b.time, double(b.fibre), b.x, b.y, b.z});
    std::vector<FibreBreak> breaks;
    for (const std::vector<double> &r :
         dealii::Utilities::MPI::all_gather(communicator, local))
      for (std::size_t k = 0; k + 4 < r.size(); k += 5)
        {
          FibreBreak b;
          b.time  = r[k];
          b.part  = part;
          b.fibre = static_cast<unsigned int>(r[k + 1]);
          b.x     = r[k + 2];
          b.y     = r[k + 3];
          b.z     = r[k + 4];
          breaks.push_back(b);
        }
    std::sort(breaks.begin(), breaks.end(), break_less);
    return breaks;
  }
} // namespace YarnImpact
