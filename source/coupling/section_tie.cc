// The overlap's transverse tie on the section's coarse modes
// (doc/hybrid.md section 2.5): a few multipliers per node layer, one
// small constant system.

#include <yarn_impact/coupling/section_tie.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace YarnImpact
{
  namespace Coupling
  {
    SectionTie::SectionTie(const unsigned int n_nodes,
                           const unsigned int n_layers,
                           const unsigned int n_modes)
      : n_layers(n_layers)
      , n_modes(n_modes)
      , node_mass(n_nodes, 0.)
      , fixed(3 * std::size_t(n_nodes), 0)
      , node_rows(std::size_t(n_layers) * n_modes * n_nodes, 0.)
    {
      if (n_modes != 1 && n_modes != 3)
        throw std::invalid_argument("SectionTie: 1 or 3 section modes");
    }


    void
    SectionTie::set_node_mass(const unsigned int node, const double mass)
    {
      node_mass.at(node) = mass;
      factorized         = false;
    }


    void
    SectionTie::fix_component(const unsigned int node, const unsigned int d)
    {
      fixed.at(3 * std::size_t(node) + d) = 1;
      factorized                          = false;
    }


    void
    SectionTie::particle_rows(const unsigned int i,
                              unsigned int *rows,
                              double *values) const
    {
      // Two layers (the hat functions of the cell's two node layers),
      // n_modes modes each; a particle on a layer has zeros on the next.
      const unsigned int l = particle_layer[i];
      const double xi      = particle_xi[i];
      for (unsigned int side = 0; side < 2; ++side)
        for (unsigned int k = 0; k < n_modes; ++k)
          {
            const unsigned int layer = std::min(l + side, n_layers - 1);
            rows[side * n_modes + k] = layer * n_modes + k;
            values[side * n_modes + k] =
              (side == 0 ? 1. - xi : (l + 1 < n_layers ? xi : 0.)) *
              particle_modes[i][k];
          }
    }


    unsigned int
    SectionTie::add_particle(const double mass,
                             const unsigned int layer,
                             const double xi,
                             const std::array<double, 3> &modes,
                             const std::vector<unsigned int> &nodes,
                             const std::vector<double> &shape_values)
    {
      if (nodes.size() != shape_values.size() || layer >= n_layers ||
          !(xi >= 0. && xi <= 1.) || modes[0] != 1.)
        throw std::invalid_argument("SectionTie::add_particle: a particle "
                                    "outside the layers, or bad modes");
      if (!(mass >= 0.))
        throw std::runtime_error("Section tie: a particle has a negative or "
                                 "undefined mass");
      double sum = 0.;
      for (unsigned int p = 0; p < nodes.size(); ++p)
        {
          if (nodes[p] >= node_mass.size())
            throw std::out_of_range("SectionTie::add_particle: node index");
          sum += shape_values[p];
        }
      // The multipliers' forces cancel only if the shape values sum to 1.
      if (!(std::abs(sum - 1.) <= 1e-12))
        throw std::runtime_error("Section tie: the shape values at particle " +
                                 std::to_string(particle_mass.size()) +
                                 " sum to " + std::to_string(sum) + ", not 1");
      particle_mass.push_back(mass);
      particle_layer.push_back(layer);
      particle_xi.push_back(xi);
      particle_modes.push_back(modes);
      const unsigned int i = particle_mass.size() - 1;
      unsigned int rows[6];
      double values[6];
      particle_rows(i, rows, values);
      const std::size_t n = node_mass.size();
      // G_f = G_d N: row r of node J gains c_ri N_J(X_i).
      for (unsigned int e = 0; e < 2 * n_modes; ++e)
        for (unsigned int p = 0; p < nodes.size(); ++p)
          node_rows[rows[e] * n + nodes[p]] +=
            mass * values[e] * shape_values[p];
      factorized = false;
      return i;
    }


    void
    SectionTie::factorize()
    {
      const unsigned int n_r = n_rows();
      const std::size_t n    = node_mass.size();
      for (std::size_t j = 0; j < n; ++j)
        if (!(node_mass[j] > 0.))
          throw std::runtime_error("Section tie: node " + std::to_string(j) +
                                   " has no positive mass");
      // The spheres' part, G_d M_d^-1 G_d^T = sum_i m_i g_i g_i^T with
      // g_ri = phi_l psi_k, the same for y and z.
      std::vector<double> spheres(std::size_t(n_r) * n_r, 0.);
      unsigned int rows[6];
      double values[6];
      for (unsigned int i = 0; i < particle_mass.size(); ++i)
        {
          particle_rows(i, rows, values);
          for (unsigned int e = 0; e < 2 * n_modes; ++e)
            for (unsigned int q = 0; q < 2 * n_modes; ++q)
              spheres[rows[e] * n_r + rows[q]] +=
                particle_mass[i] * values[e] * values[q];
        }
      for (unsigned int c = 0; c < 2; ++c)
        {
          const unsigned int d  = c + 1;
          std::vector<double> A = spheres;
          // The continuum's part, G_f M_f^-1 G_f^T over its free nodes (a
          // held node does not move).
          for (unsigned int r = 0; r < n_r; ++r)
            for (unsigned int s = 0; s <= r; ++s)
              {
                double sum = 0.;
                for (std::size_t j = 0; j < n; ++j)
                  if (!fixed[3 * j + d])
                    sum += node_rows[r * n + j] * node_rows[s * n + j] /
                           node_mass[j];
                A[r * n_r + s] += sum;
                if (s != r)
                  A[s * n_r + r] += sum;
              }
          // Cholesky in place, L in the lower triangle.
          for (unsigned int j = 0; j < n_r; ++j)
            {
              double *Lj  = &A[std::size_t(j) * n_r];
              double diag = Lj[j];
              for (unsigned int k = 0; k < j; ++k)
                diag -= Lj[k] * Lj[k];
              if (!(diag > 0.))
                throw std::runtime_error(
                  "Section tie: the multiplier system is singular at row " +
                  std::to_string(j) +
                  " (a layer without particles, or section modes its "
                  "particles do not span)");
              Lj[j] = std::sqrt(diag);
              for (unsigned int i = j + 1; i < n_r; ++i)
                {
                  double *Li = &A[std::size_t(i) * n_r];
                  double s   = Li[j];
                  for (unsigned int k = 0; k < j; ++k)
                    s -= Li[k] * Lj[k];
                  Li[j] = s / Lj[j];
                }
            }
          factors[c] = std::move(A);
        }
      factorized = true;
    }


    void
    SectionTie::accelerations(const double *node_force,
                              const double *particle_force,
                              double *node_acceleration,
                              double *particle_acceleration,
                              double *constraint_force,
                              double *node_reaction) const
    {
      if (!factorized)
        throw std::logic_error("SectionTie::accelerations before factorize()");
      const unsigned int n_r = n_rows();
      const std::size_t n    = node_mass.size();
      const std::size_t n_p  = particle_mass.size();
      unsigned int rows[6];
      double values[6];
      std::vector<double> mu(n_r);
      for (std::size_t j = 0; j < n; ++j)
        {
          node_acceleration[3 * j] = node_force[3 * j] / node_mass[j];
          node_reaction[3 * j]     = 0.;
        }
      for (std::size_t i = 0; i < n_p; ++i)
        {
          particle_acceleration[3 * i] =
            particle_force[3 * i] / particle_mass[i];
          constraint_force[3 * i] = 0.;
        }
      for (unsigned int c = 0; c < 2; ++c)
        {
          const unsigned int d = c + 1;
          // mu = -A^-1 (G_d M_d^-1 f_d - G_f M_f^-1 f_f), the
          // constraints' rate of change under the free accelerations.
          std::fill(mu.begin(), mu.end(), 0.);
          for (std::size_t i = 0; i < n_p; ++i)
            {
              particle_rows(i, rows, values);
              for (unsigned int e = 0; e < 2 * n_modes; ++e)
                mu[rows[e]] -= values[e] * particle_force[3 * i + d];
            }
          for (unsigned int r = 0; r < n_r; ++r)
            {
              double s = 0.;
              for (std::size_t j = 0; j < n; ++j)
                if (!fixed[3 * j + d])
                  s +=
                    node_rows[r * n + j] * node_force[3 * j + d] / node_mass[j];
              mu[r] += s;
            }
          const std::vector<double> &L = factors[c];
          for (unsigned int r = 0; r < n_r; ++r)
            {
              double s = mu[r];
              for (unsigned int k = 0; k < r; ++k)
                s -= L[std::size_t(r) * n_r + k] * mu[k];
              mu[r] = s / L[std::size_t(r) * n_r + r];
            }
          for (unsigned int r = n_r; r-- > 0;)
            {
              double s = mu[r];
              for (unsigned int k = r + 1; k < n_r; ++k)
                s -= L[std::size_t(k) * n_r + r] * mu[k];
              mu[r] = s / L[std::size_t(r) * n_r + r];
            }
          // The spheres: f + G_d^T mu; the nodes: f - G_f^T mu.
          for (std::size_t i = 0; i < n_p; ++i)
            {
              particle_rows(i, rows, values);
              double g = 0.;
              for (unsigned int e = 0; e < 2 * n_modes; ++e)
                g += values[e] * mu[rows[e]];
              constraint_force[3 * i + d] = particle_mass[i] * g;
              particle_acceleration[3 * i + d] =
                particle_force[3 * i + d] / particle_mass[i] + g;
            }
          for (std::size_t j = 0; j < n; ++j)
            {
              double g = 0.;
              for (unsigned int r = 0; r < n_r; ++r)
                g += node_rows[r * n + j] * mu[r];
              node_reaction[3 * j + d] = g;
              node_acceleration[3 * j + d] =
                fixed[3 * j + d] ? 0.
                                 : (node_force[3 * j + d] - g) / node_mass[j];
            }
        }
    }


    double
    SectionTie::largest_violation(const double *node_velocity,
                                  const double *particle_velocity) const
    {
      const unsigned int n_r = n_rows();
      const std::size_t n    = node_mass.size();
      unsigned int rows[6];
      double values[6];
      double largest = 0.;
      for (unsigned int d = 1; d < 3; ++d)
        {
          std::vector<double> g(n_r, 0.), scale(n_r, 0.);
          for (std::size_t i = 0; i < particle_mass.size(); ++i)
            {
              particle_rows(i, rows, values);
              for (unsigned int e = 0; e < 2 * n_modes; ++e)
                {
                  g[rows[e]] +=
                    particle_mass[i] * values[e] * particle_velocity[3 * i + d];
                  if (rows[e] % n_modes == 0)
                    scale[rows[e]] += particle_mass[i] * values[e];
                }
            }
          for (unsigned int r = 0; r < n_r; ++r)
            {
              for (std::size_t j = 0; j < n; ++j)
                g[r] -= node_rows[r * n + j] * node_velocity[3 * j + d];
              largest =
                std::max(largest, std::abs(g[r]) / scale[r - r % n_modes]);
            }
        }
      return largest;
    }
  } // namespace Coupling
} // namespace YarnImpact
