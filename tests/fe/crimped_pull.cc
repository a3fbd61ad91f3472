// Decrimping (doc/fe-model.md section 8): a crimped yarn pulled slowly
// takes up its crimp before its fibres stretch, so its initial axial
// stiffness is far below the straight yarn's. The yarn: one wavelength,
// 2 mm, 32 cells along, the paper's section and law, clamped at both end
// sections (troughs of the centreline A cos(2 pi x / lambda), normal to
// x); the end x = +L/2 is moved along x by delta = eps L, eps = 0.1 %,
// smoothly over 20 us, then held for 40 us, with mass-proportional damping
// (dynamic relaxation); the force is the end's reaction, the sum of the
// internal forces on its nodes along x.
//
// Checked, for the amplitudes A = 0, 5, 10, 20, 50 um:
// - the straight yarn (A = 0) carries the closed form of the law in
//   uniaxial tension, A_s k_e ln(1 + eps) / (1 + eps), A_s = pi a_y a_z,
//   within 0.5 %;
// - every crimped yarn carries less, the larger the amplitude the less,
//   and the force tends to the straight yarn's as A goes to 0;
// - the law has no longitudinal shear stiffness (its fibres slide freely
//   along each other), so the yarn has no bending stiffness and behaves
//   as a bundle of strings: each fibre is as long as the centreline,
//   L_c = L (1 + crimp), and the yarn carries A_s k_e ln(s) / s with
//   s = L (1 + eps) / L_c once the crimp is taken up (s > 1), nothing
//   before. The yarns of 5 and 10 um, taut at this eps, must carry that
//   string limit within 1 %; the yarn of 50 um (crimp 0.61 %, slack at
//   this eps) less than 1 % of the straight yarn's force.

#include <deal.II/base/mpi.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "crimped_yarn_runs.h"

using namespace YarnImpact;

namespace
{
  /** The reaction force [N] at the pulled end after the pull. */
  double
  pull(const double amplitude, const double eps, double &crimp)
  {
    const double L = 2e-3, lambda = 2e-3;
    CrimpedYarnRuns::Run run(L, 32, amplitude, lambda);
    crimp                    = run.crimped ? run.crimped->crimp() : 0.;
    const FE::CouplingView v = FE::coupling_view(*run.model);
    std::vector<unsigned int> pulled, free_dofs;
    for (unsigned int k = 0; k < v.nodes->size(); ++k)
      {
        const auto &n = (*v.nodes)[k];
        if (std::abs(run.abscissa(v, k) - 0.5 * L) < 1e-9 * L)
          pulled.push_back(n[0]);
        for (unsigned int d = 0; d < 3; ++d)
          if (v.inverse_mass[n[d]] > 0.)
            free_dofs.push_back(n[d]);
      }
    const double dt     = 0.8 * run.model->stable_time_step();
    const double T_ramp = 20e-6, T_end = 60e-6;
    // Damping rate [1/s]: about critical for the slowest transverse
    // (string) mode of the taut yarn, pi c sqrt(eps) / L.
    const double c_damp = 4e5;
    const double delta  = eps * L;
    double t            = 0.;
    while (t < T_end)
      {
        t += dt;
        const double ramp =
          t < T_ramp ? 0.5 * (1. - std::cos(M_PI * t / T_ramp)) : 1.;
        run.step(dt, [&]() {
          for (const unsigned int i : pulled)
            v.displacement[i] = ramp * delta;
        });
        const double damp = std::exp(-c_damp * dt);
        for (const unsigned int i : free_dofs)
          v.velocity[i] *= damp;
      }
    double force = 0.;
    for (const unsigned int i : pulled)
      force -= v.force[i];
    return force;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double eps = 1e-3;
  const YarnImpact::Parameters::Yarn yarn;
  const double area = M_PI * yarn.thickness_semi_axis * yarn.width_semi_axis;
  const FE::CharmetantParameters law;
  const auto string_force = [&](const double crimp) {
    const double s = (1. + eps) / (1. + crimp);
    return s > 1. ? area * law.k_e * std::log(s) / s : 0.;
  };
  const double amplitudes[] = {0., 5e-6, 10e-6, 20e-6, 50e-6};
  std::vector<double> force;
  bool string_limit = true;
  for (const double A : amplitudes)
    {
      double crimp    = 0.;
      const double F  = pull(A, eps, crimp);
      const double Fs = string_force(crimp);
      force.push_back(F);
      if (A > 0. && A <= 10e-6)
        string_limit = string_limit && std::abs(F / Fs - 1.) < 0.01;
      std::printf("A = %4.0f um: crimp %.4f %%, force %.3f N, string limit "
                  "%.3f N\n",
                  A * 1e6,
                  crimp * 100.,
                  F,
                  Fs);
    }
  const double closed = string_force(0.);
  std::printf("Straight: force / (A_s k_e ln(1+eps)/(1+eps)) - 1 within "
              "0.5 %%: %s\n",
              std::abs(force[0] / closed - 1.) < 5e-3 ? "OK" : "WRONG");
  bool below = true, monotone = true;
  for (unsigned int k = 1; k < force.size(); ++k)
    {
      below    = below && force[k] < force[0];
      monotone = monotone && force[k] < force[k - 1];
    }
  std::printf("Every crimped yarn below the straight one: %s; the force "
              "falls as the amplitude grows: %s\n",
              below ? "OK" : "WRONG",
              monotone ? "OK" : "WRONG");
  std::printf("A = 5, 10 um: the string limit within 1 %%: %s; A = 50 um: "
              "below 1 %% of the straight yarn's force: %s\n",
              string_limit ? "OK" : "WRONG",
              force.back() < 0.01 * force[0] ? "OK" : "WRONG");
}
