// The model of the coupled string of the test bridged_string.cc: one KM2
// fibre of spheres linked by trusses (the DEM's fibre) coupled by the
// bridging-domain constraint (coupling/bridging_domain.h, doc/hybrid.md
// section 2) to two-node finite elements, or either model alone, with a
// velocity-Verlet step and the energies, momenta and forces the test
// measures. A header, not a .cc: the test machinery compiles every .cc of
// this folder as a test.
#ifndef yarn_impact_tests_coupling_bridged_string_h
#define yarn_impact_tests_coupling_bridged_string_h

#include <yarn_impact/coupling/bridging_domain.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace BridgedString
{
  using YarnImpact::Coupling::BridgingConstraint;

  // KM2 fibre (doc/dem.md): E = 84.62 GPa, rho = 1440 kg/m^3, d = 12 um.
  constexpr double E = 84.62e9, rho = 1440., A = M_PI * 36e-12;
  constexpr double l   = 12e-6;
  const double c_axial = std::sqrt(E / rho);

  enum class Kind
  {
    hybrid,
    particles_only,
    continuum_only
  };

  struct Geometry
  {
    Kind kind;
    /** FE cell length [m]. */
    double h;
    /** Particle half-length a and overlap width w [m] (hybrid). */
    double a, w;
    /** Far end [m]. */
    double x_end;
    bool clamped;
  };

  /**
   * The particle weight beta of the string (doc/hybrid.md section 2.1):
   * 1 for x <= a - w, 0 for x >= a, linear between; here linear across the
   * overlap's cells, so that a truss straddling a node gives the ghost
   * force of section 2.4.
   */
  class OverlapWeight
  {
  public:
    OverlapWeight(const double a, const double w)
      : a(a)
      , w(w)
    {}

    double
    particle(const double x) const
    {
      return x <= a - w ? 1. : x >= a ? 0. : (a - x) / w;
    }

    /** Mean of the weight over [x0, x1] (exact: it is piecewise linear);
     * the point value for x0 == x1. */
    double
    mean_particle(const double x0, const double x1) const
    {
      if (x0 == x1)
        return particle(x0);
      return (integral(x1) - integral(x0)) / (x1 - x0);
    }

  private:
    double a, w;
    /** Integral of the weight from 0 to x >= 0: the plateau, then the
     * ramp's trapezoid. */
    double
    integral(const double x) const
    {
      if (x <= a - w)
        return x;
      const double s = std::min(x, a) - (a - w);
      return a - w + s - 0.5 * s * s / w;
    }
  };

  /** Quadratic energy of a perturbation d (relative displacement of the
   * two ends) of a segment of stiffness k under the pretension T0 along x,
   * with current rest-state length L1: (k d_x^2 + T0/L1 (d_y^2 + d_z^2))/2
   * [J]. */
  inline double
  perturbation_energy(const double *d,
                      const double k,
                      const double T0,
                      const double L1)
  {
    return 0.5 * (k * d[0] * d[0] + T0 / L1 * (d[1] * d[1] + d[2] * d[2]));
  }

  /**
   * The string: spheres (particles) and nodes (continuum), each with its
   * scaled mass, position and velocity; the trusses between consecutive
   * spheres and the elements between consecutive nodes with their weights;
   * the bridging constraint over the overlap.
   */
  class HybridString
  {
  public:
    HybridString(const Geometry &g, const double prestrain)
      : g(g)
      , weight(g.kind == Kind::hybrid ? g.a : 1.,
               g.kind == Kind::hybrid ? g.w : 1.)
      , prestrain(prestrain)
    {
      const bool particles      = g.kind != Kind::continuum_only;
      const bool continuum      = g.kind != Kind::particles_only;
      const double particle_end = g.kind == Kind::hybrid ? g.a : g.x_end;
      if (particles)
        {
          const unsigned int P = std::lround(particle_end / l);
          for (unsigned int i = 0; i <= P; ++i)
            Xs.push_back(i * l);
          for (unsigned int i = 0; i <= P; ++i)
            {
              const double natural =
                rho * A * l * ((i == 0 || i == P) ? 0.5 : 1.);
              ms.push_back(beta(Xs[i], Xs[i]) * natural);
            }
          for (unsigned int i = 0; i < P; ++i)
            truss_weight.push_back(beta(Xs[i], Xs[i + 1]));
        }
      if (continuum)
        {
          const double start   = g.kind == Kind::hybrid ? g.a - g.w : 0.;
          const unsigned int N = std::lround((g.x_end - start) / g.h);
          for (unsigned int J = 0; J <= N; ++J)
            Xn.push_back(start + J * g.h);
          Mn.assign(N + 1, 0.);
          for (unsigned int e = 0; e < N; ++e)
            {
              // Weighted lumped mass: rho A int (1 - beta) N_J, exact for a
              // weight linear over the element.
              const double c0 = 1. - beta(Xn[e], Xn[e]),
                           c1 = 1. - beta(Xn[e + 1], Xn[e + 1]);
              Mn[e] += rho * A * g.h * (2. * c0 + c1) / 6.;
              Mn[e + 1] += rho * A * g.h * (c0 + 2. * c1) / 6.;
              element_weight.push_back(1. - beta(Xn[e], Xn[e + 1]));
            }
        }
      if (g.kind == Kind::hybrid)
        setup_constraint();
      xs.resize(3 * Xs.size());
      vs.assign(3 * Xs.size(), 0.);
      xn.resize(3 * Xn.size());
      vn.assign(3 * Xn.size(), 0.);
      for (unsigned int i = 0; i < Xs.size(); ++i)
        xs[3 * i]            = (1. + prestrain) * Xs[i],
               xs[3 * i + 1] = xs[3 * i + 2] = 0.;
      for (unsigned int J = 0; J < Xn.size(); ++J)
        xn[3 * J]            = (1. + prestrain) * Xn[J],
               xn[3 * J + 1] = xn[3 * J + 2] = 0.;
      rest_xs = xs;
      rest_xn = xn;
      compute_forces();
    }

    /** The particle weight's mean over [x0, x1] (a point for x0 == x1). */
    double
    beta(const double x0, const double x1) const
    {
      if (g.kind == Kind::particles_only)
        return 1.;
      if (g.kind == Kind::continuum_only)
        return 0.;
      return weight.mean_particle(x0, x1);
    }

    /** The overlap element holding sphere @p i, and the sphere's local
     * coordinate in it, in [0, 1]. */
    void
    locate(const unsigned int i, unsigned int &e, double &x1) const
    {
      const double s = (Xs[i] - Xn[0]) / g.h;
      e  = s <= 0. ? 0u : std::min<unsigned int>(std::floor(s), n_coupled - 2);
      x1 = std::clamp((Xs[i] - Xn[e]) / g.h, 0., 1.);
    }

    void
    setup_constraint()
    {
      // Coupled nodes: those of the overlap, a - w <= X <= a.
      n_coupled = 0;
      while (n_coupled < Xn.size() && Xn[n_coupled] <= g.a * (1. + 1e-14))
        ++n_coupled;
      constraint = BridgingConstraint(n_coupled);
      for (unsigned int J = 0; J < n_coupled; ++J)
        constraint.set_node_mass(J, Mn[J]);
      slave.assign(Xs.size(), -1);
      for (unsigned int i = 0; i < Xs.size(); ++i)
        if (Xs[i] >= (g.a - g.w) * (1. - 1e-12) && Xs[i] <= g.a * (1. + 1e-12))
          {
            unsigned int e;
            double x1;
            locate(i, e, x1);
            std::vector<unsigned int> nodes;
            std::vector<double> values;
            if (1. - x1 != 0.)
              nodes.push_back(e), values.push_back(1. - x1);
            if (x1 != 0.)
              nodes.push_back(e + 1), values.push_back(x1);
            slave[i] = constraint.add_particle(ms[i], nodes, values);
            slaved.push_back(i);
          }
      constraint.factorize();
    }

    /** Fixed ends: the first and the last degree of freedom of the string. */
    bool
    sphere_fixed(const unsigned int i) const
    {
      return g.clamped &&
             (i == 0 || (g.kind == Kind::particles_only && i + 1 == Xs.size()));
    }
    bool
    node_fixed(const unsigned int J) const
    {
      return g.clamped &&
             (J + 1 == Xn.size() || (g.kind == Kind::continuum_only && J == 0));
    }

    void
    compute_forces()
    {
      fs.assign(xs.size(), 0.);
      fn.assign(xn.size(), 0.);
      segment_forces(xs, truss_weight, E * A / l, l, fs);
      segment_forces(xn, element_weight, E * A / g.h, g.h, fn);
      as.assign(xs.size(), 0.);
      an.assign(xn.size(), 0.);
      for (unsigned int i = 0; i < Xs.size(); ++i)
        if ((g.kind != Kind::hybrid || slave[i] < 0) && !sphere_fixed(i))
          for (unsigned int d = 0; d < 3; ++d)
            as[3 * i + d] = fs[3 * i + d] / ms[i];
      for (unsigned int J = (g.kind == Kind::hybrid ? n_coupled : 0);
           J < Xn.size();
           ++J)
        if (!node_fixed(J))
          for (unsigned int d = 0; d < 3; ++d)
            an[3 * J + d] = fn[3 * J + d] / Mn[J];
      if (g.kind == Kind::hybrid)
        {
          std::vector<double> fp(3 * slaved.size()), ap(3 * slaved.size());
          lambda.resize(3 * slaved.size());
          for (unsigned int k = 0; k < slaved.size(); ++k)
            for (unsigned int d = 0; d < 3; ++d)
              fp[3 * k + d] = fs[3 * slaved[k] + d];
          constraint.accelerations(fn.data(),
                                   fp.data(),
                                   an.data(),
                                   ap.data(),
                                   lambda.data());
          for (unsigned int k = 0; k < slaved.size(); ++k)
            for (unsigned int d = 0; d < 3; ++d)
              as[3 * slaved[k] + d] = ap[3 * k + d];
        }
    }

    static void
    segment_forces(const std::vector<double> &x,
                   const std::vector<double> &w,
                   const double k,
                   const double L0,
                   std::vector<double> &f)
    {
      for (unsigned int t = 0; t < w.size(); ++t)
        {
          const double e[3] = {x[3 * t + 3] - x[3 * t],
                               x[3 * t + 4] - x[3 * t + 1],
                               x[3 * t + 5] - x[3 * t + 2]};
          const double len = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
          const double s   = w[t] * k * (len - L0) / len;
          for (unsigned int d = 0; d < 3; ++d)
            {
              f[3 * t + d] += s * e[d];
              f[3 * t + 3 + d] -= s * e[d];
            }
        }
    }

    /** One velocity-Verlet step. */
    void
    step(const double dt)
    {
      for (unsigned int k = 0; k < vs.size(); ++k)
        vs[k] += 0.5 * dt * as[k], xs[k] += dt * vs[k];
      for (unsigned int k = 0; k < vn.size(); ++k)
        vn[k] += 0.5 * dt * an[k], xn[k] += dt * vn[k];
      compute_forces();
      for (unsigned int k = 0; k < vs.size(); ++k)
        vs[k] += 0.5 * dt * as[k];
      for (unsigned int k = 0; k < vn.size(); ++k)
        vn[k] += 0.5 * dt * an[k];
    }

    /** Total energy: kinetic, with the scaled masses, plus the weighted
     * strain energy of trusses and elements [J]. */
    double
    energy() const
    {
      double e = 0.;
      for (unsigned int i = 0; i < Xs.size(); ++i)
        e += 0.5 * ms[i] * squared(&vs[3 * i]);
      for (unsigned int J = 0; J < Xn.size(); ++J)
        e += 0.5 * Mn[J] * squared(&vn[3 * J]);
      e += strain_energy(xs, truss_weight, E * A / l, l);
      e += strain_energy(xn, element_weight, E * A / g.h, g.h);
      return e;
    }

    static double
    squared(const double *v)
    {
      return v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    }

    static double
    strain_energy(const std::vector<double> &x,
                  const std::vector<double> &w,
                  const double k,
                  const double L0)
    {
      double e = 0.;
      for (unsigned int t = 0; t < w.size(); ++t)
        {
          const double d[3] = {x[3 * t + 3] - x[3 * t],
                               x[3 * t + 4] - x[3 * t + 1],
                               x[3 * t + 5] - x[3 * t + 2]};
          const double len  = std::sqrt(squared(d));
          e += 0.5 * w[t] * k * (len - L0) * (len - L0);
        }
      return e;
    }

    /** Linear momentum along @p d [kg m/s], and sum |m v| over all. */
    void
    momentum(const unsigned int d, double &p, double &scale) const
    {
      p = scale = 0.;
      for (unsigned int i = 0; i < Xs.size(); ++i)
        p += ms[i] * vs[3 * i + d], scale += ms[i] * std::abs(vs[3 * i + d]);
      for (unsigned int J = 0; J < Xn.size(); ++J)
        p += Mn[J] * vn[3 * J + d], scale += Mn[J] * std::abs(vn[3 * J + d]);
    }

    /**
     * Energy of the difference between this string and @p other (the same
     * model kind on the side measured) over the spheres (particles = true)
     * or nodes with reference position in [x0, x1] and the segments with
     * both ends there, as a quadratic form about the pretensioned rest state
     * [J]. With @p other null, the perturbation from the rest state. Also
     * the centroid of that energy along x [m].
     */
    double
    difference_energy(const HybridString *other,
                      const bool particles,
                      const double x0,
                      const double x1,
                      double *centroid = nullptr) const
    {
      const auto &X   = particles ? Xs : Xn;
      const auto &m   = particles ? ms : Mn;
      const auto &x   = particles ? xs : xn;
      const auto &v   = particles ? vs : vn;
      const auto &w   = particles ? truss_weight : element_weight;
      const double L0 = particles ? l : g.h;
      const double k  = E * A / L0;
      const double T0 = E * A * prestrain;
      std::vector<double> u(x.size()), dv(v.size());
      const auto &X_other = other ? (particles ? other->Xs : other->Xn) : X;
      const auto &x_other = other ? (particles ? other->xs : other->xn)
                                  : (particles ? rest_xs : rest_xn);
      const auto &v_other = other ? (particles ? other->vs : other->vn) : dv;
      // Match the other's entities by reference position.
      const double offset       = X.empty() ? 0. : X[0];
      const double offset_other = X_other.empty() ? 0. : X_other[0];
      const long shift          = std::lround((offset - offset_other) / L0);
      double energy = 0., moment = 0.;
      for (unsigned int i = 0; i < X.size(); ++i)
        {
          const long j = long(i) + shift;
          if (j < 0 || j >= long(X_other.size()))
            continue;
          for (unsigned int d = 0; d < 3; ++d)
            {
              u[3 * i + d]  = x[3 * i + d] - x_other[3 * j + d];
              dv[3 * i + d] = v[3 * i + d] - (other ? v_other[3 * j + d] : 0.);
            }
        }
      for (unsigned int i = 0; i < X.size(); ++i)
        if (X[i] >= x0 && X[i] <= x1)
          {
            const double e = 0.5 * m[i] * squared(&dv[3 * i]);
            energy += e, moment += e * X[i];
          }
      for (unsigned int t = 0; t < w.size(); ++t)
        if (X[t] >= x0 && X[t + 1] <= x1)
          {
            const double d[3] = {u[3 * t + 3] - u[3 * t],
                                 u[3 * t + 4] - u[3 * t + 1],
                                 u[3 * t + 5] - u[3 * t + 2]};
            const double e =
              w[t] * perturbation_energy(d, k, T0, (1. + prestrain) * L0);
            energy += e, moment += e * 0.5 * (X[t] + X[t + 1]);
          }
      if (centroid)
        *centroid = energy > 0. ? moment / energy : 0.;
      return energy;
    }

    /** Add a pulse of width @p lambda centred at @p xc, displacement in
     * component @p d with amplitude @p amp, travelling with speed @p c in
     * the direction @p sign, to every free sphere and node (the overlap is
     * left alone: the pulse starts away from it). */
    void
    add_pulse(const double xc,
              const double lambda,
              const unsigned int d,
              const double amp,
              const double c,
              const double sign)
    {
      auto shape = [&](const double X, double &f, double &df) {
        const double s = (X - xc) / lambda;
        f = df = 0.;
        if (std::abs(s) < 0.5)
          {
            f  = amp * std::cos(M_PI * s) * std::cos(M_PI * s);
            df = -amp * M_PI / lambda * std::sin(2. * M_PI * s);
          }
      };
      double f, df;
      for (unsigned int i = 0; i < Xs.size(); ++i)
        {
          shape(Xs[i], f, df);
          xs[3 * i + d] += f;
          vs[3 * i + d] += -sign * c * df;
        }
      for (unsigned int J = 0; J < Xn.size(); ++J)
        {
          shape(Xn[J], f, df);
          xn[3 * J + d] += f;
          vn[3 * J + d] += -sign * c * df;
        }
      compute_forces();
    }

    /** Largest net force on a degree of freedom of the coupled system:
     * free spheres and uncoupled nodes f, coupled nodes K a [N]. Also the
     * node of the largest one. */
    double
    largest_net_force(unsigned int *at_node = nullptr) const
    {
      double largest = 0.;
      for (unsigned int i = 0; i < Xs.size(); ++i)
        if ((g.kind != Kind::hybrid || slave[i] < 0) && !sphere_fixed(i))
          for (unsigned int d = 0; d < 3; ++d)
            largest = std::max(largest, std::abs(fs[3 * i + d]));
      std::vector<double> net(fn);
      if (g.kind == Kind::hybrid)
        for (unsigned int k = 0; k < slaved.size(); ++k)
          {
            // N^T f_p: the constrained spheres' forces on the nodes.
            unsigned int e;
            double x1;
            locate(slaved[k], e, x1);
            const unsigned int i = slaved[k];
            for (unsigned int d = 0; d < 3; ++d)
              {
                net[3 * e + d] += (1. - x1) * fs[3 * i + d];
                net[3 * e + 3 + d] += x1 * fs[3 * i + d];
              }
          }
      for (unsigned int J = 0; J < Xn.size(); ++J)
        if (!node_fixed(J))
          for (unsigned int d = 0; d < 3; ++d)
            if (std::abs(net[3 * J + d]) > largest)
              {
                largest = std::abs(net[3 * J + d]);
                if (at_node)
                  *at_node = J;
              }
      return largest;
    }

    /** Net force on node @p J of the coupled system [N], along x. */
    double
    net_force_x(const unsigned int J) const
    {
      double f = fn[3 * J];
      for (unsigned int k = 0; k < slaved.size(); ++k)
        {
          const unsigned int i = slaved[k];
          unsigned int e;
          double s;
          locate(i, e, s);
          if (e == J)
            f += (1. - s) * fs[3 * i];
          if (e + 1 == J)
            f += s * fs[3 * i];
        }
      return f;
    }

    double
    largest_violation() const
    {
      std::vector<double> vp(3 * slaved.size());
      for (unsigned int k = 0; k < slaved.size(); ++k)
        for (unsigned int d = 0; d < 3; ++d)
          vp[3 * k + d] = vs[3 * slaved[k] + d];
      return constraint.largest_violation(vn.data(), vp.data());
    }

    Geometry g;
    OverlapWeight weight;
    double prestrain;
    std::vector<double> Xs, ms, xs, vs, fs, as, truss_weight, rest_xs;
    std::vector<double> Xn, Mn, xn, vn, fn, an, element_weight, rest_xn;
    std::vector<int> slave;
    std::vector<unsigned int> slaved;
    unsigned int n_coupled = 0;
    BridgingConstraint constraint;
    std::vector<double> lambda;
  };
} // namespace BridgedString

#endif
