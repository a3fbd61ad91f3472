// A physics check of the FE laws with a fibre direction M at any angle
// (doc/theory.md section 1.8), on the law's scalar path and on the cell
// kernel (four Gauss points per SIMD vector for the Charmetant law, one at
// a time for the linear law):
//
// - objectivity and material symmetry: with random rotations Q, random
//   deformations F and random fibre directions M, a law with fibre
//   direction Q M at Q F Q^T gives the stress Q P(F) Q^T and the same
//   energy as the law with M at F, to 1e-12 relative; on a distorted cell
//   whose Gauss points each have their own fibre direction, the rotated
//   cell's nodal forces are Q f and its energy and damage the same;
// - the kernel's forces against the scalar path's, Gauss point by Gauss
//   point, and the frame of M = e_x as the straight yarn's path, bit for
//   bit;
// - Mechanics::invariants(F, R) with the fibre frame of M against the
//   law's invariants.
// The closed forms along an oblique M are in fibre_direction_closed_forms.cc.

#include "fibre_direction.h"

#include <type_traits>

using namespace FibreDirectionTest;

namespace
{
  /** The linear law with Poisson ratios, so that its stiffness couples
   * the fibre to the section and the check has something to rotate. */
  LinearTransverselyIsotropicLaw
  coupled_linear_law()
  {
    LinearParameters p;
    p.E_T   = 5e9;
    p.G_LT  = 2e9;
    p.nu_LT = 0.3;
    p.nu_TT = 0.4;
    return LinearTransverselyIsotropicLaw(p, 1267.);
  }

  template <class Law>
  void
  check_law_symmetry(const Law &law, const char *name)
  {
    double worst_P = 0., worst_W = 0., worst_inv = 0., worst_kin = 0.;
    for (unsigned int sample = 0; sample < 200; ++sample)
      {
        Matrix3 Q, F, QFQ, P, QPQ, P_rotated;
        double M[3], QM[3];
        random_rotation(Q);
        random_direction(M);
        rotate_vector(Q, M, QM);
        for (unsigned int i = 0; i < 9; ++i)
          F[i] = (i % 4 == 0 ? 1. : 0.) + uniform(-0.2, 0.2);
        rotate(Q, F, QFQ);
        Invariants inv, inv_rotated;
        const double W = stress_along(law, F, M, P, inv);
        const double W_rotated =
          stress_along(law, QFQ, QM, P_rotated, inv_rotated);
        rotate(Q, P, QPQ);
        worst_P = std::max(worst_P, difference(P_rotated, QPQ, 9));
        worst_W = std::max(worst_W, relative(W_rotated, W));
        // The invariants are logarithmic strains, zero at rest: compared
        // by their difference.
        worst_inv =
          std::max({worst_inv,
                    std::abs(inv_rotated.elongation - inv.elongation),
                    std::abs(inv_rotated.compaction - inv.compaction),
                    std::abs(inv_rotated.distortion - inv.distortion)});
        // The kinematics' own invariants with the fibre frame of M (what
        // the DEM's measurements use) against the law's.
        Matrix3 R;
        YarnImpact::Mechanics::fibre_frame(M, R);
        const Invariants kin = YarnImpact::Mechanics::invariants(F, R);
        worst_kin =
          std::max(worst_kin, std::abs(kin.elongation - inv.elongation));
        if constexpr (std::is_same_v<Law, CharmetantLaw>)
          worst_kin = std::max({worst_kin,
                                std::abs(kin.compaction - inv.compaction),
                                std::abs(kin.distortion - inv.distortion)});
      }
    std::printf("%s: 200 random (Q, F, M)\n", name);
    report("P(Q F Q^T; Q M) = Q P(F; M) Q^T", worst_P, 1e-12);
    report("W(Q F Q^T; Q M) = W(F; M)", worst_W, 1e-12);
    report("the same invariants (difference)", worst_inv, 1e-13);
    report("Mechanics::invariants(F, R) = the law's", worst_kin, 1e-13);
  }

  /** The same forces from the law's scalar path, Gauss point by Gauss
   * point, in the global frame (no damage). */
  template <class Law>
  double
  scalar_forces(const Law &law,
                const OneCell &cell,
                const double (&M)[n_q][3],
                const double (&u)[n_cell_dofs],
                double (&f)[n_cell_dofs])
  {
    double energy = 0.;
    std::fill(f, f + n_cell_dofs, 0.);
    for (unsigned int q = 0; q < n_q; ++q)
      {
        Matrix3 F = {1, 0, 0, 0, 1, 0, 0, 0, 1}, P;
        for (unsigned int a = 0; a < n_nodes; ++a)
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              F[3 * i + j] += u[3 * a + i] * cell.g[q][a][j];
        Invariants inv;
        energy += stress_along(law, F, M[q], P, inv) * cell.JxW[q];
        for (unsigned int a = 0; a < n_nodes; ++a)
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              f[3 * a + i] += P[3 * i + j] * cell.g[q][a][j] * cell.JxW[q];
      }
    return energy;
  }

  template <class Law>
  void
  check_kernel_symmetry(const Law &law,
                        const char *name,
                        const FailureLaw &failure,
                        const double fibre_stretch)
  {
    double worst_f = 0., worst_W = 0., worst_d = 0., worst_scalar = 0.,
           smallest_d = 1., largest_d = 0.;
    bool bitwise = true;
    for (unsigned int sample = 0; sample < 20; ++sample)
      {
        const OneCell cell = make_cell(distorted_cube());
        Matrix3 Q, F;
        random_rotation(Q);
        double M[n_q][3], QM[n_q][3], base[3];
        random_direction(base);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            // Directions that differ from Gauss point to Gauss point, as
            // along a curved centreline.
            double n = 0.;
            for (unsigned int d = 0; d < 3; ++d)
              {
                M[q][d] = base[d] + uniform(-0.2, 0.2);
                n += M[q][d] * M[q][d];
              }
            for (double &c : M[q])
              c /= std::sqrt(n);
            rotate_vector(Q, M[q], QM[q]);
          }
        // A homogeneous deformation, with a stretch along the mean fibre
        // direction for the damage, plus a nodal perturbation: the Gauss
        // points see different F.
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            F[3 * i + j] = (i == j ? 1. : 0.) + uniform(-0.05, 0.05) +
                           (fibre_stretch - 1.) * base[i] * base[j];
        std::vector<dealii::Point<3>> QX(n_nodes);
        double u[n_cell_dofs], Qu[n_cell_dofs];
        for (unsigned int a = 0; a < n_nodes; ++a)
          {
            double x[3];
            const double X[3] = {cell.X[a][0], cell.X[a][1], cell.X[a][2]};
            rotate_vector(F, X, x);
            for (unsigned int d = 0; d < 3; ++d)
              u[3 * a + d] = x[d] - X[d] + 1e-6 * uniform(-1., 1.);
            double QX_a[3];
            rotate_vector(Q, X, QX_a);
            QX[a] = dealii::Point<3>(QX_a[0], QX_a[1], QX_a[2]);
            rotate_vector(Q, &u[3 * a], &Qu[3 * a]);
          }
        const OneCell rotated = make_cell(QX);
        double f[n_cell_dofs], f_rotated[n_cell_dofs], Qf[n_cell_dofs];
        double d, d_rotated;
        const double W = kernel_forces(law, cell, M, true, u, failure, f, d);
        const double W_rotated = kernel_forces(law,
                                               rotated,
                                               QM,
                                               true,
                                               Qu,
                                               failure,
                                               f_rotated,
                                               d_rotated);
        for (unsigned int a = 0; a < n_nodes; ++a)
          rotate_vector(Q, &f[3 * a], &Qf[3 * a]);
        worst_f = std::max(worst_f, difference(f_rotated, Qf, n_cell_dofs));
        worst_W = std::max(worst_W, relative(W_rotated, W));
        if (failure.kind == FailureLaw::Kind::progressive)
          {
            worst_d    = std::max(worst_d, relative(d_rotated, d));
            smallest_d = std::min(smallest_d, d);
            largest_d  = std::max(largest_d, d);
          }
        else
          {
            double f_scalar[n_cell_dofs];
            const double W_scalar = scalar_forces(law, cell, M, u, f_scalar);
            worst_scalar          = std::max({worst_scalar,
                                              difference(f, f_scalar, n_cell_dofs),
                                              relative(W, W_scalar)});
          }

        // The frame of e_x at every Gauss point against the straight
        // yarn's layout (no frames): the same numbers, bit for bit.
        double ex[n_q][3], f_frames[n_cell_dofs], f_straight[n_cell_dofs];
        for (auto &m : ex)
          m[0] = 1., m[1] = m[2] = 0.;
        const double W_frames =
          kernel_forces(law, cell, ex, true, u, failure, f_frames, d);
        const double W_straight =
          kernel_forces(law, cell, ex, false, u, failure, f_straight, d);
        bitwise = bitwise && W_frames == W_straight &&
                  std::equal(f_frames, f_frames + n_cell_dofs, f_straight);
      }
    std::printf("%s: cell kernel, 20 distorted cells, a fibre direction "
                "per Gauss point\n",
                name);
    report("rotated cell: forces Q f", worst_f, 1e-12);
    report("rotated cell: the same energy", worst_W, 1e-12);
    if (failure.kind == FailureLaw::Kind::progressive)
      {
        report("rotated cell: the same damage", worst_d, 1e-12);
        std::printf("  %-52s %s\n",
                    "damage between 0.05 and 0.95",
                    smallest_d > 0.05 && largest_d < 0.95 ? "OK" : "WRONG");
      }
    else
      report("kernel against the scalar path", worst_scalar, 1e-12);
    std::printf("  %-52s %s\n",
                "frames of e_x = the straight layout, bit for bit",
                bitwise ? "OK" : "WRONG");
  }
} // namespace

int
main()
{
  {
    // The frame of e_x must be the identity exactly: the straight yarn's
    // numbers do not change whichever path it takes.
    const double ex[3] = {1., 0., 0.};
    Matrix3 R;
    YarnImpact::Mechanics::fibre_frame(ex, R);
    const Matrix3 I = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    std::printf("fibre frame of e_x is the identity: %s\n",
                std::equal(R, R + 9, I) ? "OK" : "WRONG");
  }
  check_law_symmetry(CharmetantLaw(CharmetantParameters(), 1267.),
                     "Charmetant law, scalar path");
  check_law_symmetry(coupled_linear_law(),
                     "Linear law with Poisson ratios, scalar path");

  check_kernel_symmetry(CharmetantLaw(CharmetantParameters(), 1267.),
                        "Charmetant law, SIMD lanes",
                        FailureLaw(),
                        1.);
  check_kernel_symmetry(coupled_linear_law(),
                        "Linear law with Poisson ratios, one point at a time",
                        FailureLaw(),
                        1.);
  FailureLaw progressive;
  progressive.kind              = FailureLaw::Kind::progressive;
  progressive.onset_log_stretch = std::log1p(0.0347);
  progressive.fracture_energy   = 5.41e4;
  progressive.fibre_modulus     = CharmetantParameters().k_e;
  check_kernel_symmetry(CharmetantLaw(CharmetantParameters(), 1267.),
                        "Charmetant law, SIMD lanes, progressive damage",
                        progressive,
                        1.08);
}
