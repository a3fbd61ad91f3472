#include <yarn_impact/coupling/bridging_domain.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace YarnImpact
{
  namespace Coupling
  {
    BridgingConstraint::BridgingConstraint(const unsigned int n_nodes)
      : node_mass(n_nodes, 0.)
      , row_start(1, 0)
      , fixed(3 * std::size_t(n_nodes), 0)
    {}


    void
    BridgingConstraint::fix_component(const unsigned int node,
                                      const unsigned int d)
    {
      fixed.at(3 * std::size_t(node) + d) = 1;
      factorized                          = false;
    }


    void
    BridgingConstraint::set_node_mass(const unsigned int node,
                                      const double mass)
    {
      node_mass.at(node) = mass;
      factorized         = false;
    }


    unsigned int
    BridgingConstraint::add_particle(const double mass,
                                     const std::vector<unsigned int> &nodes,
                                     const std::vector<double> &shape_values)
    {
      if (nodes.size() != shape_values.size())
        throw std::invalid_argument(
          "BridgingConstraint::add_particle: as many shape values as nodes");
      for (const unsigned int n : nodes)
        if (n >= node_mass.size())
          throw std::out_of_range(
            "BridgingConstraint::add_particle: node index out of range");
      particle_mass.push_back(mass);
      column.insert(column.end(), nodes.begin(), nodes.end());
      value.insert(value.end(), shape_values.begin(), shape_values.end());
      row_start.push_back(column.size());
      factorized = false;
      return particle_mass.size() - 1;
    }


    void
    BridgingConstraint::factorize()
    {
      const unsigned int n = node_mass.size();
      for (unsigned int j = 0; j < n; ++j)
        if (!(node_mass[j] >= 0.))
          throw std::runtime_error("Bridging constraint: node " +
                                   std::to_string(j) +
                                   " has a negative or undefined mass");
      // K = diag(M) + N^T diag(m) N, dense (the coupled nodes are few).
      std::vector<double> K(std::size_t(n) * n, 0.);
      for (unsigned int j = 0; j < n; ++j)
        K[std::size_t(j) * n + j] = node_mass[j];
      for (unsigned int i = 0; i < particle_mass.size(); ++i)
        {
          if (!(particle_mass[i] >= 0.))
            throw std::runtime_error("Bridging constraint: particle " +
                                     std::to_string(i) +
                                     " has a negative or undefined mass");
          double sum = 0.;
          for (unsigned int p = row_start[i]; p < row_start[i + 1]; ++p)
            {
              // Shape functions that are non-negative within their cell
              // (Q1, and the string's linear elements) take values in
              // [0, 1] at a particle inside it.
              if (!(value[p] >= -1e-12 && value[p] <= 1. + 1e-12))
                throw std::runtime_error(
                  "Bridging constraint: shape value " +
                  std::to_string(value[p]) + " at particle " +
                  std::to_string(i) +
                  " is outside [0, 1] (the particle is not in the cell "
                  "given for it)");
              sum += value[p];
            }
          if (!(std::abs(sum - 1.) <= 1e-12))
            throw std::runtime_error(
              "Bridging constraint: the shape values at particle " +
              std::to_string(i) + " sum to " + std::to_string(sum) +
              ", not 1 (the particle is outside the continuum's mesh)");
          for (unsigned int p = row_start[i]; p < row_start[i + 1]; ++p)
            for (unsigned int q = row_start[i]; q < row_start[i + 1]; ++q)
              K[std::size_t(column[p]) * n + column[q]] +=
                particle_mass[i] * value[p] * value[q];
        }
      // One factor per distinct set of held nodes: K with their rows and
      // columns replaced by the identity.
      factors.clear();
      std::vector<std::vector<std::uint8_t>> held_sets;
      for (unsigned int d = 0; d < 3; ++d)
        {
          std::vector<std::uint8_t> held(n);
          for (unsigned int j = 0; j < n; ++j)
            held[j] = fixed[3 * std::size_t(j) + d];
          const auto known =
            std::find(held_sets.begin(), held_sets.end(), held);
          if (known != held_sets.end())
            {
              component_factor[d] = known - held_sets.begin();
              continue;
            }
          component_factor[d] = held_sets.size();
          held_sets.push_back(held);
          std::vector<double> factor = K;
          for (unsigned int j = 0; j < n; ++j)
            if (held[j])
              for (unsigned int k = 0; k < n; ++k)
                {
                  factor[std::size_t(j) * n + k] = (j == k ? 1. : 0.);
                  factor[std::size_t(k) * n + j] = (j == k ? 1. : 0.);
                }
          cholesky(factor, n);
          factors.push_back(std::move(factor));
        }
      factorized = true;
    }


    void
    BridgingConstraint::cholesky(std::vector<double> &factor,
                                 const unsigned int n)
    {
      // In place, K = L L^T, L in the lower triangle.
      for (unsigned int j = 0; j < n; ++j)
        {
          double *Lj = &factor[std::size_t(j) * n];
          double d   = Lj[j];
          for (unsigned int k = 0; k < j; ++k)
            d -= Lj[k] * Lj[k];
          if (!(d > 0.))
            throw std::runtime_error(
              "Bridging constraint: the coupled mass matrix is not positive "
              "definite at node " +
              std::to_string(j) +
              " (a coupled node with neither mass nor a particle near it)");
          Lj[j] = std::sqrt(d);
          for (unsigned int i = j + 1; i < n; ++i)
            {
              double *Li = &factor[std::size_t(i) * n];
              double s   = Li[j];
              for (unsigned int k = 0; k < j; ++k)
                s -= Li[k] * Lj[k];
              Li[j] = s / Lj[j];
            }
          for (unsigned int k = j + 1; k < n; ++k)
            Lj[k] = 0.;
        }
    }


    void
    BridgingConstraint::solve(double *b, const unsigned int d) const
    {
      const unsigned int n              = node_mass.size();
      const std::vector<double> &factor = factors[component_factor[d]];
      // A held node's right-hand side is zero: its acceleration is.
      for (unsigned int i = 0; i < n; ++i)
        if (fixed[3 * std::size_t(i) + d])
          b[3 * i + d] = 0.;
      // L y = b
      for (unsigned int i = 0; i < n; ++i)
        {
          const double *Li = &factor[std::size_t(i) * n];
          double s         = b[3 * i + d];
          for (unsigned int k = 0; k < i; ++k)
            s -= Li[k] * b[3 * k + d];
          b[3 * i + d] = s / Li[i];
        }
      // L^T x = y
      for (unsigned int i = n; i-- > 0;)
        {
          double s = b[3 * i + d];
          for (unsigned int k = i + 1; k < n; ++k)
            s -= factor[std::size_t(k) * n + i] * b[3 * k + d];
          b[3 * i + d] = s / factor[std::size_t(i) * n + i];
        }
    }


    void
    BridgingConstraint::accelerations(const double *node_force,
                                      const double *particle_force,
                                      double *node_acceleration,
                                      double *particle_acceleration,
                                      double *constraint_force) const
    {
      if (!factorized)
        throw std::logic_error(
          "BridgingConstraint::accelerations before factorize()");
      generalised_force(node_force, particle_force, node_acceleration);
      for (unsigned int d = 0; d < 3; ++d)
        solve(node_acceleration, d);
      interpolate(node_acceleration, particle_acceleration);
      if (constraint_force != nullptr)
        for (unsigned int i = 0; i < particle_mass.size(); ++i)
          for (unsigned int d = 0; d < 3; ++d)
            constraint_force[3 * i + d] =
              particle_mass[i] * particle_acceleration[3 * i + d] -
              particle_force[3 * i + d];
    }


    void
    BridgingConstraint::generalised_force(const double *node_force,
                                          const double *particle_force,
                                          double *out) const
    {
      std::copy(node_force, node_force + 3 * node_mass.size(), out);
      for (unsigned int i = 0; i < particle_mass.size(); ++i)
        for (unsigned int p = row_start[i]; p < row_start[i + 1]; ++p)
          for (unsigned int d = 0; d < 3; ++d)
            out[3 * column[p] + d] += value[p] * particle_force[3 * i + d];
    }


    void
    BridgingConstraint::interpolate(const double *node_values,
                                    double *particle_values) const
    {
      for (unsigned int i = 0; i < particle_mass.size(); ++i)
        {
          double v[3] = {0., 0., 0.};
          for (unsigned int p = row_start[i]; p < row_start[i + 1]; ++p)
            for (unsigned int d = 0; d < 3; ++d)
              v[d] += value[p] * node_values[3 * column[p] + d];
          for (unsigned int d = 0; d < 3; ++d)
            particle_values[3 * i + d] = v[d];
        }
    }


    double
    BridgingConstraint::largest_violation(const double *node_velocity,
                                          const double *particle_velocity) const
    {
      std::vector<double> v(3 * particle_mass.size());
      interpolate(node_velocity, v.data());
      double largest = 0.;
      for (unsigned int k = 0; k < v.size(); ++k)
        largest = std::max(largest, std::abs(particle_velocity[k] - v[k]));
      return largest;
    }


    std::size_t
    BridgingConstraint::memory_consumption() const
    {
      std::size_t factor_entries = 0;
      for (const std::vector<double> &factor : factors)
        factor_entries += factor.capacity();
      return sizeof(double) * (factor_entries + node_mass.capacity() +
                               particle_mass.capacity() + value.capacity()) +
             sizeof(unsigned int) * (row_start.capacity() + column.capacity()) +
             fixed.capacity();
    }


    ChainConstraint::ChainConstraint(const unsigned int n_nodes)
      : node_mass(n_nodes, 0.)
    {}


    void
    ChainConstraint::set_node_mass(const unsigned int node, const double mass)
    {
      node_mass.at(node) = mass;
      factorized         = false;
    }


    unsigned int
    ChainConstraint::add_particle(const double mass,
                                  const unsigned int node,
                                  const double xi)
    {
      if (!(xi >= 0. && xi <= 1.) ||
          node + (xi > 0. ? 1u : 0u) >= node_mass.size())
        throw std::out_of_range("ChainConstraint::add_particle: particle "
                                "outside the chain");
      particle_mass.push_back(mass);
      particle_node.push_back(node);
      particle_xi.push_back(xi);
      factorized = false;
      return particle_mass.size() - 1;
    }


    void
    ChainConstraint::factorize()
    {
      const unsigned int n = node_mass.size();
      std::vector<double> diagonal(node_mass), off(n, 0.);
      for (unsigned int i = 0; i < particle_mass.size(); ++i)
        {
          const double m = particle_mass[i], xi = particle_xi[i];
          const unsigned int j = particle_node[i];
          if (!(m >= 0.))
            throw std::runtime_error("Chain constraint: particle " +
                                     std::to_string(i) +
                                     " has a negative or undefined mass");
          diagonal[j] += m * (1. - xi) * (1. - xi);
          if (xi > 0.)
            {
              diagonal[j + 1] += m * xi * xi;
              off[j + 1] += m * xi * (1. - xi);
            }
        }
      d.assign(n, 0.);
      l.assign(n, 0.);
      for (unsigned int j = 0; j < n; ++j)
        {
          if (j > 0)
            l[j] = off[j] / d[j - 1];
          d[j] = diagonal[j] - (j > 0 ? l[j] * off[j] : 0.);
          if (!(d[j] > 0.))
            throw std::runtime_error("Chain constraint: K is not positive "
                                     "definite at node " +
                                     std::to_string(j) +
                                     " (neither mass nor a particle there)");
        }
      factorized = true;
    }


    void
    ChainConstraint::generalised_force(const double *node_force,
                                       const double *particle_force,
                                       double *out) const
    {
      std::copy(node_force, node_force + node_mass.size(), out);
      for (unsigned int i = 0; i < particle_mass.size(); ++i)
        {
          const unsigned int j = particle_node[i];
          const double xi      = particle_xi[i];
          out[j] += (1. - xi) * particle_force[i];
          if (xi > 0.)
            out[j + 1] += xi * particle_force[i];
        }
    }


    void
    ChainConstraint::accelerations(const double *node_force,
                                   const double *particle_force,
                                   double *node_acceleration,
                                   double *particle_acceleration,
                                   double *constraint_force) const
    {
      if (!factorized)
        throw std::logic_error("ChainConstraint: factorize() first");
      const unsigned int n = node_mass.size();
      double *a            = node_acceleration;
      generalised_force(node_force, particle_force, a);
      for (unsigned int j = 1; j < n; ++j)
        a[j] -= l[j] * a[j - 1];
      for (unsigned int j = 0; j < n; ++j)
        a[j] /= d[j];
      for (unsigned int j = n - 1; j-- > 0;)
        a[j] -= l[j + 1] * a[j + 1];
      for (unsigned int i = 0; i < particle_mass.size(); ++i)
        {
          const unsigned int j = particle_node[i];
          const double xi      = particle_xi[i];
          const double ai = (1. - xi) * a[j] + (xi > 0. ? xi * a[j + 1] : 0.);
          particle_acceleration[i] = ai;
          if (constraint_force != nullptr)
            constraint_force[i] = particle_mass[i] * ai - particle_force[i];
        }
    }
  } // namespace Coupling
} // namespace YarnImpact
