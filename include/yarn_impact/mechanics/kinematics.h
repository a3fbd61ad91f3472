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
     * section 1.2), with the fibre direction M = e_x or, through a
     * FibreFrame, any other. Every FE law fills at least the elongation,
     * which drives the failure test. */
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

    /**
     * The fibre frame of a reference point: the orthonormal basis
     * (M, T1, T2) of the reference configuration, M the unit fibre
     * direction and T1, T2 spanning the section plane across it, stored as
     * the columns of the rotation R (row-major, R[3 i + j] = component i
     * of basis vector j). The laws are written in this frame, where the
     * fibre lies along its first axis; a law with fibre direction M
     * evaluates them at F R and returns P = P' R^T (doc/theory.md section
     * 1.8). Built by fibre_frame() from M alone.
     */
    using FibreFrame = Matrix3;

    /**
     * The fibre frame of the unit fibre direction @p M [-]: T1 is the
     * coordinate axis on which M has its smallest component (the first
     * such one), made orthogonal to M and unit, and T2 = M x T1. The laws
     * are transversely isotropic, so which pair spans the section plane
     * does not change their stress beyond round-off. The frame of e_x is
     * the identity exactly, so the straight yarn's numbers are the same on
     * either path.
     */
    void
    fibre_frame(const double (&M)[3], FibreFrame &R);

    /** The invariants of @p F (row-major) with the fibre frame @p R:
     * those of F R with the fibre along x (doc/theory.md section 1.8). */
    Invariants
    invariants(const Matrix3 &F, const FibreFrame &R);

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

    /** F R [-]: the deformation gradient @p F with the reference
     * configuration expressed in the fibre frame @p R, the argument of a
     * law written with its fibre along x (doc/theory.md section 1.8). */
    inline void
    to_fibre_frame(const Matrix3 &F, const FibreFrame &R, Matrix3 &FR)
    {
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          FR[3 * i + j] =
            F[3 * i] * R[j] + F[3 * i + 1] * R[3 + j] + F[3 * i + 2] * R[6 + j];
    }

    /** P = P' R^T [Pa]: a first Piola-Kirchhoff stress @p P_frame of a law
     * evaluated in the fibre frame @p R, back in the reference
     * configuration's axes. */
    inline void
    from_fibre_frame(const Matrix3 &P_frame, const FibreFrame &R, Matrix3 &P)
    {
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          P[3 * i + j] = P_frame[3 * i] * R[3 * j] +
                         P_frame[3 * i + 1] * R[3 * j + 1] +
                         P_frame[3 * i + 2] * R[3 * j + 2];
    }
  } // namespace Mechanics
} // namespace YarnImpact

#endif
