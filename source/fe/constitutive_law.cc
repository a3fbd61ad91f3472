#include <yarn_impact/fe/constitutive_law.h>

#include <algorithm>

namespace YarnImpact
{
  namespace FE
  {
    namespace
    {
      /** C = F^T F (row-major, symmetric) and J = det F. */
      inline double
      right_cauchy_green(const Matrix3 &F, Matrix3 &C)
      {
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            {
              const double c = F[i] * F[j] + F[3 + i] * F[3 + j] +
                               F[6 + i] * F[6 + j];
              C[3 * i + j] = c;
              C[3 * j + i] = c;
            }
        return F[0] * (F[4] * F[8] - F[5] * F[7]) -
               F[1] * (F[3] * F[8] - F[5] * F[6]) +
               F[2] * (F[3] * F[7] - F[4] * F[6]);
      }

      /** P = F S for a symmetric S. */
      inline void
      first_piola(const Matrix3 &F, const Matrix3 &S, Matrix3 &P)
      {
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            P[3 * i + j] = F[3 * i] * S[j] + F[3 * i + 1] * S[3 + j] +
                           F[3 * i + 2] * S[6 + j];
      }
    } // namespace


    CharmetantLaw::CharmetantLaw(const CharmetantParameters &parameters,
                                 const double                density)
      : density(density)
      , k_e(parameters.k_e)
      , k_tc(parameters.k_tc)
      , p(parameters.p)
      , k_td(parameters.k_td)
    {}


    double
    CharmetantLaw::second_piola(const Matrix3 &C,
                                const double   J,
                                Matrix3       &S,
                                Invariants    &inv) const
    {
      const double I4 = C[0];
      const double I1 = C[0] + C[4] + C[8];
      const double I5 = C[0] * C[0] + C[1] * C[1] + C[2] * C[2];
      const double I3 = J * J;

      // Inverse of C from its cofactors.
      const double inv_I3 = 1. / I3;
      const double Ci00   = (C[4] * C[8] - C[5] * C[5]) * inv_I3;
      const double Ci01   = (C[2] * C[5] - C[1] * C[8]) * inv_I3;
      const double Ci02   = (C[1] * C[5] - C[2] * C[4]) * inv_I3;
      const double Ci11   = (C[0] * C[8] - C[2] * C[2]) * inv_I3;
      const double Ci12   = (C[1] * C[2] - C[0] * C[5]) * inv_I3;
      const double Ci22   = (C[0] * C[4] - C[1] * C[1]) * inv_I3;

      const double log_I4 = std::log(I4);
      const double Ie     = 0.5 * log_I4;
      const double Itc    = 0.5 * std::log(J) - 0.25 * log_I4;
      const double a_tc   = std::abs(Itc);
      // |I_tc|^(p-1), computed once for the stress and the energy.
      const double pow_pm1 = (a_tc > 0. ? std::pow(a_tc, p - 1.) : 0.);
      const double gp      = p * k_tc * pow_pm1 * (Itc >= 0. ? 1. : -1.);

      // Distortion from the Schur complement of C on the section plane,
      // which stays accurate as s -> 0 (physics.md section 1.5).
      const double inv_I4 = 1. / I4;
      const double t11    = C[4] - C[1] * C[1] * inv_I4;
      const double t22    = C[8] - C[2] * C[2] * inv_I4;
      const double t12    = C[5] - C[1] * C[2] * inv_I4;
      const double s2 =
        ((t11 - t22) * (t11 - t22) + 4. * t12 * t12) / (4. * I3 * inv_I4);
      const double s   = std::sqrt(s2);
      const double u   = std::asinh(s);
      const double psi = (s > 1e-4 ? u / s :
                                     1. - s2 / 6. + 0.075 * s2 * s2 -
                                       5. / 112. * s2 * s2 * s2);

      const double rt       = std::sqrt(I3 * I4);
      const double zeta     = (I1 * I4 - I5) / (2. * rt);
      const double inv_2rt  = 1. / (2. * rt);
      const double half_z   = 0.5 * zeta;
      // d zeta / dC, entry by entry (M = e_x, CM = first column of C).
      const double dz00 = (I4 + I1 - 2. * C[0]) * inv_2rt -
                          half_z * (Ci00 + inv_I4);
      const double dz01 = (-C[1]) * inv_2rt - half_z * Ci01;
      const double dz02 = (-C[2]) * inv_2rt - half_z * Ci02;
      const double dz11 = I4 * inv_2rt - half_z * Ci11;
      const double dz12 = -half_z * Ci12;
      const double dz22 = I4 * inv_2rt - half_z * Ci22;

      const double a = 0.5 * gp;
      const double b = 0.5 * k_td * psi;
      S[0]           = k_e * Ie * inv_I4 + a * (Ci00 - inv_I4) + b * dz00;
      S[1] = S[3] = a * Ci01 + b * dz01;
      S[2] = S[6] = a * Ci02 + b * dz02;
      S[4]        = a * Ci11 + b * dz11;
      S[5] = S[7] = a * Ci12 + b * dz12;
      S[8]        = a * Ci22 + b * dz22;

      inv.elongation = Ie;
      inv.compaction = Itc;
      inv.distortion = 0.5 * u;
      return 0.5 * k_e * Ie * Ie + k_tc * pow_pm1 * a_tc +
             0.5 * k_td * inv.distortion * inv.distortion;
    }


    double
    CharmetantLaw::stress(const Matrix3 &F, Matrix3 &P, Invariants &inv) const
    {
      Matrix3      C, S;
      const double J = right_cauchy_green(F, C);
      const double W = second_piola(C, J, S, inv);
      first_piola(F, S, P);
      return W;
    }


    double
    CharmetantLaw::transverse_modulus(const Invariants &inv) const
    {
      const double a = std::max(std::abs(inv.compaction), 1e-3);
      return p * (p - 1.) * k_tc / 4. * std::pow(a, p - 2.) + 0.25 * k_td;
    }


    Invariants
    charmetant_invariants(const Matrix3 &F)
    {
      Matrix3      C;
      const double J  = right_cauchy_green(F, C);
      const double I4 = C[0];
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


    LinearTransverselyIsotropicLaw::LinearTransverselyIsotropicLaw(
      const LinearParameters &parameters,
      const double            density)
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
    LinearTransverselyIsotropicLaw::stress(const Matrix3 &F,
                                           Matrix3       &P,
                                           Invariants    &inv) const
    {
      Matrix3 C, S;
      right_cauchy_green(F, C);
      const double E11 = 0.5 * (C[0] - 1.), E22 = 0.5 * (C[4] - 1.),
                   E33 = 0.5 * (C[8] - 1.);
      const double E12 = 0.5 * C[1], E13 = 0.5 * C[2], E23 = 0.5 * C[5];
      S[0] = C11 * E11 + C12 * (E22 + E33);
      S[4] = C12 * E11 + C22 * E22 + C23 * E33;
      S[8] = C12 * E11 + C23 * E22 + C22 * E33;
      S[1] = S[3] = 2. * G12 * E12;
      S[2] = S[6] = 2. * G12 * E13;
      S[5] = S[7] = 2. * G23 * E23;
      first_piola(F, S, P);
      inv.elongation = 0.5 * std::log(C[0]);
      return 0.5 * (S[0] * E11 + S[4] * E22 + S[8] * E33) +
             2. * (S[1] * E12 + S[2] * E13 + S[5] * E23) * 0.5;
    }
  } // namespace FE
} // namespace YarnImpact
