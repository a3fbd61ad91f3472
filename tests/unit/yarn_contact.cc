// The yarn-yarn contact of the woven fabric (Fabric::YarnContact,
// doc/fe-model.md section 8.4), on two blocks of hexahedra (yarns 0 and 1),
// each against a closed form:
// (a) pressed together by a penetration d: the normal force on each block
//     is p d times the contact area (each side a slave at half the
//     penalty), equal and opposite, on conforming and non-conforming
//     meshes;
// (b) friction: the upper block's nodes pulled along x at V for K steps
//     (positions held, the tangential spring sees u = K V dt): below
//     mu N the force is the stick spring's, k_t/k_n p A u; above, mu N;
// (c) an elastic frictionless collision of two blocks of free nodes (no
//     internal forces: the contact alone), velocity Verlet with the
//     contact's stable step times 0.5, 0.1 and 0.05: momentum kept to
//     1e-12 relative; the energy error after the bodies part, kinetic
//     plus contact energy, below 1 %, 0.1 % and 0.025 %, shrinking as the
//     step squared (velocity Verlet's order);
// (d) the spring's rest depth and the hold (the upper block moved by
//     steps, its velocity each step's motion over dt): blocks that overlap
//     by d at rest carry no force; pressed a further d in one step, p d
//     per area (the spring starts at the depth the nodes had); raised by
//     1.5 d, none (the rest depth follows them up); lowered by d / 4,
//     p d / 4 per area. A contact pressed by steps of d_max / 4 to
//     1.5 d_max carries p 1.5 d_max per area (a touching contact holds to
//     2 d_max), and lets go beyond 2 d_max; blocks brought from apart to
//     1.5 d_max in one step do not touch (no contact starts beyond d_max).
// In (a) and (b) the blocks are pressed by d in the first step, as in (d).

#include <yarn_impact/fabric/yarn_contact.h>

#include <deal.II/base/mpi.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "two_blocks.h"

using namespace YarnImpact;

namespace
{
  const double a = 1e-3, w = 0.5e-3, h = 0.2e-3; // block sizes [m]
  const double density = 1440.;                  // [kg/m^3]

  /** Block 0 (below, top at y = top0) and block 1 (above, bottom at
   * y = 0), of the given subdivisions and extents in x and z: their
   * surface. */
  Fabric::ContactSurface
  blocks_surface(const double top0,
                 const std::vector<unsigned int> &n0,
                 const std::vector<unsigned int> &n1,
                 const double margin1 = 0.)
  {
    dealii::Triangulation<3> both;
    two_blocks(both, a, h, w, top0, n0, n1, margin1);
    return Fabric::make_contact_surface(both, density);
  }

  std::vector<unsigned int>
  all_nodes(const Fabric::ContactSurface &s)
  {
    std::vector<unsigned int> owned(s.n_nodes());
    std::iota(owned.begin(), owned.end(), 0);
    return owned;
  }

  std::vector<double>
  positions(const Fabric::ContactSurface &s)
  {
    std::vector<double> x(3 * s.n_nodes());
    for (unsigned int i = 0; i < s.n_nodes(); ++i)
      for (unsigned int d = 0; d < 3; ++d)
        x[3 * i + d] = s.reference[i][d];
    return x;
  }

  /** Velocities [m/s] that move yarn 1's nodes by @p dy along y in
   * the step @p dt [s], yarn 0's at rest. */
  std::vector<double>
  moving_upper(const Fabric::ContactSurface &s,
               const double dy,
               const double dt)
  {
    std::vector<double> v(3 * s.n_nodes(), 0.);
    for (unsigned int i = 0; i < s.n_nodes(); ++i)
      if (s.node_yarn[i] == 1)
        v[3 * i + 1] = dy / dt;
    return v;
  }

  /** Move yarn 1's nodes of @p x [m] by @p dy [m] along y. */
  void
  move_upper(const Fabric::ContactSurface &s,
             std::vector<double> &x,
             const double dy)
  {
    for (unsigned int i = 0; i < s.n_nodes(); ++i)
      if (s.node_yarn[i] == 1)
        x[3 * i + 1] += dy;
  }

  /** Total force on yarn @p yarn, component @p d [N]. */
  double
  total(const Fabric::ContactSurface &s,
        const std::vector<double> &f,
        const unsigned int yarn,
        const unsigned int d)
  {
    double sum = 0.;
    for (unsigned int i = 0; i < s.n_nodes(); ++i)
      if (s.node_yarn[i] == yarn)
        sum += f[3 * i + d];
    return sum;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const char *yes_no[] = {"no", "yes"};
  Fabric::YarnContactParameters prm;
  prm.penalty                    = 5e13;
  prm.friction                   = 0.2;
  prm.tangential_stiffness_ratio = 1.;
  const double d                 = 1e-6;
  const double N                 = prm.penalty * d * a * w;

  // (a) Pressed by d, conforming (4 x 3) and non-conforming (5 x 2).
  std::printf("(a) pressed by d = 1 um, p = 5e13 Pa/m: p d a w = %.6f N\n", N);
  for (const unsigned int n1x : {4u, 5u})
    {
      const auto s = blocks_surface(d, {4, 1, 3}, {n1x, 1, n1x == 4 ? 3u : 2u});
      Fabric::YarnContact contact(prm, s, all_nodes(s), MPI_COMM_SELF);
      std::vector<double> x = positions(s), v = moving_upper(s, -d, 1e-9),
                          f(x.size(), 0.);
      contact.add_forces(x, v, 1e-9, f);
      const double f0 = total(s, f, 0, 1), f1 = total(s, f, 1, 1);
      std::printf("  upper mesh %u x %u: force on lower %.9f N, on upper "
                  "%.9f N; energy/(N d/2) "
                  "%.12f\n",
                  n1x,
                  n1x == 4 ? 3u : 2u,
                  f0,
                  f1,
                  contact.energy() / (0.5 * N * d));
      std::printf(
        "  within 1e-12 and opposite to 1e-14: %s\n",
        yes_no[std::abs(-f0 - N) < 1e-12 * N && std::abs(f0 + f1) < 1e-14 * N]);
    }

  // (b) Friction: stick below mu N, slide at mu N.
  {
    const auto s   = blocks_surface(d, {4, 1, 3}, {5, 1, 2});
    const double V = 1., dt = 1e-9;
    std::printf("(b) friction mu = 0.2, k_t = k_n: mu N = %.6f N\n",
                prm.friction * N);
    for (const unsigned int K : {100u, 150u, 1000u})
      {
        Fabric::YarnContact contact(prm, s, all_nodes(s), MPI_COMM_SELF);
        std::vector<double> x = positions(s), v = moving_upper(s, -d, dt), f;
        f.assign(x.size(), 0.);
        contact.add_forces(x, v, dt, f);
        v.assign(x.size(), 0.);
        for (unsigned int i = 0; i < s.n_nodes(); ++i)
          if (s.node_yarn[i] == 1)
            v[3 * i] = V;
        for (unsigned int k = 0; k < K; ++k)
          {
            f.assign(x.size(), 0.);
            contact.add_forces(x, v, dt, f);
          }
        const double u      = K * V * dt;
        const double stick  = prm.tangential_stiffness_ratio * N / d * u;
        const double expect = std::min(stick, prm.friction * N);
        const double f0 = total(s, f, 0, 0), f1 = total(s, f, 1, 0);
        std::printf("  u = %.2f um: force on lower %.9f N (%s %.9f N), on "
                    "upper %.9f N; within 1e-9 and opposite to 1e-14: %s\n",
                    u * 1e6,
                    f0,
                    stick < prm.friction * N ? "stick" : "slide",
                    expect,
                    f1,
                    yes_no[std::abs(f0 - expect) < 1e-9 * expect &&
                           std::abs(f0 + f1) < 1e-14 * N]);
      }
  }

  // (c) Elastic frictionless collision of free nodes.
  {
    Fabric::YarnContactParameters elastic = prm;
    elastic.friction                      = 0.;
    const double gap                      = 0.5e-6;
    const auto s          = blocks_surface(-gap, {4, 1, 2}, {5, 1, 3}, 0.1e-3);
    const double v0[2][3] = {{0.3, 1., 0.2}, {0., -0.5, 0.}};
    std::printf("(c) collision, gap 0.5 um, closing at 1.5 m/s\n");
    std::vector<double> end_errors;
    for (const double safety : {0.5, 0.1, 0.05})
      {
        Fabric::YarnContact contact(elastic, s, all_nodes(s), MPI_COMM_SELF);
        const double dt       = safety * contact.stable_time_step();
        std::vector<double> x = positions(s), v(x.size()), f(x.size(), 0.);
        double P0[3] = {0., 0., 0.}, E0 = 0.;
        for (unsigned int i = 0; i < s.n_nodes(); ++i)
          for (unsigned int c = 0; c < 3; ++c)
            {
              v[3 * i + c] = v0[s.node_yarn[i]][c];
              P0[c] += s.mass[i] * v[3 * i + c];
              E0 += 0.5 * s.mass[i] * v[3 * i + c] * v[3 * i + c];
            }
        contact.add_forces(x, v, dt, f);
        double worst_E = 0., worst_P = 0., final_E = 0.;
        unsigned int most        = 0;
        const unsigned int steps = std::ceil(4e-6 / dt);
        for (unsigned int k = 0; k < steps; ++k)
          {
            for (unsigned int i = 0; i < x.size(); ++i)
              {
                v[i] += 0.5 * dt * f[i] / s.mass[i / 3];
                x[i] += dt * v[i];
              }
            f.assign(x.size(), 0.);
            contact.add_forces(x, v, dt, f);
            double P[3] = {0., 0., 0.}, E = contact.energy();
            for (unsigned int i = 0; i < x.size(); ++i)
              {
                v[i] += 0.5 * dt * f[i] / s.mass[i / 3];
                P[i % 3] += s.mass[i / 3] * v[i];
                E += 0.5 * s.mass[i / 3] * v[i] * v[i];
              }
            worst_E = std::max(worst_E, std::abs(E - E0) / E0);
            final_E = (E - E0) / E0;
            for (unsigned int c = 0; c < 3; ++c)
              worst_P = std::max(worst_P,
                                 std::abs(P[c] - P0[c]) /
                                   std::sqrt(P0[0] * P0[0] + P0[1] * P0[1] +
                                             P0[2] * P0[2]));
            most = std::max(most, contact.n_touching());
          }
        double v_lower = 0., m_lower = 0.;
        for (unsigned int i = 0; i < s.n_nodes(); ++i)
          if (s.node_yarn[i] == 0)
            {
              v_lower += s.mass[i] * v[3 * i + 1];
              m_lower += s.mass[i];
            }
        const double tolerance =
          safety == 0.5 ? 1e-2 : (safety == 0.1 ? 1e-3 : 2.5e-4);
        std::printf("  dt = %.2f x %.4e s, %u steps, %u rebuilds, up to %u "
                    "contacts, final contact energy %.1e J: momentum error "
                    "below 1e-12: %s; energy error %.2e at the end, "
                    "largest %.2e in contact (end below %.1e: %s); lower "
                    "block's mean v_y %.4f m/s\n",
                    safety,
                    contact.stable_time_step(),
                    steps,
                    contact.n_rebuilds(),
                    most,
                    contact.energy(),
                    yes_no[worst_P < 1e-12],
                    final_E,
                    worst_E,
                    tolerance,
                    yes_no[std::abs(final_E) < tolerance],
                    v_lower / m_lower);
        end_errors.push_back(std::abs(final_E));
      }
    const double ratio = end_errors[1] / end_errors[2];
    std::printf("  end error at 0.1 over that at 0.05: %.2f (second order: "
                "4; between 3 and 6: %s)\n",
                ratio,
                yes_no[ratio > 3. && ratio < 6.]);
  }

  // (d) The rest depth and the hold: the upper block moved step by step.
  {
    const double dt = 1e-9, d_max = prm.detection_depth;
    std::printf("(d) rest depth and hold, d = 1 um, d_max = %.0f um: p A "
                "= %.6f N/um\n",
                d_max * 1e6,
                N / (d * 1e6));
    const auto s = blocks_surface(d, {4, 1, 3}, {4, 1, 3});
    // Each step: move by @p dy, evaluate, compare the force on the lower
    // block with p @p expect A and the energy with p expect^2 A / 2.
    const auto step = [&](Fabric::YarnContact &contact,
                          std::vector<double> &x,
                          const double dy,
                          const double expect,
                          const char *what) {
      move_upper(s, x, dy);
      std::vector<double> v = moving_upper(s, dy, dt), f(x.size(), 0.);
      contact.add_forces(x, v, dt, f);
      const double f0 = -total(s, f, 0, 1), f1 = total(s, f, 1, 1);
      const double want = prm.penalty * expect * a * w;
      const double E    = contact.energy();
      const bool ok     = std::abs(f0 - want) <= 1e-12 * N &&
                      std::abs(f0 - f1) <= 1e-14 * N &&
                      std::abs(E - 0.5 * want * expect) <= 1e-12 * 0.5 * N * d;
      if (what)
        std::printf("  %s: force %.9f N, energy %.6e J (p %.2f um A: "
                    "%.9f N, %.6e J): %s\n",
                    what,
                    f0,
                    E,
                    expect * 1e6,
                    want,
                    0.5 * want * expect,
                    yes_no[ok]);
      return ok;
    };
    {
      Fabric::YarnContact contact(prm, s, all_nodes(s), MPI_COMM_SELF);
      std::vector<double> x = positions(s);
      step(contact, x, 0., 0., "overlapping by d at rest");
      step(contact, x, -d, d, "pressed a further d");
      step(contact, x, 1.5 * d, 0., "raised by 1.5 d");
      step(contact, x, -0.25 * d, 0.25 * d, "lowered by d / 4");
    }
    {
      Fabric::YarnContact contact(prm, s, all_nodes(s), MPI_COMM_SELF);
      std::vector<double> x = positions(s);
      move_upper(s, x, d); // touching at y = 0
      bool ok = true;
      for (unsigned int k = 1; k <= 6; ++k)
        ok = step(contact, x, -0.25 * d_max, 0.25 * k * d_max, nullptr) && ok;
      std::printf("  pressed by steps of d_max / 4 to 1.5 d_max, p A per "
                  "depth at each: %s\n",
                  yes_no[ok]);
      step(contact, x, 0., 1.5 * d_max, "held at 1.5 d_max");
      step(contact, x, -d_max, 0., "pressed to 2.5 d_max");
    }
    {
      Fabric::YarnContact contact(prm, s, all_nodes(s), MPI_COMM_SELF);
      std::vector<double> x = positions(s);
      move_upper(s, x, d + 0.1 * d_max); // apart by d_max / 10
      step(contact, x, 0., 0., nullptr);
      step(contact, x, -1.6 * d_max, 0., "from apart to 1.5 d_max in a step");
    }
  }
  return 0;
}
