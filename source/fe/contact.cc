#include <yarn_impact/fe/contact.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace YarnImpact
{
  namespace FE
  {
    ProjectileContact::ProjectileContact(const ContactParameters &parameters)
      : parameters(parameters)
    {}


    void
    ProjectileContact::add_node(const std::array<unsigned int, 3> &dofs,
                                const double node_area,
                                const double node_mass)
    {
      nodes.push_back(dofs);
      area.push_back(node_area);
      mass.push_back(node_mass);
      reaction.push_back(0.);
      penalty_energy.push_back(0.);
      dissipated.push_back(0.);
    }


    double
    ProjectileContact::stable_time_step(const MPI_Comm communicator) const
    {
      const double zeta = parameters.damping_ratio;
      double dt_c       = std::numeric_limits<double>::max();
      for (unsigned int k = 0; k < nodes.size(); ++k)
        dt_c =
          std::min(dt_c,
                   2. * std::sqrt(mass[k] / (parameters.penalty * area[k])));
      return dealii::Utilities::MPI::min(dt_c, communicator) *
             (std::sqrt(1. + zeta * zeta) - zeta);
    }


    void
    ProjectileContact::add_forces(
      const Projectile &projectile,
      const std::vector<double> &reference_coordinate,
      const dealii::LinearAlgebra::distributed::Vector<double> &displacement,
      const dealii::LinearAlgebra::distributed::Vector<double> &velocity,
      dealii::LinearAlgebra::distributed::Vector<double> &force,
      const double dt)
    {
      const auto &contact = parameters;
      const double R      = projectile.radius();
      const double yc     = projectile.axis_position();
      const double vp     = projectile.velocity();
      for (unsigned int k = 0; k < nodes.size(); ++k)
        {
          const auto &node  = nodes[k];
          reaction[k]       = 0.;
          penalty_energy[k] = 0.;
          const double px =
            reference_coordinate[node[0]] + displacement.local_element(node[0]);
          const double py =
            reference_coordinate[node[1]] + displacement.local_element(node[1]);
          const double dx = px, dy = py - yc;
          const double dist2 = dx * dx + dy * dy;
          if (dist2 >= R * R)
            continue;
          const double dist = std::sqrt(dist2);
          const double gap  = R - dist;
          const double nx = dx / dist, ny = dy / dist;
          const double stiffness = contact.penalty * area[k];
          // Relative velocity of the node with respect to the cylinder.
          const double rvx = velocity.local_element(node[0]);
          const double rvy = velocity.local_element(node[1]) - vp;
          const double rvz = velocity.local_element(node[2]);
          const double vn  = rvx * nx + rvy * ny;
          double fn        = stiffness * gap;
          if (contact.damping_ratio > 0.)
            {
              const double c =
                2. * contact.damping_ratio * std::sqrt(mass[k] * stiffness);
              const double fd = std::max(-c * vn, -fn);
              fn += fd;
              dissipated[k] += -fd * vn * dt;
            }
          double ft[3] = {0., 0., 0.};
          if (contact.friction > 0.)
            {
              const double vt[3] = {rvx - vn * nx, rvy - vn * ny, rvz};
              const double speed =
                std::sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
              // Coulomb's law, explicit: the friction force never exceeds
              // the one that stops the slip within the step (m |v_t| / dt),
              // so that sticking nodes do not chatter.
              const double limit = mass[k] * speed / dt;
              const double scale =
                speed > 0. ? -std::min(contact.friction * fn, limit) / speed
                           : 0.;
              for (unsigned int d = 0; d < 3; ++d)
                ft[d] = scale * vt[d];
              dissipated[k] +=
                -(ft[0] * vt[0] + ft[1] * vt[1] + ft[2] * vt[2]) * dt;
            }
          force.local_element(node[0]) += fn * nx + ft[0];
          force.local_element(node[1]) += fn * ny + ft[1];
          force.local_element(node[2]) += ft[2];
          reaction[k]       = -(fn * ny + ft[1]);
          penalty_energy[k] = 0.5 * stiffness * gap * gap;
        }
    }


    void
    ProjectileContact::add_reactions(ReproducibleSum &sum,
                                     const unsigned int i) const
    {
      for (const double r : reaction)
        sum.add(i, r);
    }


    void
    ProjectileContact::add_energies(ReproducibleSum &sum,
                                    const unsigned int i) const
    {
      for (const double e : penalty_energy)
        sum.add(i, e);
    }


    void
    ProjectileContact::add_dissipated(ReproducibleSum &sum,
                                      const unsigned int i) const
    {
      for (const double d : dissipated)
        sum.add(i, d);
    }
  } // namespace FE
} // namespace YarnImpact
