// A crimped yarn (FE/Crimp, doc/fe-model.md section 8) at rest stays at
// rest, and conserves its energy under an initial velocity field. The
// yarn: 4 mm clamped at both ends, 64 cells along, the paper's section,
// crimp amplitude 0.1 mm and wavelength 2 mm (a crimp of 2.42 %), its
// fibres along the centreline's tangent at every Gauss point.
//
// (1) Unloaded, the reference state is stress-free whatever the fibre
// directions: after 2000 steps (12.6 us, 25 axial transits) every node's
// speed must stay below 1e-9 m/s (a spurious force of the fibre frames
// would accelerate the nodes of a 64-cell yarn to cm/s within a transit),
// and the elastic energy below 1e-18 J.
// (2) Given the velocity field v0 [sin(pi xi) t(x) + sin(2 pi xi) e_y],
// v0 = 1 m/s, xi = (x - x_begin) / L the abscissa of the node's section
// and t(x) the centreline's tangent there (axial and transverse motion),
// the kinetic plus elastic energy must stay within 0.1 % of the initial
// kinetic energy, 1/2 sum m v^2 summed here from the lumped masses,
// over 2000 steps.

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "crimped_yarn_runs.h"

using namespace YarnImpact;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double L = 4e-3, A = 1e-4, lambda = 2e-3;
  const unsigned int n_steps = 2000;
  {
    CrimpedYarnRuns::Run run(L, 64, A, lambda);
    const FE::CouplingView v = FE::coupling_view(*run.model);
    const double dt          = 0.8 * run.model->stable_time_step();
    double largest           = 0.;
    for (unsigned int s = 0; s < n_steps; ++s)
      {
        run.step(dt);
        for (unsigned int i = 0; i < v.nodes->size() * 3; ++i)
          largest = std::max(largest, std::abs(v.velocity[i]));
      }
    const Observables o = run.model->observables();
    std::printf("At rest, %u steps of %.2f ns: largest speed below 1e-9 "
                "m/s: %s, elastic energy below 1e-18 J: %s\n",
                n_steps,
                dt * 1e9,
                largest < 1e-9 ? "OK" : "WRONG",
                o.elastic_energy < 1e-18 ? "OK" : "WRONG");
  }
  {
    CrimpedYarnRuns::Run run(L, 64, A, lambda);
    const FE::CouplingView v = FE::coupling_view(*run.model);
    const double v0          = 1.;
    double E0                = 0.;
    for (unsigned int k = 0; k < v.nodes->size(); ++k)
      {
        const auto &n = (*v.nodes)[k];
        if (v.inverse_mass[n[0]] == 0.)
          continue; // a clamped node
        const double x  = run.abscissa(v, k);
        const double xi = (x + 0.5 * L) / L;
        const auto t    = run.crimped->tangent(x);
        double vel[3]   = {v0 * std::sin(M_PI * xi) * t[0],
                           v0 * std::sin(M_PI * xi) * t[1] +
                             v0 * std::sin(2. * M_PI * xi),
                           0.};
        for (unsigned int d = 0; d < 3; ++d)
          {
            v.velocity[n[d]] = vel[d];
            E0 += 0.5 * v.mass[n[d]] * vel[d] * vel[d];
          }
      }
    const double kinetic0 = run.model->observables().kinetic_energy;
    const double dt       = 0.8 * run.model->stable_time_step();
    double largest_error  = 0.;
    for (unsigned int s = 1; s <= n_steps; ++s)
      {
        run.step(dt);
        if (s % 20 == 0)
          {
            const Observables o = run.model->observables();
            largest_error =
              std::max(largest_error,
                       std::abs(o.kinetic_energy + o.elastic_energy - E0) / E0);
          }
      }
    std::printf("Initial velocity field, E0 = %.4e J (the model's kinetic "
                "energy: %s); largest |E - E0| / E0 over %u steps below "
                "1e-3: %s\n",
                E0,
                std::abs(kinetic0 - E0) <= 1e-12 * E0 ? "the same" : "WRONG",
                n_steps,
                largest_error < 1e-3 ? "OK" : "WRONG");
    std::printf("  largest |E - E0| / E0 = %.1e\n", largest_error);
  }
}
