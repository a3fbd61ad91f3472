#ifndef yarn_impact_coupling_bridging_domain_h
#define yarn_impact_coupling_bridging_domain_h

#include <cstddef>
#include <cstdint>
#include <vector>

namespace YarnImpact
{
  /**
   * The coupling of a particle model (the DEM fibres) and a continuum (the
   * FE yarn) in an overlap where both exist: the bridging domain method
   * (doc/hybrid.md). This layer sits above the models and is the only one
   * allowed to know both; what is here is model-neutral (arrays of masses,
   * forces and shape values), so that it can be checked on its own
   * (tests/coupling).
   */
  namespace Coupling
  {
    /**
     * The constraints of the overlap: every particle i in it moves with the
     * continuum, v_i = sum_J N_J(X_i) v_J, with N_J the continuum's shape
     * functions at the particle's reference position X_i. The constraint is
     * strong (one per particle) and holds exactly at every step, in
     * velocities, hence in displacements.
     *
     * The explicit step with Lagrange multipliers lambda (the force the
     * continuum exerts on particle i): with the scaled lumped masses M_J of
     * the continuum's nodes and m_i of the particles, and the scaled forces
     * f_J and f_i of each model,
     *
     *   M_J a_J = f_J - sum_i N_J(X_i) lambda_i,
     *   m_i a_i = f_i + lambda_i,
     *   a_i     = sum_J N_J(X_i) a_J.
     *
     * Eliminating lambda and the particles' accelerations leaves
     *
     *   K a = f + N^T f_p,  with K = diag(M) + N^T diag(m) N,
     *
     * a small symmetric positive definite system over the nodes that carry
     * constrained particles (hundreds of nodes against tens of thousands of
     * particles). K is constant (reference positions and masses), so it is
     * factorised once (Cholesky) and every step costs two triangular
     * solves. This is the multiplier system A lambda = g of the method,
     * A = diag(m)^-1 + N diag(M)^-1 N^T, solved exactly (Woodbury's
     * identity) instead of with A lumped: the constraints hold to round-off
     * and the coupled system is a Lagrangian system with the mass matrix
     * K, so velocity Verlet keeps its energy behaviour.
     *
     * Linear momentum is exact when the shape values at every particle sum
     * to one (checked): the multipliers' sum on the particles equals their
     * sum on the nodes. The multipliers do no work on velocities that
     * satisfy the constraints; the work they do on each model separately
     * (what crosses the interface) is lambda . v_i summed over the
     * particles.
     *
     * Vectors of three components per node or particle are stored
     * interleaved: [x0, y0, z0, x1, ...].
     */
    class BridgingConstraint
    {
    public:
      /** @p n_nodes coupled nodes (indices 0 .. n_nodes - 1), no particles,
       * every nodal mass zero. */
      explicit BridgingConstraint(const unsigned int n_nodes = 0);

      /** Set the scaled lumped mass of coupled node @p node: the
       * continuum's mass there, multiplied by its weight [kg]. */
      void
      set_node_mass(const unsigned int node, const double mass);

      /**
       * Add a constrained particle.
       * @param mass its scaled mass (mass times its weight) [kg]
       * @param nodes the coupled nodes whose shape functions do not vanish
       * at its reference position
       * @param shape_values N_J(X_i) for those nodes; they must sum to one
       * [-]
       * @return the particle's index in this constraint
       */
      unsigned int
      add_particle(const double mass,
                   const std::vector<unsigned int> &nodes,
                   const std::vector<double> &shape_values);

      /**
       * Hold component @p d (0: x, 1: y, 2: z) of coupled node @p node at
       * zero acceleration, as the continuum holds a node on a symmetry
       * plane (z on z = 0 with quarter symmetry): that component is solved
       * with the node's row and column of K replaced by the identity, so
       * that the other nodes and the particles move as the held node
       * lets them.
       */
      void
      fix_component(const unsigned int node, const unsigned int d);

      /**
       * Assemble K and factorise it. Throws std::runtime_error naming the
       * cause if a particle's shape values do not sum to one within 1e-12,
       * a mass is negative, or K is not positive definite (a coupled node
       * with neither mass nor a particle in its support).
       */
      void
      factorize();

      /** Number of coupled nodes. */
      unsigned int
      n_nodes() const
      {
        return node_mass.size();
      }

      /** Number of constrained particles. */
      unsigned int
      n_particles() const
      {
        return particle_mass.size();
      }

      /**
       * The accelerations of the coupled system (after factorize()).
       * @param node_force the continuum's scaled forces at the coupled
       * nodes, 3 per node [N]
       * @param particle_force the particle model's scaled forces on the
       * constrained particles, 3 per particle [N]
       * @param[out] node_acceleration 3 per node [m/s^2]
       * @param[out] particle_acceleration 3 per particle, the interpolated
       * node accelerations [m/s^2]
       * @param[out] constraint_force if not null, lambda: the force of the
       * continuum on each particle, 3 per particle (its opposite acts on
       * the nodes through N^T) [N]
       */
      void
      accelerations(const double *node_force,
                    const double *particle_force,
                    double *node_acceleration,
                    double *particle_acceleration,
                    double *constraint_force = nullptr) const;

      /** The generalised force of the coupled system on the nodes,
       * @p node_force + N^T @p particle_force (3 per node, 3 per particle)
       * into @p out (3 per node) [N]: what moves the nodes; zero for a
       * state in equilibrium. */
      void
      generalised_force(const double *node_force,
                        const double *particle_force,
                        double *out) const;

      /** The nodal field @p node_values (3 per node) interpolated at the
       * particles: @p particle_values = N node_values (3 per particle). */
      void
      interpolate(const double *node_values, double *particle_values) const;

      /** Largest |v_i - sum_J N_J(X_i) v_J| over the particles and
       * components: how far the velocities are from the constraints
       * [m/s]. */
      double
      largest_violation(const double *node_velocity,
                        const double *particle_velocity) const;

      /** Memory of the constraint: the factor of K and the shape values
       * [bytes]. */
      std::size_t
      memory_consumption() const;

    private:
      std::vector<double> node_mass;
      std::vector<double> particle_mass;
      /** Shape values of particle i: entries row_start[i] .. row_start[i+1]
       * of column and value. */
      std::vector<unsigned int> row_start;
      std::vector<unsigned int> column;
      std::vector<double> value;
      /** Whether component d of node J is held: entry 3 J + d. */
      std::vector<std::uint8_t> fixed;
      /** Lower Cholesky factors of K, dense, row-major n x n: one per
       * distinct set of held nodes among the components, and the factor
       * each component uses. */
      std::vector<std::vector<double>> factors;
      unsigned int component_factor[3] = {0, 0, 0};
      bool factorized                  = false;

      /** Cholesky factorisation of the n x n matrix @p factor in place;
       * throws naming the node if it is not positive definite. */
      static void
      cholesky(std::vector<double> &factor, const unsigned int n);

      /** Solve K x = b in place for one component (stride 3, offset d). */
      void
      solve(double *b, const unsigned int d) const;
    };

    /**
     * The same constraint for one component of particles on a chain of
     * nodes along a line, with linear shape functions: particle i lies
     * between nodes j_i and j_i + 1 at the fraction xi_i, and moves with
     * (1 - xi_i) v_j + xi_i v_{j+1}. K = diag(M) + N^T diag(m) N is then
     * tridiagonal: factorised once (L D L^T), two sweeps a step, so that a
     * chain of hundreds of nodes costs what its particles cost. It ties a
     * DEM fibre's axial motion to its own fibre bars (doc/hybrid.md
     * section 3.4). Vectors hold one value per node or particle.
     */
    class ChainConstraint
    {
    public:
      /** @p n_nodes nodes, no particles, every nodal mass zero. */
      explicit ChainConstraint(const unsigned int n_nodes = 0);

      /** Scaled lumped mass of node @p node [kg]. */
      void
      set_node_mass(const unsigned int node, const double mass);

      /**
       * Add a constrained particle of scaled mass @p mass [kg] at the
       * fraction @p xi in [0, 1] of the way from node @p node to the next
       * (xi = 0: on the node; the last node needs xi = 0) [-]. Returns its
       * index.
       */
      unsigned int
      add_particle(const double mass, const unsigned int node, const double xi);

      /** Assemble K and factorise it; throws std::runtime_error naming the
       * cause if a mass is negative or K is not positive definite. */
      void
      factorize();

      /** Number of nodes. */
      unsigned int
      n_nodes() const
      {
        return node_mass.size();
      }

      /** Number of constrained particles. */
      unsigned int
      n_particles() const
      {
        return particle_mass.size();
      }

      /**
       * The coupled accelerations [m/s^2] of the nodes and particles from
       * their scaled forces [N], and the multipliers (the force of the
       * chain on each particle) [N], as
       * BridgingConstraint::accelerations() for one component.
       */
      void
      accelerations(const double *node_force,
                    const double *particle_force,
                    double *node_acceleration,
                    double *particle_acceleration,
                    double *constraint_force) const;

      /** @p node_force + N^T @p particle_force into @p out [N]. */
      void
      generalised_force(const double *node_force,
                        const double *particle_force,
                        double *out) const;

    private:
      std::vector<double> node_mass, particle_mass;
      std::vector<unsigned int> particle_node;
      std::vector<double> particle_xi;
      /** L D L^T of K: the diagonal D and the sub-diagonal of L. */
      std::vector<double> d, l;
      bool factorized = false;
    };
  } // namespace Coupling
} // namespace YarnImpact

#endif
