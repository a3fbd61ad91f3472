// The axial tie of a DEM fibre to its fibre bars (coupling/bridging_domain.h
// ChainConstraint, doc/hybrid.md section 3.4), checked on one KM2 fibre: 12
// um spheres linked by trusses on x in [0, a], coupled in the overlap
// [a - w, a] (4 cells of 21 trusses, weights linear per cell as in the
// hybrid yarn) to a chain of bars from a - w to the far end, m bars per
// cell, axial motion only.
//
// Physics checks, no recorded numbers: each line of `output` says what is
// checked against which bound and PASS or FAIL; the measured values go to
// stdout.
//
// 1. The tridiagonal solve is the bridging constraint's: the accelerations
//    and multipliers of ChainConstraint equal those of the dense
//    BridgingConstraint (x component) for random masses, positions and
//    forces, within 1e-12.
// 2. Bars as fine as the trusses (m = 21, the default): each overlap sphere
//    sits on a bar node, their weighted masses and stiffnesses add up to
//    the fibre's, so the coupled chain is the uniform fibre: a sharp pulse
//    (10 truss lengths) crosses the overlap and leaves behind what it
//    leaves on the DEM fibre alone (within 1e-10 of its energy: no
//    reflection), its energy conserved within 1e-5 as on the fibre alone.
// 3. Momentum: random velocities, 4000 steps: conserved to 1e-12 of
//    sum |m v|; the constraints hold to 1e-12 of the largest speed.
// The reflected energy of coarser bars (m = 1, 3, 7) is printed, not
// checked: it is why the default is one bar per truss.

#include <yarn_impact/coupling/bridging_domain.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "verdicts.h"

using namespace YarnImpact::Coupling;

namespace
{
  // KM2 fibre: E = 84.62 GPa, rho = 1440 kg/m^3, d = 12 um.
  constexpr double E = 84.62e9, rho = 1440., A = M_PI * 36e-12;
  constexpr double l       = 12e-6;
  constexpr unsigned int M = 21, n_w = 4;

  using Verdicts::all_passed;
  using Verdicts::check;


  /** The coupled fibre: spheres 0 .. n_s (the last at a; @p n_only
   * trusses before the overlap), bars from a - w with m per cell over the
   * overlap and @p cells_after cells beyond it. */
  struct Fibre
  {
    unsigned int m, n_s, first, n_b, n_nodes;
    double h_b;
    std::vector<double> truss_w, sphere_m, bar_w, node_m;
    std::vector<double> u, v, f, ub, vb, fb;
    ChainConstraint tie;

    Fibre(const unsigned int m_,
          const unsigned int n_only,
          const unsigned int cells_after,
          const bool uniform = false)
      : m(m_)
    {
      n_s     = n_only + n_w * M;
      first   = n_s - n_w * M;
      n_b     = n_w + cells_after;
      n_nodes = n_b * m + 1;
      h_b     = M * l / m;
      // Particle weight per overlap cell: 1 - (k + 1/2) / n_w.
      auto beta = [](const unsigned int k) { return 1. - (k + 0.5) / n_w; };
      truss_w.assign(n_s, 1.);
      for (unsigned int t = first; t < n_s; ++t)
        truss_w[t] = uniform ? 1. : beta((t - first) / M);
      sphere_m.assign(n_s + 1, 0.);
      for (unsigned int s = 0; s <= n_s; ++s)
        sphere_m[s] =
          rho * A * l * 0.5 *
          ((s > 0 ? truss_w[s - 1] : 1.) + (s < n_s ? truss_w[s] : 0.));
      bar_w.assign(n_b * m, 1.);
      for (unsigned int j = 0; j < n_w * m; ++j)
        bar_w[j] = 1. - beta(j / m);
      node_m.assign(n_nodes, 0.);
      for (unsigned int j = 0; j < n_b * m; ++j)
        {
          node_m[j] += 0.5 * bar_w[j] * rho * A * h_b;
          node_m[j + 1] += 0.5 * bar_w[j] * rho * A * h_b;
        }
      if (uniform)
        {
          // The reference: the DEM fibre alone, as long as the pulse
          // needs (no bars; n_s is its end).
          n_s += cells_after * M;
          truss_w.assign(n_s, 1.);
          sphere_m.assign(n_s + 1, rho * A * l);
          sphere_m[0] = sphere_m[n_s] = 0.5 * rho * A * l;
          n_b = n_nodes = 0;
          first         = n_s + 1;
          u.assign(n_s + 1, 0.);
          v = f = u;
          return;
        }
      tie = ChainConstraint(n_w * m + 1);
      for (unsigned int j = 0; j <= n_w * m; ++j)
        tie.set_node_mass(j, node_m[j]);
      for (unsigned int s = first; s <= n_s; ++s)
        {
          const double t = double(s - first) * l / h_b;
          unsigned int j = std::lround(t);
          double xi      = 0.;
          if (std::abs(t - j) > 1e-9)
            {
              j  = std::min<unsigned int>(n_w * m - 1, unsigned(t));
              xi = t - j;
            }
          tie.add_particle(sphere_m[s], j, xi);
        }
      tie.factorize();
      u.assign(n_s + 1, 0.);
      v = f = u;
      ub.assign(n_nodes, 0.);
      vb = fb = ub;
    }

    /** Forces, then the tie: f and fb give the coupled accelerations. */
    void
    forces()
    {
      std::fill(f.begin(), f.end(), 0.);
      std::fill(fb.begin(), fb.end(), 0.);
      const double k = E * A / l, k_b = E * A / h_b;
      for (unsigned int t = 0; t < n_s; ++t)
        {
          const double s = truss_w[t] * k * (u[t + 1] - u[t]);
          f[t] += s;
          f[t + 1] -= s;
        }
      for (unsigned int j = 0; j + 1 < n_nodes; ++j)
        {
          const double s = bar_w[j] * k_b * (ub[j + 1] - ub[j]);
          fb[j] += s;
          fb[j + 1] -= s;
        }
      if (n_nodes == 0)
        return;
      const unsigned int n_t = n_w * m + 1, n_p = n_s - first + 1;
      std::vector<double> an(n_t), ap(n_p), lambda(n_p);
      tie.accelerations(fb.data(),
                        &f[first],
                        an.data(),
                        ap.data(),
                        lambda.data());
      for (unsigned int j = 0; j < n_t; ++j)
        fb[j] = an[j] * node_m[j];
      for (unsigned int q = 0; q < n_p; ++q)
        f[first + q] = ap[q] * sphere_m[first + q];
    }

    /** One velocity-Verlet step of @p dt [s] (the far end held). */
    void
    step(const double dt)
    {
      for (unsigned int s = 0; s <= n_s; ++s)
        {
          v[s] += 0.5 * dt * f[s] / sphere_m[s];
          u[s] += dt * v[s];
        }
      for (unsigned int j = 0; j + 1 < n_nodes; ++j)
        {
          vb[j] += 0.5 * dt * fb[j] / node_m[j];
          ub[j] += dt * vb[j];
        }
      forces();
      for (unsigned int s = 0; s <= n_s; ++s)
        v[s] += 0.5 * dt * f[s] / sphere_m[s];
      for (unsigned int j = 0; j + 1 < n_nodes; ++j)
        vb[j] += 0.5 * dt * fb[j] / node_m[j];
    }

    /** Weighted kinetic and strain energy of the spheres with x < @p x_end
     * (all if infinite), and of everything [J]. */
    double
    energy(const double x_end) const
    {
      const double k = E * A / l, k_b = E * A / h_b;
      double e = 0.;
      for (unsigned int s = 0; s <= n_s; ++s)
        if (s * l < x_end)
          e += 0.5 * sphere_m[s] * v[s] * v[s];
      for (unsigned int t = 0; t < n_s; ++t)
        if (t * l < x_end)
          e += 0.5 * truss_w[t] * k * std::pow(u[t + 1] - u[t], 2);
      if (!(x_end < 1.))
        {
          for (unsigned int j = 0; j < n_nodes; ++j)
            e += 0.5 * node_m[j] * vb[j] * vb[j];
          for (unsigned int j = 0; j + 1 < n_nodes; ++j)
            e += 0.5 * bar_w[j] * k_b * std::pow(ub[j + 1] - ub[j], 2);
        }
      return e;
    }
  };


  /** A right-going pulse of width @p sigma [m] starting in the DEM-only
   * part; returns the energy left in it (x < a - w) once the pulse has
   * crossed the overlap, over the pulse's energy, and the largest energy
   * drift. The DEM-only part holds all that the overlap reflects; the bars
   * go on far enough for nothing to come back from their held end. */
  std::pair<double, double>
  pulse(const unsigned int m, const double sigma, const bool uniform = false)
  {
    const unsigned int span = std::ceil(6 * sigma / l);
    Fibre fibre(m, 3 * span + 100, 2 * span / M + 10, uniform);
    const double c         = std::sqrt(E / rho);
    const double a         = (3 * span + 100 + n_w * M) * l;
    const double x0        = a - n_w * M * l - 40 * l - 6 * sigma;
    const double amplitude = 1e-3 * sigma; // strain about 1e-3
    for (unsigned int s = 0; s <= fibre.n_s; ++s)
      {
        const double x = s * l, g = std::exp(-std::pow((x - x0) / sigma, 2));
        fibre.u[s] = amplitude * g;
        fibre.v[s] = c * amplitude * 2. * (x - x0) / (sigma * sigma) * g;
      }
    fibre.forces();
    const double e0 = fibre.energy(2.);
    const double dt = 0.5 * l / c;
    // Until the pulse is 6 sigma + 2 cells past the overlap's end.
    const double travel      = (a - x0) + 6 * sigma + 2 * M * l;
    const unsigned int steps = std::ceil(travel / c / dt);
    double drift             = 0.;
    for (unsigned int n = 0; n < steps; ++n)
      {
        fibre.step(dt);
        if (n % 100 == 0)
          drift = std::max(drift, std::abs(fibre.energy(2.) - e0) / e0);
      }
    const double left = fibre.energy(a - n_w * M * l - 0.5 * l) / e0;
    return {left, drift};
  }
} // namespace


int
main()
{
  // 1. The tridiagonal solve against the dense one.
  {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> uniform(0.5, 1.5);
    const unsigned int n = 9, n_p = 40;
    ChainConstraint chain(n);
    BridgingConstraint dense(n);
    for (unsigned int j = 0; j < n; ++j)
      {
        const double mass = uniform(random);
        chain.set_node_mass(j, mass);
        dense.set_node_mass(j, mass);
      }
    for (unsigned int i = 0; i < n_p; ++i)
      {
        const double mass    = uniform(random);
        const unsigned int j = i % (n - 1);
        const double xi      = (i % 3 == 0) ? 0. : uniform(random) - 0.5;
        chain.add_particle(mass, j, xi);
        if (xi == 0.)
          dense.add_particle(mass, {j}, {1.});
        else
          dense.add_particle(mass, {j, j + 1}, {1. - xi, xi});
      }
    chain.factorize();
    dense.factorize();
    std::vector<double> fn(n), fp(n_p), fn3(3 * n, 0.), fp3(3 * n_p, 0.);
    for (unsigned int j = 0; j < n; ++j)
      fn3[3 * j] = fn[j] = uniform(random) - 1.;
    for (unsigned int i = 0; i < n_p; ++i)
      fp3[3 * i] = fp[i] = uniform(random) - 1.;
    std::vector<double> an(n), ap(n_p), lp(n_p), an3(3 * n), ap3(3 * n_p),
      lp3(3 * n_p);
    chain.accelerations(fn.data(), fp.data(), an.data(), ap.data(), lp.data());
    dense.accelerations(fn3.data(),
                        fp3.data(),
                        an3.data(),
                        ap3.data(),
                        lp3.data());
    double worst = 0.;
    for (unsigned int j = 0; j < n; ++j)
      worst = std::max(worst, std::abs(an[j] - an3[3 * j]));
    for (unsigned int i = 0; i < n_p; ++i)
      worst = std::max(
        {worst, std::abs(ap[i] - ap3[3 * i]), std::abs(lp[i] - lp3[3 * i])});
    std::printf("tridiagonal against dense: largest difference %.3e\n", worst);
    check(worst <= 1e-12,
          "ChainConstraint's accelerations and multipliers equal the dense "
          "BridgingConstraint's for random masses, positions and forces "
          "(within 1e-12)");
  }

  // 2. Bars as fine as the trusses: the uniform fibre.
  {
    // A pulse of 10 truss lengths (its energy below the chain's cutoff,
    // so that the explicit step conserves it), against the same pulse on
    // the DEM fibre alone (its dispersive wake stays behind too).
    const double sigma              = 10 * l;
    const auto [left, drift]        = pulse(M, sigma);
    const auto [alone, alone_drift] = pulse(M, sigma, true);
    std::printf("one bar per truss: energy left behind %.3e (the DEM fibre "
                "alone: %.3e), drift %.3e (alone: %.3e)\n",
                left,
                alone,
                drift,
                alone_drift);
    check(std::abs(left - alone) <= 1e-10,
          "one bar per truss: a pulse of 10 truss lengths crosses the "
          "overlap and leaves behind what it leaves on the DEM fibre alone, "
          "within 1e-10 of its energy (no reflection)");
    check(drift <= 1e-5 && std::abs(drift - alone_drift) <= 1e-9,
          "one bar per truss: the pulse's energy conserved within 1e-5 (the "
          "explicit step's own oscillation, as on the DEM fibre alone "
          "within 1e-9)");
    for (const unsigned int m : {7u, 3u, 1u})
      for (const double sigma : {3 * l, 10 * M * l / 2.})
        {
          const auto [coarse, coarse_drift] = pulse(m, sigma);
          std::printf("%u bar(s) per cell, pulse of %.0f um: energy left "
                      "behind %.3e, drift %.3e\n",
                      m,
                      sigma * 1e6,
                      coarse,
                      coarse_drift);
        }
  }

  // 3. Momentum with random velocities.
  {
    Fibre fibre(3, 100, 4);
    std::mt19937 random(3);
    std::uniform_real_distribution<double> uniform(-1., 1.);
    for (double &x : fibre.v)
      x = uniform(random);
    // Velocities that satisfy the constraint: the spheres of the overlap
    // from the bar nodes.
    for (double &x : fibre.vb)
      x = uniform(random);
    for (unsigned int s = fibre.first; s <= fibre.n_s; ++s)
      {
        const double t = double(s - fibre.first) * l / fibre.h_b;
        const unsigned int j =
          std::min<unsigned int>(n_w * fibre.m - 1, unsigned(t + 1e-12));
        const double xi = t - j;
        fibre.v[s]      = (1. - xi) * fibre.vb[j] + xi * fibre.vb[j + 1];
      }
    fibre.vb.back() = 0.;
    // Momentum without the held far end.
    auto momentum = [&fibre](double &scale) {
      double p = 0.;
      scale    = 0.;
      for (unsigned int s = 0; s <= fibre.n_s; ++s)
        {
          p += fibre.sphere_m[s] * fibre.v[s];
          scale += std::abs(fibre.sphere_m[s] * fibre.v[s]);
        }
      for (unsigned int j = 0; j + 1 < fibre.n_nodes; ++j)
        {
          p += fibre.node_m[j] * fibre.vb[j];
          scale += std::abs(fibre.node_m[j] * fibre.vb[j]);
        }
      return p;
    };
    // A free chain: the far end's bar removed by zero weight.
    fibre.bar_w.back() = 0.;
    fibre.forces();
    double scale;
    const double p0 = momentum(scale);
    double worst = 0., violation = 0., speed = 0.;
    for (unsigned int n = 0; n < 4000; ++n)
      {
        fibre.step(0.2 * l / std::sqrt(E / rho));
        double s;
        worst = std::max(worst, std::abs(momentum(s) - p0) / scale);
      }
    for (unsigned int s = fibre.first; s <= fibre.n_s; ++s)
      {
        const double t = double(s - fibre.first) * l / fibre.h_b;
        const unsigned int j =
          std::min<unsigned int>(n_w * fibre.m - 1, unsigned(t + 1e-12));
        const double xi = t - j;
        violation       = std::max(violation,
                             std::abs(fibre.v[s] - (1. - xi) * fibre.vb[j] -
                                      xi * fibre.vb[j + 1]));
        speed           = std::max(speed, std::abs(fibre.v[s]));
      }
    std::printf("momentum: largest drift %.3e of sum |m v|, constraint "
                "violation %.3e of the largest speed\n",
                worst,
                violation / speed);
    check(worst <= 1e-12,
          "momentum: free fibre and bars with random velocities, 4000 steps: "
          "|P - P0| <= 1e-12 sum |m v|");
    check(violation <= 1e-12 * speed,
          "constraints: the overlap's spheres move with their bars within "
          "1e-12 of the largest speed");
  }
  return all_passed ? 0 : 1;
}
