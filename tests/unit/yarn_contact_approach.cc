// The yarn contact's lists along an approach (Fabric::YarnContact,
// doc/fe-model.md section 8.4, "The candidate search"): a block (yarn 1,
// 4 x 1 x 3 cells, a x h x w) is brought down onto the lateral face of
// another (yarn 0) from a gap of 55 um, 0.7 um a step, in 86 steps, to an
// overlap of 5.2 um. The lists are built at 2 d_max + skin = 60 um, so the
// approach starts with every node listed and beyond the reach of the
// contacts, and the lists are built again whenever the drift passes
// skin/2 = 10 um.
// - At every step the force on yarn 0 is the closed form: exactly 0 while
//   the blocks do not overlap, then p delta a w at the overlap delta
//   (within 1e-9 of p (0.7 um) a w: a contact that starts in a step
//   presses by all its depth, doc/fe-model.md section 8.4), from the first
//   step with an overlap, opposite on yarn 1: no contact is missed or
//   started late across the list builds.
// A physics check against a closed form, not a regression record: every
// line says yes or no.

#include <yarn_impact/fabric/yarn_contact.h>

#include <deal.II/base/mpi.h>
#include <deal.II/grid/tria.h>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include "two_blocks.h"

using namespace YarnImpact;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const char *yes_no[] = {"no", "yes"};
  const double a = 1e-3, w = 0.6e-3, h = 0.2e-3, dt = 1e-9;
  const double gap = 55e-6, delta = 0.7e-6;
  const unsigned int n_steps = 86;
  Fabric::YarnContactParameters prm;
  prm.penalty  = 5e13;
  prm.friction = 0.2;

  // Yarn 1's bottom at y = 0, yarn 0's top at y = -gap.
  dealii::Triangulation<3> both;
  two_blocks(both, a, h, w, -gap, {4, 1, 3}, {4, 1, 3});
  const Fabric::ContactSurface s = Fabric::make_contact_surface(both, 1440.);
  std::vector<unsigned int> owned(s.n_nodes());
  std::iota(owned.begin(), owned.end(), 0);
  Fabric::YarnContact contact(prm, s, owned, MPI_COMM_SELF);
  std::printf("yarn 1 brought down onto yarn 0 from a gap of %.0f um by "
              "%.1f um a step; detection depth %.0f um, skin %.0f um\n",
              gap * 1e6,
              delta * 1e6,
              prm.detection_depth * 1e6,
              prm.skin * 1e6);

  std::vector<double> x(3 * s.n_nodes()), v(x.size(), 0.), f(x.size());
  for (unsigned int i = 0; i < s.n_nodes(); ++i)
    if (s.node_yarn[i] == 1)
      v[3 * i + 1] = -delta / dt;
  const double scale = prm.penalty * delta * a * w;
  bool closed_form = true, opposite = true;
  unsigned int first_force = 0;
  for (unsigned int k = 0; k <= n_steps; ++k)
    {
      for (unsigned int i = 0; i < s.n_nodes(); ++i)
        for (unsigned int c = 0; c < 3; ++c)
          x[3 * i + c] = s.reference[i][c] -
                         (s.node_yarn[i] == 1 && c == 1 ? k * delta : 0.);
      std::fill(f.begin(), f.end(), 0.);
      contact.add_forces(x, v, dt, f);
      double f0 = 0., f1 = 0.;
      for (unsigned int i = 0; i < s.n_nodes(); ++i)
        (s.node_yarn[i] == 0 ? f0 : f1) += f[3 * i + 1];
      // The overlap from the nodes' own coordinates (yarn 0's top, yarn
      // 1's bottom).
      const double overlap = -gap - (0. - k * delta);
      const double expected =
        overlap > 0. ? -prm.penalty * overlap * a * w : 0.;
      closed_form =
        closed_form && (overlap > 0. ? std::abs(f0 - expected) < 1e-9 * scale
                                     : f0 == 0. && f1 == 0.);
      opposite = opposite && std::abs(f0 + f1) < 1e-12 * scale;
      if (first_force == 0 && f0 != 0.)
        first_force = k;
    }
  std::printf("first force in the first step with an overlap: %s\n",
              yes_no[first_force ==
                     static_cast<unsigned int>(std::floor(gap / delta)) + 1]);
  std::printf("force on yarn 0 at every step: 0 apart, p delta a w "
              "overlapped (within 1e-9 of p 0.7 um a w): %s\n",
              yes_no[closed_form]);
  std::printf("opposite on yarn 1 to 1e-12: %s\n", yes_no[opposite]);
  std::printf("lists built more than twice on the way (the drift passed "
              "skin/2): %s\n",
              yes_no[contact.n_rebuilds() > 2]);
  return 0;
}
