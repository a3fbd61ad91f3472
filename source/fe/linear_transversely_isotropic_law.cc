#include <yarn_impact/fe/linear_transversely_isotropic_law.h>

#include <cmath>

namespace YarnImpact
{
  namespace FE
  {
    LinearTransverselyIsotropicLaw::LinearTransverselyIsotropicLaw(
      const LinearParameters &parameters,
      const double density)
      : density(density)
      , E_L(parameters.E_L)
    {
      // Compliance of the normal block, inverted.
      const double EL = parameters.E_L, ET = parameters.E_T;
      const double nLT = parameters.nu_LT, nTT = parameters.nu_TT;
      const double s11 = 1. / EL, s12 = -nLT / EL, s22 = 1. / ET,
                   s23 = -nTT / ET;
      // [[s11 s12 s12] [s12 s22 s23] [s12 s23 s22]]^-1
      const double det =
        s11 * (s22 * s22 - s23 * s23) - 2. * s12 * (s12 * s22 - s23 * s12);
      C11 = (s22 * s22 - s23 * s23) / det;
      C12 = (s12 * s23 - s12 * s22) / det;
      C22 = (s11 * s22 - s12 * s12) / det;
      C23 = (s12 * s12 - s11 * s23) / det;
      G12 = parameters.G_LT;
      G23 = ET / (2. * (1. + nTT));
    }


    double
    LinearTransverselyIsotropicLaw::stress(const Mechanics::Matrix3 &F,
                                           Mechanics::Matrix3 &P,
                                           Mechanics::Invariants &inv) const
    {
      Mechanics::Matrix3 C, S;
      Mechanics::right_cauchy_green(F, C);
      const double E11 = 0.5 * (C[0] - 1.), E22 = 0.5 * (C[4] - 1.),
                   E33 = 0.5 * (C[8] - 1.);
      const double E12 = 0.5 * C[1], E13 = 0.5 * C[2], E23 = 0.5 * C[5];
      S[0] = C11 * E11 + C12 * (E22 + E33);
      S[4] = C12 * E11 + C22 * E22 + C23 * E33;
      S[8] = C12 * E11 + C23 * E22 + C22 * E33;
      S[1] = S[3] = 2. * G12 * E12;
      S[2] = S[6] = 2. * G12 * E13;
      S[5] = S[7] = 2. * G23 * E23;
      Mechanics::first_piola(F, S, P);
      inv.elongation = 0.5 * std::log(C[0]);
      return 0.5 * (S[0] * E11 + S[4] * E22 + S[8] * E33) +
             2. * (S[1] * E12 + S[2] * E13 + S[5] * E23) * 0.5;
    }
  } // namespace FE
} // namespace YarnImpact
