#ifndef yarn_impact_fe_charmetant_law_h
#define yarn_impact_fe_charmetant_law_h

#include <yarn_impact/fe/parameters.h>
#include <yarn_impact/fe/simd.h>
#include <yarn_impact/mechanics/kinematics.h>

#include <cmath>

namespace YarnImpact
{
  namespace FE
  {
    /**
     * The revisited Charmetant law of the paper (Eq. 1-4, Table 1):
     * \f[
     *   W = \tfrac12 k_e I_e^2 + k_{tc}|I_{tc}|^p + \tfrac12 k_{td} I_{td}^2,
     * \f]
     * with the NaN-free evaluation of doc/theory.md section 1.4: the
     * distortion measure comes from the Schur complement of C on the
     * section plane, \f$I_{td} = \tfrac12\mathrm{asinh}(s)\f$, and never
     * from \f$\mathrm{acosh}\,\zeta\f$.
     */
    class CharmetantLaw
    {
    public:
      /** The force loop may call stress_kernel() with Double4 (the
       * constitutive-law contract, constitutive_law.h). */
      static constexpr bool vectorised = true;
      /** The energy is 1/2 k_e I_e^2 (k_e = axial_modulus()) plus terms of
       * the section alone, so the progressive failure law can damage the
       * fibre term by itself (constitutive_law.h, cell_kernel.h). */
      static constexpr bool separable_fibre_term = true;

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
      stress(const Mechanics::Matrix3 &F,
             Mechanics::Matrix3 &P,
             Mechanics::Invariants &inv) const;

      /**
       * Second Piola-Kirchhoff stress S = 2 dW/dC from the right
       * Cauchy-Green tensor (row-major, symmetric) and J = det F.
       * @return W [J/m^3]
       */
      double
      second_piola(const Mechanics::Matrix3 &C,
                   const double J,
                   Mechanics::Matrix3 &S,
                   Mechanics::Invariants &inv) const;

      /**
       * Energy density as a function of C, templated so that it can be
       * differentiated automatically (tests compare S with 2 dW/dC).
       * @param C right Cauchy-Green tensor (row-major)
       */
      template <typename Number>
      Number
      energy(const Number (&C)[9]) const;

      /**
       * The stress and energy evaluated for a scalar (V = double) or for
       * four Gauss points at once (V = internal::Double4): the same code,
       * so the unit tests of the scalar path cover the vector one.
       * @param F deformation gradient (row-major)
       * @param P first Piola-Kirchhoff stress [Pa] (output)
       * @param Ie, Itc, Itd the invariants (output)
       * @return W [J/m^3]
       */
      template <typename V>
      V
      stress_kernel(const V (&F)[9], V (&P)[9], V &Ie, V &Itc, V &Itd) const;

      /** Second Piola-Kirchhoff stress from C and J = det F, as
       * stress_kernel(). */
      template <typename V>
      V
      second_piola_kernel(const V (&C)[9],
                          const V J,
                          V (&S)[9],
                          V &Ie,
                          V &Itc,
                          V &Itd) const;

      /** Small-strain axial modulus k_e [Pa]. */
      double
      axial_modulus() const
      {
        return k_e;
      }

      /** Modulus of the transverse P wave at a compaction state,
       * \f$K_T(I_{tc}) + k_{td}/4\f$ with \f$K_T = p(p-1)k_{tc}/4
       * |I_{tc}|^{p-2}\f$ (doc/theory.md section 1.6), bounded at the
       * reference state by its value at |I_tc| = 1e-3 [Pa]. */
      double
      transverse_modulus(const Mechanics::Invariants &inv) const;

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
      bool resist_dilation;
    };


    // The kernels take and return Double4 by value; they are inline, so the
    // ABI note of GCC about AVX vectors does not apply.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
    template <typename V>
    inline V
    CharmetantLaw::second_piola_kernel(const V (&C)[9],
                                       const V J,
                                       V (&S)[9],
                                       V &Ie,
                                       V &Itc,
                                       V &Itd) const
    {
      using namespace internal;
      const V I4     = C[0];
      const V I1     = C[0] + C[4] + C[8];
      const V I5     = C[0] * C[0] + C[1] * C[1] + C[2] * C[2];
      const V I3     = J * J;
      const V inv_I4 = 1. / I4;
      const V inv_I3 = 1. / I3;

      // Inverse of C from its cofactors.
      const V Ci00 = (C[4] * C[8] - C[5] * C[5]) * inv_I3;
      const V Ci01 = (C[2] * C[5] - C[1] * C[8]) * inv_I3;
      const V Ci02 = (C[1] * C[5] - C[2] * C[4]) * inv_I3;
      const V Ci11 = (C[0] * C[8] - C[2] * C[2]) * inv_I3;
      const V Ci12 = (C[1] * C[2] - C[0] * C[5]) * inv_I3;
      const V Ci22 = (C[0] * C[4] - C[1] * C[1]) * inv_I3;

      const V log_I4 = lane_log(I4);
      Ie             = 0.5 * log_I4;
      Itc            = 0.5 * lane_log(J) - 0.25 * log_I4;
      // Without resistance to dilation only compaction (I_tc < 0) counts:
      // |min(I_tc, 0)| = (|I_tc| - I_tc) / 2.
      const V a_tc =
        resist_dilation ? lane_abs(Itc) : 0.5 * (lane_abs(Itc) - Itc);
      // |I_tc|^(p-1), computed once for the stress and the energy.
      const V pow_pm1 = lane_pow(a_tc, p - 1.);
      const V gp      = resist_dilation ? (p * k_tc) * pow_pm1 * lane_sign(Itc)
                                        : (-p * k_tc) * pow_pm1;

      // Distortion from the Schur complement of C on the section plane,
      // which stays accurate as s -> 0 (doc/theory.md section 1.4).
      const V t11 = C[4] - C[1] * C[1] * inv_I4;
      const V t22 = C[8] - C[2] * C[2] * inv_I4;
      const V t12 = C[5] - C[1] * C[2] * inv_I4;
      const V s2 =
        ((t11 - t22) * (t11 - t22) + 4. * t12 * t12) * (0.25 * I4 * inv_I3);
      const V s   = lane_sqrt(s2);
      const V psi = lane_asinh_ratio(s, s2);
      Itd         = 0.5 * s * psi;

      const V inv_2rt = 0.5 / (lane_abs(J) * lane_sqrt(I4));
      const V zeta    = (I1 * I4 - I5) * inv_2rt;
      const V half_z  = 0.5 * zeta;
      // d zeta / dC, entry by entry (M = e_x, CM = first column of C).
      const V dz00 = (I4 + I1 - 2. * C[0]) * inv_2rt - half_z * (Ci00 + inv_I4);
      const V dz01 = (-C[1]) * inv_2rt - half_z * Ci01;
      const V dz02 = (-C[2]) * inv_2rt - half_z * Ci02;
      const V dz11 = I4 * inv_2rt - half_z * Ci11;
      const V dz12 = -half_z * Ci12;
      const V dz22 = I4 * inv_2rt - half_z * Ci22;

      const V a = 0.5 * gp;
      const V b = (0.5 * k_td) * psi;
      S[0]      = k_e * Ie * inv_I4 + a * (Ci00 - inv_I4) + b * dz00;
      S[1] = S[3] = a * Ci01 + b * dz01;
      S[2] = S[6] = a * Ci02 + b * dz02;
      S[4]        = a * Ci11 + b * dz11;
      S[5] = S[7] = a * Ci12 + b * dz12;
      S[8]        = a * Ci22 + b * dz22;

      return 0.5 * k_e * Ie * Ie + k_tc * pow_pm1 * a_tc +
             0.5 * k_td * Itd * Itd;
    }


#pragma GCC diagnostic pop

    template <typename V>
    inline V
    CharmetantLaw::stress_kernel(const V (&F)[9],
                                 V (&P)[9],
                                 V &Ie,
                                 V &Itc,
                                 V &Itd) const
    {
      V C[9], S[9];
      const V J = Mechanics::right_cauchy_green(F, C);
      const V W = second_piola_kernel(C, J, S, Ie, Itc, Itd);
      Mechanics::first_piola(F, S, P);
      return W;
    }


    inline double
    CharmetantLaw::second_piola(const Mechanics::Matrix3 &C,
                                const double J,
                                Mechanics::Matrix3 &S,
                                Mechanics::Invariants &inv) const
    {
      return second_piola_kernel(C,
                                 J,
                                 S,
                                 inv.elongation,
                                 inv.compaction,
                                 inv.distortion);
    }


    inline double
    CharmetantLaw::stress(const Mechanics::Matrix3 &F,
                          Mechanics::Matrix3 &P,
                          Mechanics::Invariants &inv) const
    {
      return stress_kernel(F,
                           P,
                           inv.elongation,
                           inv.compaction,
                           inv.distortion);
    }


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
      const Number a_tc =
        resist_dilation ? Number(abs(Itc)) : Number(0.5 * (abs(Itc) - Itc));
      return 0.5 * k_e * Ie * Ie + k_tc * pow(a_tc, p) + 0.5 * k_td * Itd * Itd;
    }
  } // namespace FE
} // namespace YarnImpact

#endif
