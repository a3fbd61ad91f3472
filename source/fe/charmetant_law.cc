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
    CharmetantLaw::transverse_modulus(const Invariants &inv) const
    {
      const double a = std::max(std::abs(inv.compaction), 1e-3);
      return p * (p - 1.) * k_tc / 4. * std::pow(a, p - 2.) + 0.25 * k_td;
    }


    Invariants
    charmetant_invariants(const Matrix3 &F)
    {
      Matrix3 C;
      const double J   = internal::right_cauchy_green(F, C);
      const double I4  = C[0];
      const double t11 = C[4] - C[1] * C[1] / I4;
      const double t22 = C[8] - C[2] * C[2] / I4;
      const double t12 = C[5] - C[1] * C[2] / I4;
      const double s2 =
        ((t11 - t22) * (t11 - t22) + 4. * t12 * t12) / (4. * J * J / I4);
      Invariants inv;
      inv.elongation = 0.5 * std::log(I4);
      inv.compaction = 0.5 * std::log(J) - 0.25 * std::log(I4);
      inv.distortion = 0.5 * std::asinh(std::sqrt(s2));
      return inv;
    }
  } // namespace FE
} // namespace YarnImpact
