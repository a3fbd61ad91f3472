// The bridging-domain coupling (coupling/bridging_domain.h, doc/hybrid.md
// section 2) checked on its own, on a string: one KM2 fibre of 12 um
// spheres linked by trusses (the DEM's fibre) on x in [0, a], coupled in
// the overlap [a - w, a] to two-node finite elements of ten sphere spacings
// (the same linear density rho A and axial stiffness EA, lumped mass) up to
// the far end. Both are geometrically exact, so a pretensioned string also
// carries transverse waves.
//
// Physics checks, no recorded numbers: each line of the file `output` says
// what is checked against which bound and PASS or FAIL; the measured values
// go to stdout (kept by the test machinery in `stdout`), and a failed check
// makes the exit code non-zero.
//
// 1. Patch test: a uniform stretch at rest gives no force on any degree of
//    freedom (round-off, 1e-9 of the tension) when the overlap's nodes sit
//    on spheres; with nodes between spheres, the force on such a node is the
//    closed form T l^2 / (4 w h) of the weighted sums (doc/hybrid.md 2.4).
// 2. Momentum: free string, random velocities, 4000 steps: the total linear
//    momentum is conserved to 1e-12 of sum |m v|; the constraints hold to
//    1e-12 of the largest speed.
// 3. Waves: a longitudinal pulse and a transverse pulse (pretension 1 %) of
//    10 and 20 cells cross the overlap in both directions. Reflected energy
//    (the energy of the difference to the same pulse in the incoming side's
//    model alone, in the incoming side's own region) <= 1 % of the pulse's;
//    the transmitted pulse's speed (its energy centroid over 40 cells)
//    within 1 % of the receiving model's own speed for the same pulse; the
//    total energy conserved within 0.05 % of the pulse's energy.

#include "bridged_string.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "verdicts.h"

using namespace BridgedString;

namespace
{
  using Verdicts::all_passed;
  using Verdicts::check;


  void
  patch_tests()
  {
    const double eps = 0.01, T = E * A * eps;
    {
      const Geometry g{Kind::hybrid, 10 * l, 100 * l, 40 * l, 300 * l, true};
      const HybridString s(g, eps);
      const double f = s.largest_net_force();
      std::printf(
        "patch, nodes on spheres: largest net force %.3e N = %.3e T\n",
        f,
        f / T);
      check(f <= 1e-9 * T,
            "patch test, overlap nodes on spheres (h = 10 l, w = 4 h): no "
            "force on any degree of freedom under a uniform stretch of 1 % "
            "(|f| <= 1e-9 T)");
    }
    {
      // h = 10.5 l: the overlap's inner and outer nodes on spheres, the
      // nodes at 10.5 l and 31.5 l from its start half-way between two.
      const double h = 10.5 * l, w = 4 * h;
      const Geometry g{Kind::hybrid,
                       h,
                       60 * l + w,
                       w,
                       60 * l + w + 20 * h,
                       true};
      const HybridString s(g, eps);
      const double predicted = T * l * l / (4. * w * h);
      const double f1        = std::abs(s.net_force_x(1)),
                   f3        = std::abs(s.net_force_x(3));
      const double largest   = s.largest_net_force();
      std::printf("patch, nodes between spheres: |f| at the straddled nodes "
                  "%.6e, %.6e N, largest %.6e N, closed form T l^2/(4wh) "
                  "%.6e N\n",
                  f1,
                  f3,
                  largest,
                  predicted);
      check(std::abs(f1 - predicted) <= 1e-6 * predicted &&
              std::abs(f3 - predicted) <= 1e-6 * predicted &&
              largest <= predicted * (1. + 1e-6),
            "patch test, overlap nodes between spheres (h = 10.5 l): the "
            "force on a node straddled by a truss is T l^2 / (4 w h) within "
            "1e-6, and no force anywhere is larger");
    }
  }


  void
  momentum_test()
  {
    const Geometry g{Kind::hybrid, 10 * l, 100 * l, 40 * l, 300 * l, false};
    HybridString s(g, 0.);
    std::mt19937 random(5);
    std::uniform_real_distribution<double> speed(-10., 10.);
    for (auto &v : s.vn)
      v = speed(random);
    for (unsigned int i = 0; i < s.Xs.size(); ++i)
      if (s.slave[i] < 0)
        for (unsigned int d = 0; d < 3; ++d)
          s.vs[3 * i + d] = speed(random);
    // The constrained spheres move with the nodes.
    std::vector<double> vp(3 * s.slaved.size());
    s.constraint.interpolate(s.vn.data(), vp.data());
    for (unsigned int k = 0; k < s.slaved.size(); ++k)
      for (unsigned int d = 0; d < 3; ++d)
        s.vs[3 * s.slaved[k] + d] = vp[3 * k + d];
    double p0[3], scale[3];
    for (unsigned int d = 0; d < 3; ++d)
      s.momentum(d, p0[d], scale[d]);
    const double dt = 0.5 * l / c_axial;
    double drift = 0., violation = 0.;
    for (unsigned int n = 0; n < 4000; ++n)
      {
        s.step(dt);
        for (unsigned int d = 0; d < 3; ++d)
          {
            double p, sc;
            s.momentum(d, p, sc);
            drift = std::max(drift, std::abs(p - p0[d]) / scale[d]);
          }
        violation = std::max(violation, s.largest_violation());
      }
    std::printf("momentum: largest |P - P0| / sum|m v| %.3e, largest "
                "constraint violation %.3e m/s\n",
                drift,
                violation);
    check(drift <= 1e-12,
          "momentum: free string with random velocities, 4000 steps: |P - "
          "P0| <= 1e-12 sum |m v| in every direction");
    check(violation <= 1e-12 * 10.,
          "constraints: |v_i - N v| <= 1e-12 of the largest initial speed "
          "at every step");
  }


  struct PulseResult
  {
    double reflected, speed_ratio, energy_error;
  };

  /** One pulse of @p cells FE cells in component @p d, from the particles
   * to the continuum (@p rightward) or back. */
  PulseResult
  pulse_test(const double cells, const unsigned int d, const bool rightward)
  {
    const double h = 10 * l, w = 4 * h, lambda = cells * h;
    const double a = 100 * h + w, x_end = a + 120 * h;
    const double eps = d == 0 ? 0. : 0.01;
    // Longitudinal: c = sqrt(E/rho); transverse, pretension T0 = EA eps:
    // c^2 = T0 / (rho A (1 + eps)) in reference coordinates.
    const double c = d == 0 ? c_axial : std::sqrt(E * eps / (rho * (1. + eps)));
    const double amp = (d == 0 ? 1e-3 : 1e-2) * lambda / M_PI;
    const double xc =
      rightward ? a - w - 0.5 * lambda - 2 * h : a + 0.5 * lambda + 2 * h;
    const double sign = rightward ? 1. : -1.;
    const Geometry hybrid{Kind::hybrid, h, a, w, x_end, true};
    const Geometry particles{Kind::particles_only, h, a, w, x_end, true};
    const Geometry continuum{Kind::continuum_only, h, a, w, x_end, true};
    HybridString s(hybrid, eps), p(particles, eps), q(continuum, eps);
    for (HybridString *m : {&s, &p, &q})
      m->add_pulse(xc, lambda, d, amp, c, sign);
    HybridString &incoming  = rightward ? p : q;
    HybridString &receiving = rightward ? q : p;
    // The pulse energy, in its own model.
    const double pulse_energy =
      incoming.difference_energy(nullptr, rightward, 0., x_end);
    const double e0 = s.energy();
    // Times: the pulse has wholly left the overlap at t1; speed measured
    // over the next 40 cells, reflection at t2.
    const double t1 = (rightward ? (a - (xc - 0.5 * lambda))
                                 : ((xc + 0.5 * lambda) - (a - w))) /
                        c +
                      2 * h / c;
    const double t2 = t1 + 40 * h / c;
    const double dt = 0.5 * l / c_axial;
    // The receiving side's own region.
    const double r0 = rightward ? a : 0., r1 = rightward ? x_end : a - w;
    const double i0 = rightward ? 0. : a, i1 = rightward ? a - w : x_end;
    double t = 0., energy_error = 0., centroid[2][2] = {{0, 0}, {0, 0}};
    unsigned int mark = 0;
    while (t < t2)
      {
        for (HybridString *m : {&s, &p, &q})
          m->step(dt);
        t += dt;
        energy_error =
          std::max(energy_error, std::abs(s.energy() - e0) / pulse_energy);
        if (mark == 0 && t >= t1)
          {
            s.difference_energy(nullptr, !rightward, r0, r1, &centroid[0][0]);
            receiving.difference_energy(nullptr,
                                        !rightward,
                                        r0,
                                        r1,
                                        &centroid[1][0]);
            mark = 1;
          }
      }
    s.difference_energy(nullptr, !rightward, r0, r1, &centroid[0][1]);
    receiving.difference_energy(nullptr, !rightward, r0, r1, &centroid[1][1]);
    const double reflected =
      s.difference_energy(&incoming, rightward, i0, i1) / pulse_energy;
    const double speed_ratio =
      (centroid[0][1] - centroid[0][0]) / (centroid[1][1] - centroid[1][0]);
    std::printf("pulse %s, %2.0f cells, %s: reflected %.3e of the pulse "
                "energy, transmitted speed / receiving model's %.5f "
                "(%.1f m/s, c = %.1f m/s), energy error %.2e of the pulse's\n",
                d == 0 ? "longitudinal" : "transverse  ",
                cells,
                rightward ? "particles -> continuum" : "continuum -> particles",
                reflected,
                speed_ratio,
                (centroid[0][1] - centroid[0][0]) / (t2 - t1),
                c,
                energy_error);
    return {reflected, speed_ratio, energy_error};
  }


  void
  wave_tests()
  {
    for (const unsigned int d : {0u, 1u})
      for (const double cells : {10., 20.})
        for (const bool rightward : {true, false})
          {
            const PulseResult r = pulse_test(cells, d, rightward);
            const std::string what =
              std::string(d == 0 ? "longitudinal" : "transverse") +
              " pulse of " + std::to_string(int(cells)) + " cells, " +
              (rightward ? "particles -> continuum" : "continuum -> particles");
            check(r.reflected <= 0.01,
                  what + ": reflected energy <= 1 % of the pulse's");
            check(std::abs(r.speed_ratio - 1.) <= 0.01,
                  what + ": transmitted speed within 1 % of the receiving "
                         "model's");
            check(r.energy_error <= 5e-4,
                  what + ": total energy within 0.05 % of the pulse's");
          }
  }
} // namespace


int
main()
{
  patch_tests();
  momentum_test();
  wave_tests();
  return all_passed ? 0 : 1;
}
