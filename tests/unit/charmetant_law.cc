// The Charmetant law against the closed forms of doc/theory.md section 1.5
// (a)-(e), its stress against the derivative of W by automatic
// differentiation (Sacado) at random deformations, and its finiteness and
// symmetry at exactly transversely isotropic states.

#include <yarn_impact/fe/constitutive_law.h>

#include <Sacado.hpp>

#include <cmath>
#include <cstdio>
#include <random>

using namespace YarnImpact::FE;
using YarnImpact::Mechanics::Invariants;
using YarnImpact::Mechanics::Matrix3;

namespace
{
  CharmetantLaw
  paper_law()
  {
    return CharmetantLaw(CharmetantParameters(), 1267.);
  }

  /** Kirchhoff stress tau = P F^T [MPa]. */
  void
  kirchhoff(const Matrix3 &F, Matrix3 &tau, double &W)
  {
    Matrix3 P;
    Invariants inv;
    W = paper_law().stress(F, P, inv);
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        tau[3 * i + j] =
          1e-6 * (P[3 * i] * F[3 * j] + P[3 * i + 1] * F[3 * j + 1] +
                  P[3 * i + 2] * F[3 * j + 2]);
  }

  double
  relative(const double value, const double reference)
  {
    return std::abs(value - reference) / std::abs(reference);
  }

  void
  check(const char *name,
        const double value,
        const double reference,
        const double tolerance)
  {
    const double e = relative(value, reference);
    std::printf("%-34s %12.6f  reference %12.6f  %s\n",
                name,
                value,
                reference,
                e <= tolerance ? "OK" : "WRONG");
  }

  void
  diag(Matrix3 &F, const double a, const double b, const double c)
  {
    for (double &f : F)
      f = 0.;
    F[0] = a;
    F[4] = b;
    F[8] = c;
  }
} // namespace

int
main()
{
  const CharmetantParameters k;
  Matrix3 F, tau;
  double W;

  std::printf("(a) fibre tension, F = diag(1.0452, 1, 1) [MPa]\n");
  {
    const double l = 1.0452;
    diag(F, l, 1., 1.);
    Matrix3 P;
    Invariants inv;
    paper_law().stress(F, P, inv);
    check("P11", 1e-6 * P[0], 1e-6 * k.k_e * std::log(l) / l, 1e-10);
    check("P11 (doc/theory.md 1.5)", 1e-6 * P[0], 3386.98, 2e-6);
    kirchhoff(F, tau, W);
    check("tau11", tau[0], 1e-6 * k.k_e * std::log(l), 1e-10);
    std::printf("%-34s %12.3e\n",
                "|tau22| + |tau33|",
                std::abs(tau[4]) + std::abs(tau[8]));
  }

  std::printf("(b) equibiaxial compaction, F = diag(1, l, l) [MPa]\n");
  for (const double l : {0.95, 0.90, 0.80})
    {
      diag(F, 1., l, l);
      kirchhoff(F, tau, W);
      const double I  = std::log(l);
      const double gp = -k.p * k.k_tc * std::pow(-I, k.p - 1.);
      char name[64];
      std::snprintf(name, sizeof(name), "tau22 at l = %.2f", l);
      check(name, tau[4], 1e-6 * 0.5 * gp, 1e-10);
      std::snprintf(name, sizeof(name), "tau33 at l = %.2f", l);
      check(name, tau[8], 1e-6 * 0.5 * gp, 1e-10);
    }

  std::printf("(c) isochoric distortion, F = diag(1, l, 1/l) [MPa]\n");
  for (const double l : {1.01, 1.1, 1.3})
    {
      diag(F, 1., l, 1. / l);
      kirchhoff(F, tau, W);
      char name[64];
      std::snprintf(name, sizeof(name), "tau22 at l = %.2f", l);
      check(name, tau[4], 1e-6 * 0.5 * k.k_td * std::log(l), 1e-10);
      std::snprintf(name, sizeof(name), "tau33 at l = %.2f", l);
      check(name, tau[8], -1e-6 * 0.5 * k.k_td * std::log(l), 1e-10);
    }

  std::printf("(d) uniaxial transverse strain, F = diag(1, l, 1) [MPa]\n");
  for (const double l : {0.95, 0.90, 0.80})
    {
      diag(F, 1., l, 1.);
      kirchhoff(F, tau, W);
      const double I  = 0.5 * std::log(l);
      const double gp = -k.p * k.k_tc * std::pow(-I, k.p - 1.);
      char name[64];
      std::snprintf(name, sizeof(name), "tau22 at l = %.2f", l);
      check(name,
            tau[4],
            1e-6 * (0.5 * gp + 0.25 * k.k_td * std::log(l)),
            1e-10);
      std::snprintf(name, sizeof(name), "tau33 at l = %.2f", l);
      check(name,
            tau[8],
            1e-6 * (0.5 * gp - 0.25 * k.k_td * std::log(l)),
            1e-10);
    }

  std::printf("(e) longitudinal shear F = I + 0.2 e1 (x) e2\n");
  {
    diag(F, 1., 1., 1.);
    F[1] = 0.2;
    kirchhoff(F, tau, W);
    double max_tau = 0.;
    for (const double t : tau)
      max_tau = std::max(max_tau, std::abs(t));
    std::printf("%-34s %12.3e  %s\n",
                "W [J/m^3] + max |tau| [MPa]",
                std::abs(W) + max_tau,
                std::abs(W) < 1e-6 && max_tau < 1e-12 ? "OK" : "WRONG");
  }

  std::printf("stress against 2 dW/dC by automatic differentiation\n");
  {
    using AD = Sacado::Fad::DFad<double>;
    std::mt19937 generator(42);
    std::uniform_real_distribution<double> noise(-0.15, 0.15);
    double worst = 0.;
    for (unsigned int sample = 0; sample < 20; ++sample)
      {
        for (unsigned int i = 0; i < 9; ++i)
          F[i] = (i % 4 == 0 ? 1. : 0.) + noise(generator);
        Matrix3 C;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            C[3 * i + j] =
              F[i] * F[j] + F[3 + i] * F[3 + j] + F[6 + i] * F[6 + j];
        AD C_ad[9];
        for (unsigned int i = 0; i < 9; ++i)
          C_ad[i] = AD(9, i, C[i]);
        const CharmetantLaw law = paper_law();
        const AD W_ad           = law.energy(C_ad);
        Matrix3 S;
        Invariants inv;
        const double J = F[0] * (F[4] * F[8] - F[5] * F[7]) -
                         F[1] * (F[3] * F[8] - F[5] * F[6]) +
                         F[2] * (F[3] * F[7] - F[4] * F[6]);
        const double W_law = law.second_piola(C, J, S, inv);
        double norm = 0., diff = 0.;
        for (unsigned int i = 0; i < 9; ++i)
          {
            norm = std::max(norm, std::abs(S[i]));
            diff = std::max(diff, std::abs(S[i] - 2. * W_ad.dx(i)));
          }
        worst = std::max(worst, diff / norm);
        worst = std::max(worst, relative(W_law, W_ad.val()));
      }
    std::printf("%-34s %s (below 1e-10)\n",
                "largest relative difference",
                worst < 1e-10 ? "OK" : "WRONG");
  }

  std::printf("four Gauss points per SIMD vector against the scalar path\n");
  {
    using YarnImpact::FE::internal::Double4;
    std::mt19937 generator(7);
    std::uniform_real_distribution<double> noise(-0.2, 0.2);
    const CharmetantLaw law = paper_law();
    double worst            = 0.;
    for (unsigned int sample = 0; sample < 10; ++sample)
      {
        Double4 Fv[9], Pv[9], Ie, Itc, Itd;
        Matrix3 Fs[4];
        for (unsigned int l = 0; l < 4; ++l)
          for (unsigned int i = 0; i < 9; ++i)
            {
              // Lane 3 of the first sample: exactly isotropic section.
              Fs[l][i] = (i % 4 == 0 ? 1. : 0.) +
                         (sample == 0 && l == 3 ? 0. : noise(generator));
              Fv[i][l] = Fs[l][i];
            }
        const Double4 Wv = law.stress_kernel(Fv, Pv, Ie, Itc, Itd);
        for (unsigned int l = 0; l < 4; ++l)
          {
            Matrix3 P;
            Invariants inv;
            const double W = law.stress(Fs[l], P, inv);
            double norm = 1e-300, diff = 0.;
            for (unsigned int i = 0; i < 9; ++i)
              {
                norm = std::max(norm, std::abs(P[i]));
                diff = std::max(diff, std::abs(P[i] - Pv[i][l]));
              }
            worst = std::max({worst,
                              diff / norm,
                              std::abs(W - Wv[l]) / std::max(W, 1e-300),
                              std::abs(inv.compaction - Itc[l])});
          }
      }
    std::printf("%-34s %s\n",
                "largest difference below 1e-12",
                worst < 1e-12 ? "OK" : "WRONG");
  }

  std::printf("exactly transversely isotropic states\n");
  {
    // A rotation about the fibre axis times diag(1.03, 0.95, 0.95): zeta = 1
    // exactly in exact arithmetic, and acosh would give NaN.
    const double c = std::cos(0.3), s = std::sin(0.3);
    const double R[9] = {1, 0, 0, 0, c, -s, 0, s, c};
    const double D[3] = {1.03, 0.95, 0.95};
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        F[3 * i + j] = R[3 * i + j] * D[j];
    Matrix3 P;
    Invariants inv;
    const double W0 = paper_law().stress(F, P, inv);
    bool finite     = std::isfinite(W0);
    for (const double p : P)
      finite = finite && std::isfinite(p);
    kirchhoff(F, tau, W);
    const double asym = std::max({std::abs(tau[1] - tau[3]),
                                  std::abs(tau[2] - tau[6]),
                                  std::abs(tau[5] - tau[7])});
    std::printf("%-34s %s\n",
                "finite energy and stress",
                finite ? "OK" : "WRONG");
    std::printf("%-34s %s\n",
                "symmetric Kirchhoff stress",
                asym < 1e-9 ? "OK" : "WRONG");
    std::printf("%-34s %s\n",
                "distortion invariant below 1e-7",
                inv.distortion < 1e-7 ? "OK" : "WRONG");
    diag(F, 1., 1., 1.);
    const double W1 = paper_law().stress(F, P, inv);
    double max_p    = 0.;
    for (const double p : P)
      max_p = std::max(max_p, std::abs(p));
    std::printf("%-34s %s\n",
                "reference state: W = 0, P = 0",
                W1 == 0. && max_p == 0. ? "OK" : "WRONG");
  }

  std::printf("linear transversely isotropic law, null Poisson ratios\n");
  {
    const LinearTransverselyIsotropicLaw linear(LinearParameters(), 1267.);
    Matrix3 P;
    Invariants inv;
    diag(F, 1.01, 1., 1.);
    linear.stress(F, P, inv);
    const LinearParameters lp;
    check("P11 at 1 % strain [MPa]",
          1e-6 * P[0],
          1e-6 * lp.E_L * (0.01 + 0.5e-4) * 1.01,
          1e-10);
    std::printf("%-34s %s\n",
                "no transverse stress",
                std::abs(P[4]) + std::abs(P[8]) == 0. ? "OK" : "WRONG");
  }
}
