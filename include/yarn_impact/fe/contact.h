#ifndef yarn_impact_fe_contact_h
#define yarn_impact_fe_contact_h

#include <yarn_impact/core/projectile.h>
#include <yarn_impact/core/reproducible_sum.h>
#include <yarn_impact/fe/parameters.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <mpi.h>

#include <array>
#include <vector>

namespace YarnImpact
{
  namespace FE
  {
    /**
     * Penalty contact of the yarn's lateral surface nodes with the rigid
     * cylindrical projectile (axis along z, at x = 0): a normal force
     * proportional to the penetration and the node's surface area, with
     * optional viscous damping and optional explicit Coulomb friction.
     * Node-to-surface penalty is what explicit impact codes use; the
     * projectile is analytic, so no contact search is needed.
     */
    class ProjectileContact
    {
    public:
      /** @param parameters penalty [Pa/m], friction, damping ratio */
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
       * its force on the projectile and its penalty energy, and adds its
       * damping and friction work over the step @p dt [s] to its own
       * total: per-node terms, so that their sums over the ranks can be
       * taken independently of the partition (add_reactions() and the
       * like).
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

      /** Add the penalty energy of each node [J], at the last
       * add_forces(), to sum @p i of @p sum. */
      void
      add_energies(ReproducibleSum &sum, const unsigned int i) const;

      /** Add the damping and friction work of each node so far [J] to
       * sum @p i of @p sum. */
      void
      add_dissipated(ReproducibleSum &sum, const unsigned int i) const;

    private:
      const ContactParameters parameters;
      /** Local indices of the x, y, z dofs of each node. */
      std::vector<std::array<unsigned int, 3>> nodes;
      /** Surface area of each node [m^2]. */
      std::vector<double> area;
      /** Lumped mass of each node [kg]. */
      std::vector<double> mass;
      /** Force of each node on the projectile along y [N], penalty energy
       * [J] (both at the last add_forces()) and damping and friction work
       * so far [J]. */
      std::vector<double> reaction, penalty_energy, dissipated;
    };
  } // namespace FE
} // namespace YarnImpact

#endif
