// The overlap's tie in projection (coupling/bridging_domain.h,
// BridgingConstraint::set_projected, doc/hybrid.md section 2.5): a section
// of a yarn, 3 node layers of 4 nodes (2 cells of trilinear-like shape
// values: linear in x times bilinear in the section), 300 particles at
// random places with random masses, y and z tied in projection, x sphere by
// sphere.
//
// Physics checks, no recorded numbers: each line of `output` says what is
// checked against which bound and PASS or FAIL; the measured values go to
// stdout.
//
// 1. The nodes' accelerations are the strong tie's (K a = f + N^T f_p, the
//    same constraint without projection), within 1e-12 of their scale.
// 2. The projected constraint holds on the accelerations:
//    N^T M_p (a_p - N a_n) = 0 in y and z, within 1e-12 of N^T |f_p|; x is
//    tied sphere by sphere, a_p = N a_n, within 1e-12.
// 3. Momentum: the accelerations' total force equals the applied forces'
//    sum, within 1e-12 of sum |f|.
// 4. Dynamics: every particle and node on its own linear spring (random
//    stiffnesses) from random velocities that meet the constraints,
//    velocity Verlet for 20 000 steps at a hundredth of the fastest period:
//    the energy of the coupled system stays within 1e-3 of its initial
//    value (the explicit step's own oscillation, no drift), and the
//    projected constraints hold on the velocities within 1e-10 of the
//    largest speed, while the particles move relative to the continuum
//    (they do not under the strong tie).

#include <yarn_impact/coupling/bridging_domain.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

using namespace YarnImpact::Coupling;

namespace
{
  std::ofstream verdicts("output");
  bool all_passed = true;

  void
  check(const bool ok, const std::string &what)
  {
    verdicts << (ok ? "PASS " : "FAIL ") << what << '\n';
    std::printf("%s %s\n", ok ? "PASS" : "FAIL", what.c_str());
    all_passed = all_passed && ok;
  }

  constexpr unsigned int n_layers = 3, n_section = 4, n_particles = 300;
  constexpr unsigned int n_nodes = n_layers * n_section;

  /** The particles' nodes and shape values, masses, and the nodes'
   * masses, drawn once. */
  struct Set_up
  {
    std::vector<std::vector<unsigned int>> nodes;
    std::vector<std::vector<double>> values;
    std::vector<double> particle_mass, node_mass;

    explicit Set_up(std::mt19937 &random)
    {
      std::uniform_real_distribution<double> unit(0., 1.);
      for (unsigned int i = 0; i < n_particles; ++i)
        {
          const double x = 2. * unit(random), s = unit(random),
                       t          = unit(random);
          const unsigned int cell = std::min(1u, unsigned(x));
          const double xi         = x - cell;
          const double section[4] = {(1 - s) * (1 - t),
                                     s * (1 - t),
                                     (1 - s) * t,
                                     s * t};
          std::vector<unsigned int> n;
          std::vector<double> v;
          for (unsigned int side = 0; side < 2; ++side)
            for (unsigned int q = 0; q < 4; ++q)
              {
                n.push_back((cell + side) * n_section + q);
                v.push_back((side == 0 ? 1. - xi : xi) * section[q]);
              }
          nodes.push_back(n);
          values.push_back(v);
          particle_mass.push_back(1. + unit(random));
        }
      for (unsigned int j = 0; j < n_nodes; ++j)
        node_mass.push_back(20. * (0.5 + unit(random)));
    }

    BridgingConstraint
    constraint(const bool projected) const
    {
      BridgingConstraint c(n_nodes);
      for (unsigned int j = 0; j < n_nodes; ++j)
        c.set_node_mass(j, node_mass[j]);
      for (unsigned int d = 1; d < 3; ++d)
        c.set_projected(d, projected);
      for (unsigned int i = 0; i < n_particles; ++i)
        c.add_particle(particle_mass[i], nodes[i], values[i]);
      c.factorize();
      return c;
    }

    /** N^T M_p v_p - B v_n for component d (B = N^T M_p N). */
    std::vector<double>
    projected_residual(const std::vector<double> &node_v,
                       const std::vector<double> &particle_v,
                       const unsigned int d) const
    {
      std::vector<double> r(n_nodes, 0.);
      for (unsigned int i = 0; i < n_particles; ++i)
        {
          double interpolated = 0.;
          for (unsigned int p = 0; p < nodes[i].size(); ++p)
            interpolated += values[i][p] * node_v[3 * nodes[i][p] + d];
          for (unsigned int p = 0; p < nodes[i].size(); ++p)
            r[nodes[i][p]] += values[i][p] * particle_mass[i] *
                              (particle_v[3 * i + d] - interpolated);
        }
      return r;
    }
  };
} // namespace


int
main()
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> symmetric(-1., 1.);
  const Set_up set_up(random);
  const BridgingConstraint strong    = set_up.constraint(false),
                           projected = set_up.constraint(true);

  // 1-3: random forces.
  std::vector<double> f_n(3 * n_nodes), f_p(3 * n_particles);
  for (double &f : f_n)
    f = symmetric(random);
  for (double &f : f_p)
    f = symmetric(random);
  std::vector<double> a_n(3 * n_nodes), a_p(3 * n_particles), s_n(3 * n_nodes),
    s_p(3 * n_particles), lambda(3 * n_particles);
  strong.accelerations(f_n.data(), f_p.data(), s_n.data(), s_p.data());
  projected.accelerations(f_n.data(),
                          f_p.data(),
                          a_n.data(),
                          a_p.data(),
                          lambda.data());
  double node_error = 0., node_scale = 0.;
  for (unsigned int k = 0; k < a_n.size(); ++k)
    {
      node_error = std::max(node_error, std::abs(a_n[k] - s_n[k]));
      node_scale = std::max(node_scale, std::abs(s_n[k]));
    }
  std::printf("nodes: largest |a - a_strong| %.3e of %.3e\n",
              node_error,
              node_scale);
  check(node_error <= 1e-12 * node_scale,
        "the nodes' accelerations are the strong tie's (within 1e-12)");

  double residual = 0., force_scale = 0., x_error = 0.;
  for (unsigned int d = 1; d < 3; ++d)
    for (const double r : set_up.projected_residual(a_n, a_p, d))
      residual = std::max(residual, std::abs(r));
  for (unsigned int i = 0; i < n_particles; ++i)
    {
      force_scale += std::abs(f_p[3 * i + 1]) + std::abs(f_p[3 * i + 2]);
      x_error = std::max(x_error, std::abs(a_p[3 * i] - s_p[3 * i]));
    }
  std::printf("projected constraint on accelerations: %.3e (scale %.3e); "
              "x: %.3e\n",
              residual,
              force_scale,
              x_error);
  check(residual <= 1e-12 * force_scale,
        "N^T M_p (a_p - N a_n) = 0 in y and z (within 1e-12 of sum |f_p|)");
  check(x_error <= 1e-12 * node_scale,
        "x tied sphere by sphere: a_p = N a_n (within 1e-12)");

  double momentum_error = 0., momentum_scale = 0.;
  for (unsigned int d = 0; d < 3; ++d)
    {
      double total = 0., applied = 0.;
      for (unsigned int j = 0; j < n_nodes; ++j)
        {
          total += set_up.node_mass[j] * a_n[3 * j + d];
          applied += f_n[3 * j + d];
          momentum_scale += std::abs(f_n[3 * j + d]);
        }
      for (unsigned int i = 0; i < n_particles; ++i)
        {
          total += set_up.particle_mass[i] * a_p[3 * i + d];
          applied += f_p[3 * i + d];
          momentum_scale += std::abs(f_p[3 * i + d]);
        }
      momentum_error = std::max(momentum_error, std::abs(total - applied));
    }
  std::printf("momentum: |sum m a - sum f| %.3e of %.3e\n",
              momentum_error,
              momentum_scale);
  check(momentum_error <= 1e-12 * momentum_scale,
        "momentum: sum m a = sum f (within 1e-12 of sum |f|)");

  // 4: springs, velocity Verlet.
  std::uniform_real_distribution<double> unit(0., 1.);
  std::vector<double> k_n(3 * n_nodes), k_p(3 * n_particles);
  double omega2 = 0.;
  for (unsigned int k = 0; k < k_n.size(); ++k)
    {
      k_n[k] = 1. + unit(random);
      omega2 = std::max(omega2, k_n[k] / set_up.node_mass[k / 3]);
    }
  for (unsigned int k = 0; k < k_p.size(); ++k)
    {
      k_p[k] = 1. + unit(random);
      omega2 = std::max(omega2, k_p[k] / set_up.particle_mass[k / 3]);
    }
  const double dt = 0.01 * 2. * M_PI / std::sqrt(omega2);
  std::vector<double> u_n(3 * n_nodes, 0.), u_p(3 * n_particles, 0.),
    v_n(3 * n_nodes), v_p(3 * n_particles);
  // Velocities that meet the constraints: the nodes' interpolated, and in
  // y and z a random fine-scale part with no projection on the nodes
  // (zero acceleration of free particles under zero force leaves exactly
  // that part: a_p = f_p / m_p - N g with f_p = m_p w, w's projection
  // removed).
  for (double &v : v_n)
    v = symmetric(random);
  std::vector<double> w(3 * n_particles, 0.), zero_n(3 * n_nodes, 0.),
    fine(3 * n_particles);
  for (unsigned int i = 0; i < n_particles; ++i)
    for (unsigned int d = 1; d < 3; ++d)
      w[3 * i + d] = set_up.particle_mass[i] * symmetric(random);
  std::vector<double> ignored(3 * n_nodes), w_strong(3 * n_particles);
  projected.accelerations(zero_n.data(), w.data(), ignored.data(), fine.data());
  strong.accelerations(zero_n.data(),
                       w.data(),
                       ignored.data(),
                       w_strong.data());
  strong.interpolate(v_n.data(), v_p.data());
  for (unsigned int k = 0; k < v_p.size(); ++k)
    v_p[k] += fine[k] - w_strong[k];

  auto energy = [&]() {
    double e = 0.;
    for (unsigned int k = 0; k < v_n.size(); ++k)
      e += 0.5 * set_up.node_mass[k / 3] * v_n[k] * v_n[k] +
           0.5 * k_n[k] * u_n[k] * u_n[k];
    for (unsigned int k = 0; k < v_p.size(); ++k)
      e += 0.5 * set_up.particle_mass[k / 3] * v_p[k] * v_p[k] +
           0.5 * k_p[k] * u_p[k] * u_p[k];
    return e;
  };
  auto step_accelerations = [&]() {
    for (unsigned int k = 0; k < f_n.size(); ++k)
      f_n[k] = -k_n[k] * u_n[k];
    for (unsigned int k = 0; k < f_p.size(); ++k)
      f_p[k] = -k_p[k] * u_p[k];
    projected.accelerations(f_n.data(), f_p.data(), a_n.data(), a_p.data());
  };
  const double e0      = energy();
  double largest_speed = 0.;
  for (const double v : v_p)
    largest_speed = std::max(largest_speed, std::abs(v));
  step_accelerations();
  double energy_error = 0., violation = 0., relative_motion = 0.;
  std::vector<double> interpolated(3 * n_particles);
  for (unsigned int step = 0; step < 20000; ++step)
    {
      for (unsigned int k = 0; k < v_n.size(); ++k)
        {
          v_n[k] += 0.5 * dt * a_n[k];
          u_n[k] += dt * v_n[k];
        }
      for (unsigned int k = 0; k < v_p.size(); ++k)
        {
          v_p[k] += 0.5 * dt * a_p[k];
          u_p[k] += dt * v_p[k];
        }
      step_accelerations();
      for (unsigned int k = 0; k < v_n.size(); ++k)
        v_n[k] += 0.5 * dt * a_n[k];
      for (unsigned int k = 0; k < v_p.size(); ++k)
        v_p[k] += 0.5 * dt * a_p[k];
      energy_error = std::max(energy_error, std::abs(energy() - e0) / e0);
      for (unsigned int d = 1; d < 3; ++d)
        for (const double r : set_up.projected_residual(v_n, v_p, d))
          violation = std::max(violation, std::abs(r));
      strong.interpolate(v_n.data(), interpolated.data());
      for (unsigned int k = 0; k < v_p.size(); ++k)
        relative_motion =
          std::max(relative_motion, std::abs(v_p[k] - interpolated[k]));
    }
  double mass_scale = 0.;
  for (const double m : set_up.particle_mass)
    mass_scale += m;
  std::printf("dynamics: energy error %.3e, projected violation %.3e "
              "(scale %.3e), particles' speed relative to the continuum "
              "%.3e\n",
              energy_error,
              violation,
              mass_scale * largest_speed,
              relative_motion);
  check(energy_error <= 1e-3,
        "dynamics: energy within 1e-3 of its initial value over 20000 steps");
  check(violation <= 1e-10 * mass_scale * largest_speed,
        "dynamics: N^T M_p (v_p - N v_n) = 0 within 1e-10 of sum m |v|max");
  check(relative_motion >= 0.01 * largest_speed,
        "dynamics: the particles move relative to the continuum (at least "
        "1 % of the largest speed)");
  return all_passed ? 0 : 1;
}
