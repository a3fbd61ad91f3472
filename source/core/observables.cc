#include <yarn_impact/core/observables.h>

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
} // namespace YarnImpact
