#include <yarn_impact/mechanics/kinematics.h>

#include <cmath>

namespace YarnImpact
{
  namespace Mechanics
  {
    Invariants
    invariants(const Matrix3 &F)
    {
      Matrix3 C;
      const double J   = right_cauchy_green(F, C);
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
  } // namespace Mechanics
} // namespace YarnImpact
