// Unit checks of the DEM building blocks: the hexagonal packing (exactly N
// fibres, all inside the ellipse, no overlap, symmetric) and the contact law
// (restitution coefficient from the damping, energy conservation without
// damping, Coulomb sliding).
#include <yarn_impact/contact/contact_law.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/dem/packing.h>

#include <cmath>
#include <iomanip>
#include <iostream>

using namespace YarnImpact;
using namespace YarnImpact::DEM;

namespace
{
  const char *
  verdict(const bool ok)
  {
    return ok ? "PASSED" : "FAILED";
  }

  void
  check_packing(const unsigned int n,
                const double a_y,
                const double a_z,
                const bool symmetric)
  {
    const double d = 12e-6;
    const auto c   = hexagonal_packing(n, d, a_y, a_z, 1.1, symmetric);
    bool inside = true, symmetric_about = true;
    for (unsigned int k = 0; k < c.size(); ++k)
      {
        const double rho =
          std::sqrt(std::pow(c.y[k] / a_y, 2) + std::pow(c.z[k] / a_z, 2));
        inside        = inside && rho <= c.scale * (1. + 1e-12);
        bool mirrored = false;
        for (unsigned int l = 0; l < c.size(); ++l)
          mirrored = mirrored || (std::abs(c.y[l] - c.y[k]) < 1e-15 &&
                                  std::abs(c.z[l] + c.z[k]) < 1e-15);
        symmetric_about = symmetric_about && mirrored;
      }
    const double gap = min_distance(c) / d;
    std::cout << std::fixed << std::setprecision(4) << "packing N = " << n
              << ": " << c.size() << " fibres, ellipse scale " << c.scale
              << ", smallest distance / d " << gap << ", inside "
              << verdict(inside) << ", no overlap "
              << verdict(gap >= 1. - 1e-12) << ", exactly N "
              << verdict(c.size() == n);
    if (symmetric)
      std::cout << ", symmetric about z = 0 " << verdict(symmetric_about);
    std::cout << '\n';
  }

  /** Two equal spheres meeting head-on; returns the restitution
   * coefficient and the largest relative energy error. */
  void
  collide(const double zeta, double &e, double &energy_error)
  {
    const double m = 1.9543e-12, k = 3.99e5, d = 12e-6, v0 = 10.;
    Contact::CundallStrackLaw law;
    law.k_n         = k;
    law.c_n         = 2. * zeta * std::sqrt(0.5 * m * k);
    law.k_t         = 2. / 7. * k;
    law.mu          = 0.2;
    const double dt = 0.02 * std::sqrt(m / k);
    double x[2] = {0., d + 1e-9}, v[2] = {0.5 * v0, -0.5 * v0}, f[2];
    double xi[3] = {0., 0., 0.}, dissipated = 0.;
    const double E0 = 0.25 * m * v0 * v0;
    energy_error    = 0.;
    auto forces     = [&]() {
      const double delta = d - (x[1] - x[0]);
      f[0] = f[1] = 0.;
      if (delta > 0.)
        {
          const double n[3]  = {-1., 0., 0.}; // from sphere 1 to sphere 0
          const double vr[3] = {v[0] - v[1], 0., 0.};
          double fc[3];
          Contact::contact_force(law, delta, n, vr, dt, xi, fc, dissipated);
          f[0] = fc[0];
          f[1] = -fc[0];
        }
      return delta > 0. ? 0.5 * k * delta * delta : 0.;
    };
    forces();
    for (unsigned int step = 0; step < 100000; ++step)
      {
        for (unsigned int a = 0; a < 2; ++a)
          {
            v[a] += 0.5 * dt * f[a] / m;
            x[a] += dt * v[a];
          }
        const double U = forces();
        for (unsigned int a = 0; a < 2; ++a)
          v[a] += 0.5 * dt * f[a] / m;
        const double K = 0.5 * m * (v[0] * v[0] + v[1] * v[1]);
        energy_error =
          std::max(energy_error, std::abs(K + U + dissipated - E0) / E0);
        if (x[1] - x[0] > d + 2e-9 && v[1] - v[0] > 0.)
          break;
      }
    e = (v[1] - v[0]) / v0;
  }

  /** A sphere pressed on a flat by a normal force N and pulled along it
   * by P: returns its mean tangential acceleration over the run. */
  double
  slide(const double P, const double N, const double mu)
  {
    const double m = 1.9543e-12, k = 3.99e5;
    Contact::CundallStrackLaw law;
    law.k_n         = k;
    law.c_n         = 2. * 0.5 * std::sqrt(m * k);
    law.k_t         = 2. / 7. * k;
    law.mu          = mu;
    const double dt = 0.05 * std::sqrt(m / k);
    // y: normal (flat at y = 0, sphere centre at y = r - delta), x: tangent
    double pos[2] = {0., -N / k}, vel[2] = {0., 0.}, frc[2];
    double xi[3] = {0., 0., 0.}, dissipated = 0.;
    auto forces = [&]() {
      const double delta = -pos[1];
      const double n[3]  = {0., 1., 0.};
      const double vr[3] = {vel[0], vel[1], 0.};
      double fc[3]       = {0., 0., 0.};
      if (delta > 0.)
        Contact::contact_force(law, delta, n, vr, dt, xi, fc, dissipated);
      frc[0] = fc[0] + P;
      frc[1] = fc[1] - N;
    };
    forces();
    const unsigned int n_steps = 20000;
    for (unsigned int step = 0; step < n_steps; ++step)
      {
        for (unsigned int a = 0; a < 2; ++a)
          {
            vel[a] += 0.5 * dt * frc[a] / m;
            pos[a] += dt * vel[a];
          }
        forces();
        for (unsigned int a = 0; a < 2; ++a)
          vel[a] += 0.5 * dt * frc[a] / m;
      }
    return vel[0] / (n_steps * dt);
  }
} // namespace

int
main()
{
  // The paper's ellipse with 400 fibres, a 40-fibre yarn, a single fibre.
  check_packing(400, 0.0575e-3, 0.267e-3, false);
  check_packing(400, 0.0575e-3, 0.267e-3, true);
  check_packing(40, 0.0182e-3, 0.0844e-3, false);
  check_packing(1, 6e-6, 6e-6, false);
  try
    {
      hexagonal_packing(1000, 12e-6, 0.0575e-3, 0.267e-3, 1.1);
      std::cout << "too many fibres: no error FAILED\n";
    }
  catch (const InputError &e)
    {
      std::cout << "too many fibres: " << e.what() << '\n';
    }

  for (const double zeta : {0.1, 0.3})
    {
      double e, error;
      const double expected =
        std::exp(-M_PI * zeta / std::sqrt(1. - zeta * zeta));
      collide(zeta, e, error);
      std::cout << std::setprecision(4) << "restitution, damping ratio " << zeta
                << ": " << e << ", theory " << expected << ", error within 2 % "
                << verdict(std::abs(e - expected) < 0.02 * expected) << '\n';
    }
  {
    double e, error;
    collide(0., e, error);
    std::cout << std::setprecision(4) << "undamped collision: restitution " << e
              << ", energy error below 0.1 % " << verdict(error < 1e-3) << '\n';
  }
  {
    const double m = 1.9543e-12, N = 1e-3, mu = 0.2;
    const double a_stick  = slide(0.5 * mu * N, N, mu);
    const double a_slide  = slide(2. * mu * N, N, mu);
    const double expected = (2. * mu * N - mu * N) / m;
    std::cout << std::setprecision(4) << "Coulomb: pulled by 0.5 mu N: sticks "
              << verdict(std::abs(a_stick) < 1e-3 * expected)
              << "; pulled by 2 mu N: acceleration / (mu N / m) "
              << a_slide / expected << " "
              << verdict(std::abs(a_slide / expected - 1.) < 0.01) << '\n';
  }
  return 0;
}
