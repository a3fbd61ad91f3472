#include <yarn_impact/contact/projectile_contact.h>
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
      history.insert(history.end(), 3, 0.);
      touching.push_back(0);
      reaction.push_back(0.);
      stored_energy.push_back(0.);
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


    inline Contact::ContactConstants
    ProjectileContact::node_constants(const unsigned int k) const
    {
      Contact::ContactConstants c;
      c.stiffness = parameters.penalty * area[k];
      c.damping   = (parameters.damping_ratio > 0.
                       ? Contact::critical_damping(parameters.damping_ratio,
                                                 mass[k],
                                                 c.stiffness)
                       : 0.);
      c.tangential_stiffness =
        parameters.tangential_stiffness_ratio * c.stiffness;
      c.friction = parameters.friction;
      c.mass     = mass[k];
      return c;
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
      // A surface node touches within the projectile's radius.
      const double R   = projectile.radius();
      const double yc  = projectile.axis_position();
      const double vp  = projectile.velocity();
      const auto shape = projectile.shape();
      const double x0  = projectile.offset_x();
      const double z0  = projectile.offset_z();
      // The law is chosen once per call; the loop over the nodes is
      // instantiated for each law.
      Contact::with_contact_law(parameters.law, [&](auto tag) {
        using Law                           = typename decltype(tag)::type;
        constexpr unsigned int history_size = Law::history_size;
        for (unsigned int k = 0; k < nodes.size(); ++k)
          {
            const auto &node = nodes[k];
            // From the impact point (x0 = 0 changes no bit).
            const double px = reference_coordinate[node[0]] +
                              displacement.local_element(node[0]) - x0;
            const double py = reference_coordinate[node[1]] +
                              displacement.local_element(node[1]);
            double delta, n[3];
            reaction[k]      = 0.;
            stored_energy[k] = 0.;
            // The sphere and the flat cylinder (Model = fabric) also see
            // the node's z.
            bool touches;
            if (shape == YarnImpact::Parameters::ProjectileShape::cylinder)
              touches = Contact::projectile_overlap(px, py, yc, R, delta, n);
            else
              {
                const double pz = reference_coordinate[node[2]] +
                                  displacement.local_element(node[2]) - z0;
                touches =
                  shape == YarnImpact::Parameters::ProjectileShape::sphere
                    ? Contact::sphere_overlap(px, py, pz, yc, R, delta, n)
                    : Contact::flat_cylinder_overlap(px,
                                                     py,
                                                     pz,
                                                     yc - R,
                                                     R,
                                                     delta,
                                                     n);
              }
            if (!touches)
              {
                if constexpr (history_size > 0)
                  touching[k] = 0;
                continue;
              }
            double *xi = &history[3 * k];
            if constexpr (history_size > 0)
              {
                // A new contact starts without tangential history.
                if (!touching[k])
                  for (unsigned int c = 0; c < history_size; ++c)
                    xi[c] = 0.;
                touching[k] = 1;
              }
            const double v[3] = {velocity.local_element(node[0]),
                                 velocity.local_element(node[1]),
                                 velocity.local_element(node[2])};
            double vr[3];
            Contact::relative_to_projectile(v, vp, vr);
            const Law law(node_constants(k));
            double f[3];
            Contact::contact_force(law, delta, n, vr, dt, xi, f, dissipated[k]);
            force.local_element(node[0]) += f[0];
            force.local_element(node[1]) += f[1];
            force.local_element(node[2]) += f[2];
            reaction[k]      = -f[1];
            stored_energy[k] = law.energy(delta, xi);
          }
      });
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
      for (const double e : stored_energy)
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
