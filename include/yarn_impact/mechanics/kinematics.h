#ifndef yarn_impact_mechanics_kinematics_h
#define yarn_impact_mechanics_kinematics_h

namespace YarnImpact
{
  /**
   * The continuum kinematics both models measure with: the FE's laws
   * compute their stress from it, and the DEM's elementary tests report the
   * periodic segment's affine deformation in the same invariants, so that
   * the identification compares like with like (doc/identification.md).
   * It includes no model.
   */
  namespace Mechanics
  {
    /**
     * A 3x3 matrix stored row by row, F[3*i + j] = F_ij. The laws work on
     * plain arrays so that the hot loop of the FE model stays free of
     * temporaries; deal.II tensors are used around it.
     */
    using Matrix3 = double[9];

    /** The three physical invariants of the Charmetant law (doc/theory.md
     * section 1.2), fibre direction M = e_x. Every FE law fills at least
     * the elongation, which drives the failure test. */
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

    /** The invariants of a deformation gradient @p F (row-major, fibre
     * direction x), with the NaN-free distortion of doc/theory.md section
     * 1.4. */
    Invariants
    invariants(const Matrix3 &F);

    // Double4 results are returned by value from inline functions: GCC's
    // ABI note about AVX vectors does not apply.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

    // Tensor operations on row-major 3x3 arrays, templates so that the FE
    // evaluates them on double and on four Gauss points at once
    // (FE::internal::Double4) with one body.

    /** det F of a row-major 3x3 matrix. */
    template <typename V>
    inline V
    determinant(const V (&F)[9])
    {
      return F[0] * (F[4] * F[8] - F[5] * F[7]) -
             F[1] * (F[3] * F[8] - F[5] * F[6]) +
             F[2] * (F[3] * F[7] - F[4] * F[6]);
    }

    /** C = F^T F (row-major, symmetric); returns J = det F. */
    template <typename V>
    inline V
    right_cauchy_green(const V (&F)[9], V (&C)[9])
    {
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          {
            const V c = F[i] * F[j] + F[3 + i] * F[3 + j] + F[6 + i] * F[6 + j];
            C[3 * i + j] = c;
            C[3 * j + i] = c;
          }
      return determinant(F);
    }

    /** P = F S for a symmetric S. */
    template <typename V>
    inline void
    first_piola(const V (&F)[9], const V (&S)[9], V (&P)[9])
    {
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          P[3 * i + j] =
            F[3 * i] * S[j] + F[3 * i + 1] * S[3 + j] + F[3 * i + 2] * S[6 + j];
    }
#pragma GCC diagnostic pop
  } // namespace Mechanics
} // namespace YarnImpact

#endif
