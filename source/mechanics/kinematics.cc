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


    void
    fibre_frame(const double (&M)[3], FibreFrame &R)
    {
      const double n    = std::sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]);
      const double m[3] = {M[0] / n, M[1] / n, M[2] / n};
      // The axis least aligned with M gives the best-conditioned T1.
      unsigned int k = 0;
      for (unsigned int i = 1; i < 3; ++i)
        if (std::abs(m[i]) < std::abs(m[k]))
          k = i;
      // Written so that e_x gives +0 entries, not -0: the frame of e_x is
      // the identity bit for bit.
      double t[3];
      for (unsigned int i = 0; i < 3; ++i)
        t[i] = (i == k ? 1. : 0.) - m[k] * m[i];
      const double nt = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
      for (double &c : t)
        c /= nt;
      const double b[3] = {m[1] * t[2] - m[2] * t[1],
                           m[2] * t[0] - m[0] * t[2],
                           m[0] * t[1] - m[1] * t[0]};
      for (unsigned int i = 0; i < 3; ++i)
        {
          R[3 * i]     = m[i];
          R[3 * i + 1] = t[i];
          R[3 * i + 2] = b[i];
        }
    }


    Invariants
    invariants(const Matrix3 &F, const FibreFrame &R)
    {
      Matrix3 FR;
      to_fibre_frame(F, R, FR);
      return invariants(FR);
    }
  } // namespace Mechanics
} // namespace YarnImpact
