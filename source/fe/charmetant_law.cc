#include <yarn_impact/fe/charmetant_law.h>

#include <algorithm>
#include <cmath>

namespace YarnImpact
{
  namespace FE
  {
    CharmetantLaw::CharmetantLaw(const CharmetantParameters &parameters,
                                 const double density)
      : density(density)
      , k_e(parameters.k_e)
      , k_tc(parameters.k_tc)
      , p(parameters.p)
      , k_td(parameters.k_td)
      , resist_dilation(parameters.resist_dilation)
    {}


    double
    CharmetantLaw::transverse_modulus(const Mechanics::Invariants &inv) const
    {
      const double a = std::max(std::abs(inv.compaction), 1e-3);
      return p * (p - 1.) * k_tc / 4. * std::pow(a, p - 2.) + 0.25 * k_td;
    }
  } // namespace FE
} // namespace YarnImpact
