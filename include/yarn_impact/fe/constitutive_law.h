#ifndef yarn_impact_fe_constitutive_law_h
#define yarn_impact_fe_constitutive_law_h

#include <yarn_impact/fe/parameters.h>

#include <cmath>

namespace YarnImpact
{
  namespace FE
  {
    /**
     * A 3x3 matrix stored row by row, F[3*i + j] = F_ij. The laws work on
     * plain arrays so that the hot loop of the FE model stays free of
     * temporaries; deal.II tensors are used around it.
     */
    using Matrix3 = double[9];

    /** The three physical invariants of the Charmetant law (physics.md
     * section 1.2), fibre direction M = e_x. */
    struct Invariants
    {
      /** Fibre elongation \f$I_e = \ln\lambda_f\f$ [-]. */
      double elongation = 0.;
      /** Transverse compaction \f$I_{tc} = \tfrac14\ln(I_3/I_4)\f$ [-]. */
      double compaction = 0.;
      /** Transverse distortion \f$I_{td} = \tfrac12\,\mathrm{asinh}(s)\f$
       * [-]. */
      double distortion = 0.;
    };

    /**
     * The revisited Charmetant law of the paper (Eq. 1-4, Table 1):
     * \f[
     *   W = \tfrac12 k_e I_e^2 + k_{tc}|I_{tc}|^p + \tfrac12 k_{td} I_{td}^2,
     * \f]
     * with the NaN-free evaluation of physics.md section 1.5: the distortion
     * measure comes from the Schur complement of C on the section plane,
     * \f$I_{td} = \tfrac12\mathrm{asinh}(s)\f$, and never from
     * \f$\mathrm{acosh}\,\zeta\f$.
     */
    class CharmetantLaw
    {
    public:
      /** @param parameters the moduli @param density [kg/m^3] */
      CharmetantLaw(const CharmetantParameters &parameters,
                    const double density);

      /**
       * First Piola-Kirchhoff stress and energy density.
       * @param F deformation gradient (row-major)
       * @param P first Piola-Kirchhoff stress [Pa] (output, row-major)
       * @param inv invariants (output)
       * @return strain energy density W [J/m^3]
       */
      double
      stress(const Matrix3 &F, Matrix3 &P, Invariants &inv) const;

      /**
       * Second Piola-Kirchhoff stress S = 2 dW/dC from the right
       * Cauchy-Green tensor (row-major, symmetric) and J = det F.
       * @return W [J/m^3]
       */
      double
      second_piola(const Matrix3 &C,
                   const double J,
                   Matrix3 &S,
                   Invariants &inv) const;

      /**
       * Energy density as a function of C, templated so that it can be
       * differentiated automatically (tests compare S with 2 dW/dC).
       * @param C right Cauchy-Green tensor (row-major)
       */
      template <typename Number>
      Number
      energy(const Number (&C)[9]) const;

      /** Small-strain axial modulus k_e [Pa]. */
      double
      axial_modulus() const
      {
        return k_e;
      }

      /** Modulus of the transverse P wave at a compaction state,
       * \f$K_T(I_{tc}) + k_{td}/4\f$ with \f$K_T = p(p-1)k_{tc}/4
       * |I_{tc}|^{p-2}\f$ (physics.md section 1.8), bounded at the
       * reference state by its value at |I_tc| = 1e-3 [Pa]. */
      double
      transverse_modulus(const Invariants &inv) const;

      /** Uniaxial nominal stress \f$P(\varepsilon) = k_e
       * \ln(1+\varepsilon)/(1+\varepsilon)\f$ [Pa]. */
      double
      uniaxial_nominal_stress(const double strain) const
      {
        return k_e * std::log1p(strain) / (1. + strain);
      }

      /** Density [kg/m^3]. */
      double density;

    private:
      double k_e, k_tc, p, k_td;
    };


    /**
     * The classical linear transversely isotropic yarn law, fibre direction
     * x, in St. Venant-Kirchhoff form: \f$S = \mathbb{C} : E\f$ with the
     * Green-Lagrange strain E. With the default null Poisson ratios the
     * section does not react to axial strain: the paper's point.
     */
    class LinearTransverselyIsotropicLaw
    {
    public:
      /** @param parameters the moduli @param density [kg/m^3] */
      LinearTransverselyIsotropicLaw(const LinearParameters &parameters,
                                     const double density);

      /** First Piola-Kirchhoff stress and energy density, as
       * CharmetantLaw::stress(); the invariants are filled too. */
      double
      stress(const Matrix3 &F, Matrix3 &P, Invariants &inv) const;

      /** Axial P-wave modulus \f$\mathbb{C}_{1111}\f$ [Pa]. */
      double
      axial_modulus() const
      {
        return C11;
      }

      /** Transverse P-wave modulus \f$\mathbb{C}_{2222}\f$ [Pa]. */
      double
      transverse_modulus(const Invariants &) const
      {
        return C22;
      }

      /** Uniaxial nominal stress of the SVK bar under free lateral
       * contraction, \f$P = E_L (\varepsilon + \varepsilon^2/2)
       * (1+\varepsilon)\f$ [Pa] (exact for null Poisson ratios). */
      double
      uniaxial_nominal_stress(const double strain) const
      {
        return E_L * (strain + 0.5 * strain * strain) * (1. + strain);
      }

      /** Density [kg/m^3]. */
      double density;

    private:
      double E_L;
      /** Stiffness in Voigt form (x = 1, y = 2, z = 3). */
      double C11, C12, C22, C23, G12, G23;
    };

    namespace internal
    {
      /** C = F^T F (row-major, symmetric) and J = det F. */
      inline double
      right_cauchy_green(const Matrix3 &F, Matrix3 &C)
      {
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            {
              const double c =
                F[i] * F[j] + F[3 + i] * F[3 + j] + F[6 + i] * F[6 + j];
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
    } // namespace internal


    inline double
    CharmetantLaw::second_piola(const Matrix3 &C,
                                const double J,
                                Matrix3 &S,
                                Invariants &inv) const
    {
      const double I4     = C[0];
      const double I1     = C[0] + C[4] + C[8];
      const double I5     = C[0] * C[0] + C[1] * C[1] + C[2] * C[2];
      const double I3     = J * J;
      const double inv_I4 = 1. / I4;
      const double inv_I3 = 1. / I3;

      // Inverse of C from its cofactors.
      const double Ci00 = (C[4] * C[8] - C[5] * C[5]) * inv_I3;
      const double Ci01 = (C[2] * C[5] - C[1] * C[8]) * inv_I3;
      const double Ci02 = (C[1] * C[5] - C[2] * C[4]) * inv_I3;
      const double Ci11 = (C[0] * C[8] - C[2] * C[2]) * inv_I3;
      const double Ci12 = (C[1] * C[2] - C[0] * C[5]) * inv_I3;
      const double Ci22 = (C[0] * C[4] - C[1] * C[1]) * inv_I3;

      const double log_I4 = std::log(I4);
      const double Ie     = 0.5 * log_I4;
      const double Itc    = 0.5 * std::log(J) - 0.25 * log_I4;
      const double a_tc   = std::abs(Itc);
      // |I_tc|^(p-1), computed once for the stress and the energy.
      const double pow_pm1 = (a_tc > 0. ? std::pow(a_tc, p - 1.) : 0.);
      const double gp      = p * k_tc * pow_pm1 * (Itc >= 0. ? 1. : -1.);

      // Distortion from the Schur complement of C on the section plane,
      // which stays accurate as s -> 0 (physics.md section 1.5).
      const double t11 = C[4] - C[1] * C[1] * inv_I4;
      const double t22 = C[8] - C[2] * C[2] * inv_I4;
      const double t12 = C[5] - C[1] * C[2] * inv_I4;
      const double s2 =
        ((t11 - t22) * (t11 - t22) + 4. * t12 * t12) * (0.25 * I4 * inv_I3);
      const double s = std::sqrt(s2);
      // psi = asinh(s)/s: its Taylor series in s^2 up to s^16 is exact to
      // round-off for s < 0.1 (the usual range) and needs no division.
      const double psi =
        (s < 0.1 ?
           1. +
             s2 * (-1. / 6. +
                   s2 * (3. / 40. +
                         s2 * (-5. / 112. +
                               s2 * (35. / 1152. +
                                     s2 * (-63. / 2816. +
                                           s2 * (231. / 13312. +
                                                 s2 * (-143. / 10240. +
                                                       s2 * 6435. /
                                                         557056.))))))) :
           std::asinh(s) / s);
      const double u = s * psi;

      const double inv_2rt = 0.5 / (std::abs(J) * std::sqrt(I4));
      const double zeta    = (I1 * I4 - I5) * inv_2rt;
      const double half_z  = 0.5 * zeta;
      // d zeta / dC, entry by entry (M = e_x, CM = first column of C).
      const double dz00 =
        (I4 + I1 - 2. * C[0]) * inv_2rt - half_z * (Ci00 + inv_I4);
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


    inline double
    CharmetantLaw::stress(const Matrix3 &F, Matrix3 &P, Invariants &inv) const
    {
      Matrix3 C, S;
      const double J = internal::right_cauchy_green(F, C);
      const double W = second_piola(C, J, S, inv);
      internal::first_piola(F, S, P);
      return W;
    }


    /** Compute the invariants of the Charmetant law from F (row-major). */
    Invariants
    charmetant_invariants(const Matrix3 &F);


    template <typename Number>
    Number
    CharmetantLaw::energy(const Number (&C)[9]) const
    {
      using std::abs;
      using std::asinh;
      using std::log;
      using std::pow;
      using std::sqrt;
      // Symmetric parts, so that d/dC_ij of this expression is the
      // derivative with respect to a symmetric tensor.
      const Number c00 = C[0], c11 = C[4], c22 = C[8];
      const Number c01 = 0.5 * (C[1] + C[3]);
      const Number c02 = 0.5 * (C[2] + C[6]);
      const Number c12 = 0.5 * (C[5] + C[7]);
      const Number I4  = c00;
      const Number I3  = c00 * (c11 * c22 - c12 * c12) -
                        c01 * (c01 * c22 - c12 * c02) +
                        c02 * (c01 * c12 - c11 * c02);
      const Number Ie  = 0.5 * log(I4);
      const Number Itc = 0.25 * log(I3 / I4);
      const Number t11 = c11 - c01 * c01 / I4;
      const Number t22 = c22 - c02 * c02 / I4;
      const Number t12 = c12 - c01 * c02 / I4;
      const Number s2 =
        ((t11 - t22) * (t11 - t22) + 4. * t12 * t12) / (4. * I3 / I4);
      const Number Itd = 0.5 * asinh(sqrt(s2));
      return 0.5 * k_e * Ie * Ie + k_tc * pow(abs(Itc), p) +
             0.5 * k_td * Itd * Itd;
    }
  } // namespace FE
} // namespace YarnImpact

#endif
