#ifndef yarn_impact_fe_contact_h
#define yarn_impact_fe_contact_h

#include <yarn_impact/contact/contact_law.h>
#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/core/reproducible_sum.h>
#include <yarn_impact/fe/parameters.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <mpi.h>

#include <array>
#include <cstdint>
#include <vector>

namespace YarnImpact
{
  namespace FE
  {
    /**
     * Penalty contact of the yarn's lateral surface nodes with the rigid
     * cylindrical projectile (axis along z, at x = 0): each touching node
     * gets the force of the contact law `FE/Contact/Law` (by default
     * Contact::PenaltyCoulombLaw: a normal force proportional to the
     * penetration, optional viscous damping, optional explicit Coulomb
     * friction). What makes it the FE's contact is the constants, not the
     * law: the normal stiffness of a node is the penalty per area times its
     * share of the surface, and the damping and friction bound use its
     * lumped mass. Node-to-surface penalty is what explicit impact codes
     * use; the projectile is analytic, so no contact search is needed.
     */
    class ProjectileContact
    {
    public:
      /** @param parameters law, penalty [Pa/m], friction, damping ratio,
       * tangential stiffness ratio */
      explicit ProjectileContact(const ContactParameters &parameters);

      /**
       * Add an owned surface node that may touch the projectile.
       * @param dofs local indices of its x, y, z dofs
       * @param area its share of the lateral surface [m^2]
       * @param mass its lumped mass [kg]
       */
      void
      add_node(const std::array<unsigned int, 3> &dofs,
               const double area,
               const double mass);

      /**
       * Stable step [s] of a contact node on its penalty spring (the
       * smallest over all ranks of @p communicator), reduced for the
       * damping. Collective.
       */
      double
      stable_time_step(const MPI_Comm communicator) const;

      /**
       * Add the contact forces [N] on the nodes to @p force (owned
       * entries) at the current positions (@p reference_coordinate [m]
       * plus @p displacement [m]) and velocities [m/s]. Each node keeps
       * its force on the projectile and its contact energy, and adds its
       * damping and friction work over the step @p dt [s] to its own
       * total: per-node terms, so that their sums over the ranks can be
       * taken independently of the partition (add_reactions() and the
       * like). The law is chosen once per call, not per node.
       */
      void
      add_forces(
        const Projectile &projectile,
        const std::vector<double> &reference_coordinate,
        const dealii::LinearAlgebra::distributed::Vector<double> &displacement,
        const dealii::LinearAlgebra::distributed::Vector<double> &velocity,
        dealii::LinearAlgebra::distributed::Vector<double> &force,
        const double dt);

      /** Add the force of each node on the projectile along y [N], at the
       * last add_forces(), to sum @p i of @p sum. */
      void
      add_reactions(ReproducibleSum &sum, const unsigned int i) const;

      /** Add the contact energy of each node [J], at the last
       * add_forces(), to sum @p i of @p sum. */
      void
      add_energies(ReproducibleSum &sum, const unsigned int i) const;

      /** Add the damping and friction work of each node so far [J] to
       * sum @p i of @p sum. */
      void
      add_dissipated(ReproducibleSum &sum, const unsigned int i) const;

      /** Write the contact's state (tangential histories, which nodes
       * touch, each node's reaction, energy and dissipated work) to a
       * checkpoint. */
      void
      save(Checkpoint::Writer &out) const
      {
        out.put(history);
        out.put(touching);
        out.put(reaction);
        out.put(stored_energy);
        out.put(dissipated);
      }

      /** Read what save() wrote. */
      void
      load(Checkpoint::Reader &in)
      {
        in.get_same_size(history, "tangential history of the contact nodes");
        in.get_same_size(touching, "contact state of the contact nodes");
        in.get_same_size(reaction, "reactions of the contact nodes");
        in.get_same_size(stored_energy, "energies of the contact nodes");
        in.get_same_size(dissipated, "dissipated work of the contact nodes");
      }

    private:
      /** The contact constants of node @p k: the normal stiffness penalty
       * x area [N/m], the damping of its lumped mass on that spring
       * [N s/m], the tangential stiffness [N/m], the friction coefficient
       * [-] and its mass [kg]. */
      Contact::ContactConstants
      node_constants(const unsigned int k) const;

      const ContactParameters parameters;
      /** Local indices of the x, y, z dofs of each node. */
      std::vector<std::array<unsigned int, 3>> nodes;
      /** Surface area of each node [m^2]. */
      std::vector<double> area;
      /** Lumped mass of each node [kg]. */
      std::vector<double> mass;
      /** Tangential history of each node, 3 doubles, for a law that keeps
       * one [m]. */
      std::vector<double> history;
      /** Whether each node touched the projectile at the last
       * add_forces() (a new contact starts without history). */
      std::vector<std::uint8_t> touching;
      /** Force of each node on the projectile along y [N], contact energy
       * [J] (both at the last add_forces()) and damping and friction work
       * so far [J]. */
      std::vector<double> reaction, stored_energy, dissipated;
    };
  } // namespace FE
} // namespace YarnImpact

#endif
