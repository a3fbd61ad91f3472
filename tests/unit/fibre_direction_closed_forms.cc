// A physics check of the FE laws with a fibre direction at any angle
// (doc/theory.md section 1.8): the closed forms of doc/theory.md section
// 1.5 (a)-(c), turned to the oblique fibre direction M = (1, 2, 2)/3 and a
// transverse pair that is not its fibre frame's: fibre tension (both
// laws), compaction and distortion of the section (Charmetant law), from
// the law's scalar path and from the cell kernel's virial stress on one
// distorted cell, to 1e-12 relative.

#include "fibre_direction.h"

using namespace FibreDirectionTest;

namespace
{
  /** The first Piola stress of a homogeneous deformation F of one cell
   * from the kernel's forces: the virial (1/V) sum_a f_a (x) X_a. */
  template <class Law>
  void
  kernel_stress(const Law &law,
                const Matrix3 &F,
                const double (&M)[3],
                Matrix3 &P)
  {
    const OneCell cell = make_cell(distorted_cube());
    double Ms[n_q][3], u[n_cell_dofs], f[n_cell_dofs], d;
    for (auto &m : Ms)
      std::copy(M, M + 3, m);
    for (unsigned int a = 0; a < n_nodes; ++a)
      {
        const double X[3] = {cell.X[a][0], cell.X[a][1], cell.X[a][2]};
        double x[3];
        rotate_vector(F, X, x);
        for (unsigned int i = 0; i < 3; ++i)
          u[3 * a + i] = x[i] - X[i];
      }
    kernel_forces(law, cell, Ms, true, u, FailureLaw(), f, d);
    double V = 0.;
    for (const double w : cell.JxW)
      V += w;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int k = 0; k < 3; ++k)
        {
          double s = 0.;
          for (unsigned int a = 0; a < n_nodes; ++a)
            s += f[3 * a + i] * cell.X[a][k];
          P[3 * i + k] = s / V;
        }
  }

  /** M.A.N for a row-major A. */
  double
  component(const Matrix3 &A, const double *m, const double *n)
  {
    double s = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        s += m[i] * A[3 * i + j] * n[j];
    return s;
  }

  /** Kirchhoff stress tau = P F^T. */
  void
  kirchhoff(const Matrix3 &P, const Matrix3 &F, Matrix3 &tau)
  {
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        tau[3 * i + j] = P[3 * i] * F[3 * j] + P[3 * i + 1] * F[3 * j + 1] +
                         P[3 * i + 2] * F[3 * j + 2];
  }

  /** F = a M (x) M + b T1 (x) T1 + c T2 (x) T2 for the orthonormal triad
   * (M, T1, T2). */
  void
  principal(const double *M,
            const double *T1,
            const double *T2,
            const double a,
            const double b,
            const double c,
            Matrix3 &F)
  {
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        F[3 * i + j] = a * M[i] * M[j] + b * T1[i] * T1[j] + c * T2[i] * T2[j];
  }

  /** The closed forms of doc/theory.md section 1.5 (a)-(c) along the
   * oblique fibre direction M = (1, 2, 2)/3 and a transverse pair that is
   * not the one of its fibre frame, from the law and from the kernel. */
  void
  check_oblique_closed_forms()
  {
    const CharmetantParameters k;
    const CharmetantLaw law(k, 1267.);
    const LinearTransverselyIsotropicLaw linear(LinearParameters(), 1267.);
    const double M[3] = {1. / 3., 2. / 3., 2. / 3.};
    const double c = std::cos(0.7), s = std::sin(0.7);
    // A, B: an orthonormal pair across M, turned by 0.7 rad about it.
    const double A[3]  = {2. / 3., 1. / 3., -2. / 3.};
    const double B[3]  = {2. / 3., -2. / 3., 1. / 3.};
    const double T1[3] = {c * A[0] + s * B[0],
                          c * A[1] + s * B[1],
                          c * A[2] + s * B[2]};
    const double T2[3] = {-s * A[0] + c * B[0],
                          -s * A[1] + c * B[1],
                          -s * A[2] + c * B[2]};
    Matrix3 F, P, P_kernel, tau;
    Invariants inv;
    char name[80];

    std::printf("closed forms along M = (1, 2, 2)/3 [MPa]\n");
    {
      const double l = 1.0452;
      principal(M, T1, T2, l, 1., 1., F);
      stress_along(law, F, M, P, inv);
      kernel_stress(law, F, M, P_kernel);
      const double P_MM = k.k_e * std::log(l) / l;
      check("(a) fibre tension: M.P.M",
            1e-6 * component(P, M, M),
            1e-6 * P_MM,
            1e-12);
      check("(a) the same from the kernel",
            1e-6 * component(P_kernel, M, M),
            1e-6 * P_MM,
            1e-12);
      check("(a) M.P.M (doc/theory.md 1.5)",
            1e-6 * component(P, M, M),
            3386.98,
            2e-6);
      const double off = std::max({std::abs(component(P, T1, T1)),
                                   std::abs(component(P, T2, T2)),
                                   std::abs(component(P, M, T1)),
                                   std::abs(component(P, T1, T2))});
      report("(a) other components / M.P.M", off / P_MM, 1e-12);
      // The linear law's fibre stress E_L (eps + eps^2/2)(1 + eps).
      stress_along(linear, F, M, P, inv);
      kernel_stress(linear, F, M, P_kernel);
      const double lin = linear.uniaxial_nominal_stress(l - 1.);
      check("(a) linear law: M.P.M",
            1e-6 * component(P, M, M),
            1e-6 * lin,
            1e-12);
      check("(a) linear law, from the kernel",
            1e-6 * component(P_kernel, M, M),
            1e-6 * lin,
            1e-12);
    }
    for (const double l : {0.95, 0.80})
      {
        principal(M, T1, T2, 1., l, l, F);
        stress_along(law, F, M, P, inv);
        kirchhoff(P, F, tau);
        const double gp = -k.p * k.k_tc * std::pow(-std::log(l), k.p - 1.);
        std::snprintf(name, sizeof(name), "(b) compaction %.2f: T1.tau.T1", l);
        check(name, 1e-6 * component(tau, T1, T1), 1e-6 * 0.5 * gp, 1e-12);
        std::snprintf(name, sizeof(name), "(b) compaction %.2f: T2.tau.T2", l);
        check(name, 1e-6 * component(tau, T2, T2), 1e-6 * 0.5 * gp, 1e-12);
        kernel_stress(law, F, M, P_kernel);
        kirchhoff(P_kernel, F, tau);
        std::snprintf(name, sizeof(name), "(b) %.2f from the kernel", l);
        check(name, 1e-6 * component(tau, T1, T1), 1e-6 * 0.5 * gp, 1e-12);
      }
    for (const double l : {1.01, 1.3})
      {
        principal(M, T1, T2, 1., l, 1. / l, F);
        stress_along(law, F, M, P, inv);
        kirchhoff(P, F, tau);
        const double t = 0.5 * k.k_td * std::log(l);
        std::snprintf(name, sizeof(name), "(c) distortion %.2f: T1.tau.T1", l);
        check(name, 1e-6 * component(tau, T1, T1), 1e-6 * t, 1e-12);
        std::snprintf(name, sizeof(name), "(c) distortion %.2f: T2.tau.T2", l);
        check(name, 1e-6 * component(tau, T2, T2), -1e-6 * t, 1e-12);
        kernel_stress(law, F, M, P_kernel);
        kirchhoff(P_kernel, F, tau);
        std::snprintf(name, sizeof(name), "(c) %.2f from the kernel", l);
        check(name, 1e-6 * component(tau, T1, T1), 1e-6 * t, 1e-12);
      }
  }
} // namespace

int
main()
{
  check_oblique_closed_forms();
}
