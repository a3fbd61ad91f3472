#ifndef yarn_impact_coupling_section_tie_h
#define yarn_impact_coupling_section_tie_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace YarnImpact
{
  namespace Coupling
  {
    /**
     * The transverse tie of the overlap on the section's coarse modes only
     * (`Hybrid/Transverse tie = section mean | section affine`,
     * doc/hybrid.md section 2.5): for every node layer l of the overlap
     * (hat function phi_l(x) of the FE node layers along x) and every
     * section mode psi_k (1; with the affine modes also Y/s and Z/s, the
     * reference section coordinates over a length s), the y and z
     * velocities of the spheres and of the continuum at the spheres have
     * the same mass-weighted moment:
     *
     *   sum_i phi_l(x_i) psi_k(i) m_i (v_i - sum_J N_J(X_i) v_J) = 0.
     *
     * With G_d the spheres' rows c_ri = phi_l psi_k m_i and G_f = G_d N the
     * nodes', the multipliers mu solve the small constant system
     * A mu = -(G_d M_d^-1 f_d - G_f M_f^-1 f_f),
     * A = G_d M_d^-1 G_d^T + G_f M_f^-1 G_f^T (one row per layer and mode),
     * factorised once. The spheres get the force G_d^T mu, the nodes
     * -G_f^T mu: they sum to zero (the shape values at each sphere sum to
     * one), and do no work on velocities that meet the constraints.
     * Model-neutral: arrays of masses, forces and shape values with three
     * components per node and particle, of which y and z (d = 1, 2) are
     * tied here; x is left to the caller.
     */
    class SectionTie
    {
    public:
      /** A tie over @p n_nodes continuum nodes, @p n_layers node layers
       * along x and @p n_modes section modes per layer (1: the mean; 3:
       * affine in the section) [-]. */
      SectionTie(const unsigned int n_nodes  = 0,
                 const unsigned int n_layers = 0,
                 const unsigned int n_modes  = 1);

      /** The (weighted, lumped) mass of node @p node [kg]. */
      void
      set_node_mass(const unsigned int node, const double mass);

      /** Hold component @p d of node @p node (a symmetry plane): its
       * acceleration is zero, it takes the multipliers' force as a
       * support. */
      void
      fix_component(const unsigned int node, const unsigned int d);

      /**
       * A particle of (weighted) mass @p mass [kg] between node layers
       * @p layer and @p layer + 1 at the fraction @p xi in [0, 1] of the
       * way, with section modes @p modes (the first must be 1; [-]), and
       * the continuum's shape values @p shape_values at its reference
       * position for the nodes @p nodes. Returns its index.
       */
      unsigned int
      add_particle(const double mass,
                   const unsigned int layer,
                   const double xi,
                   const std::array<double, 3> &modes,
                   const std::vector<unsigned int> &nodes,
                   const std::vector<double> &shape_values);

      /** Build and factorise A for y and z (after every node and
       * particle). */
      void
      factorize();

      /**
       * The coupled accelerations [m/s^2] from the forces [N] (three
       * components per node and per particle): y and z tied, x free
       * (force over mass). @p constraint_force receives each particle's
       * multiplier force G_d^T mu [N] and @p node_reaction each node's
       * G_f^T mu [N] (the nodes receive its opposite), x components zero.
       */
      void
      accelerations(const double *node_force,
                    const double *particle_force,
                    double *node_acceleration,
                    double *particle_acceleration,
                    double *constraint_force,
                    double *node_reaction) const;

      /** The largest violation of the constraints by these velocities
       * [m/s]: max over rows of |G_d v_d - G_f v_f| over the row's
       * particle mass sum_i phi_l(x_i) m_i. */
      double
      largest_violation(const double *node_velocity,
                        const double *particle_velocity) const;

      /** Constraint rows per component (layers times modes) [-]. */
      unsigned int
      n_rows() const
      {
        return n_layers * n_modes;
      }
      unsigned int
      n_particles() const
      {
        return particle_mass.size();
      }

    private:
      unsigned int n_layers = 0, n_modes = 1;
      std::vector<double> node_mass;
      std::vector<std::uint8_t> fixed;
      std::vector<double> particle_mass;
      /** Per particle: its first layer, xi and modes. */
      std::vector<unsigned int> particle_layer;
      std::vector<double> particle_xi;
      std::vector<std::array<double, 3>> particle_modes;
      /** G_f, dense: rows by nodes [kg]. */
      std::vector<double> node_rows;
      /** Per particle's rows: r and the row value over the mass,
       * phi_l psi_k [-]. */
      void
      particle_rows(const unsigned int i,
                    unsigned int *rows,
                    double *values) const;
      /** Cholesky factors of A for y and z (lower triangle). */
      std::array<std::vector<double>, 2> factors;
      bool factorized = false;
    };
  } // namespace Coupling
} // namespace YarnImpact

#endif
