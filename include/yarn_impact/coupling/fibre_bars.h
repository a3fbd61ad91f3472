#ifndef yarn_impact_coupling_fibre_bars_h
#define yarn_impact_coupling_fibre_bars_h

#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/coupling/hybrid_model.h>

#include <deal.II/grid/tria.h>

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace YarnImpact
{
  namespace Coupling
  {
    /**
     * The far field of the hybrid yarn as fibres (`Hybrid/Far field =
     * fibre bars`, doc/hybrid.md section 3.4): every fibre of the DEM part
     * goes on, from the overlap's first node layer to the clamp, as a chain
     * of m bars per FE cell (`Hybrid/Fibre bars per FE cell`; by default
     * one per DEM truss, so that the overlap ties each sphere to one bar
     * node). Each bar node j carries one axial unknown u_{f,j}; its
     * transverse position is the continuum's at the fibre's place in the
     * section, linear in x between the FE node layers, so the fibres move
     * together across the section (the continuum's compaction and
     * distortion) but slide along each other, each with its own bar waves.
     *
     * A bar of fibre f between nodes j and j + 1 joins
     * p_j = (x_j + u_{f,j}, y_f + v(x_j, y_f, z_f), z_f + w(x_j, y_f, z_f)),
     * (v, w) the FE part's transverse displacement, and pulls with
     * T = alpha E_f A_f (l / h_b - 1) along its chord (geometrically exact,
     * as a DEM truss), h_b = h / m, alpha the continuum weight of its cell
     * layer: the axial part acts on u, the transverse part on the FE nodes
     * through the shape values. The FE part then has no fibre term
     * (k_e = 0), and its axial displacement is not its own: at every node
     * layer it is the least-squares fit of the fibres' axial displacements
     * over the section, U_x = P u (P = (Psi^T Psi)^-1 Psi^T, Psi the
     * section's shape values at the fibres), so that its transverse terms
     * see the section the fibres make (a deflected yarn's section turns
     * with it instead of being compacted by the slope), and its axial
     * forces go back to the fibres through P^T. The bars carry the axial
     * stiffness and the axial mass (each node the fibre's mass
     * alpha rho_f A_f h_b / 2 per adjacent bar), the FE nodes the
     * transverse mass. A bar breaks, for good, when its strain passes
     * Yarn/Failure strain, as a DEM truss does.
     *
     * Every rank holds and steps all bars (no contact, no search) in the
     * same order, so the bars are the same on any number of ranks; the FE
     * nodes' transverse displacements they need are summed from their
     * owners each step, exactly (one owner, zeros elsewhere).
     */
    class FibreBars
    {
    public:
      /**
       * Lay the bars along the FE part @p fe_model (extruded from
       * @p section, node layers as in @p layout from the overlap's first),
       * layout.bars_per_cell per cell, for the fibres at (@p fibre_y,
       * @p fibre_z) [m] of the section (collective). @p failure: whether
       * bars break at @p yarn.failure_strain.
       */
      void
      set_up(ImpactModel &fe_model,
             const dealii::Triangulation<2> &section,
             const HybridLayout &layout,
             const YarnImpact::Parameters::Yarn &yarn,
             const std::vector<double> &fibre_y,
             const std::vector<double> &fibre_z,
             const bool failure,
             const MPI_Comm communicator);

      /** v += dt f / m on every bar node but the clamped one (the last)
       * [s]. */
      void
      kick(const double dt);

      /** u += dt v [s]. */
      void
      drift(const double dt);

      /** Set the owned FE nodes' axial displacements of @p fe_model to
       * the fibres' fit, P u, and their axial velocities to zero (the bars
       * carry the axial motion); before the FE part's forces. */
      void
      set_continuum_axial(ImpactModel &fe_model) const;

      /**
       * The bars' forces at the present displacements: the axial ones on
       * the bar nodes (replacing the last), the transverse ones added to
       * the owned FE nodes' forces of @p fe_model, the FE nodes' axial
       * forces moved to the bars through P^T (and zeroed there); breaks
       * bars past the failure strain (collective: sums the FE
       * displacements and axial forces of the node layers). After the FE
       * part's forces.
       */
      void
      compute_forces(ImpactModel &fe_model, const MPI_Comm communicator);

      /** Stable step of the bar chains alone, 2 / omega_max with the
       * Gershgorin bound on the weighted stiffness over the nodes'
       * masses [s]. */
      double
      stable_time_step() const;

      /** Kinetic energy of the axial motion, 1/2 sum m v^2 [J] (modelled
       * part). */
      double
      kinetic_energy() const;

      /** Strain energy of the intact bars at the last compute_forces(),
       * 1/2 sum alpha E_f A_f h eps^2 [J]. */
      double
      elastic_energy() const
      {
        return elastic;
      }

      /** Strain energy released by the bars broken so far [J]. */
      double
      dissipated_energy() const
      {
        return dissipated;
      }

      /** Largest strain of an intact bar at the last compute_forces()
       * [-]. */
      double
      largest_strain() const
      {
        return largest;
      }

      /** Broken bars [-]. */
      unsigned long
      n_broken() const;

      /** Broken bars per 1 mm of reference x of their middle, from x = 0
       * [-]. */
      std::vector<unsigned long>
      broken_per_millimetre() const;

      /** Whether fibre @p f has a broken bar. */
      bool
      fibre_broken(const unsigned int f) const;

      /** Mean strain over the fibres at FE node layer @p k (of the
       * intact bars next to its bar node), for the station profile [-]. */
      double
      mean_strain(const unsigned int k) const;

      /** Fibres, bar nodes per fibre, bars per FE cell and FE node layers
       * [-]. */
      unsigned int n_fibres = 0, n_nodes = 0, bars_per_cell = 1, n_layers = 0;

      /** Node j of fibre f: its index in the arrays below. */
      std::size_t
      index(const unsigned int f, const unsigned int j) const
      {
        return std::size_t(f) * n_nodes + j;
      }

      /** Reference x of bar node @p j [m]. */
      double
      node_x(const unsigned int j) const
      {
        return x_begin + j * h;
      }

      /** Axial displacement [m], velocity [m/s], force [N] and weighted
       * lumped mass [kg] of each bar node. */
      std::vector<double> displacement, velocity, force, mass;

      /** Write and read the bars' state (every rank the same). */
      void
      save_state(Checkpoint::Writer &out) const;
      void
      load_state(Checkpoint::Reader &in);

      /** Memory of the bars on one rank [bytes]. */
      std::size_t
      memory_consumption() const;

    private:
      /** Reference x of the first bar node [m]; reference y and z of each
       * fibre [m]. */
      double x_begin = 0.;
      std::vector<double> fibre_y, fibre_z;
      /** Continuum weight alpha of the bars of each FE cell layer [-]. */
      std::vector<double> cell_weight;
      /** The section vertices around each fibre and their bilinear values
       * there [-]. */
      std::vector<std::array<unsigned int, 4>> fibre_vertices;
      std::vector<std::array<double, 4>> fibre_values;
      /** Section vertices [-]. */
      unsigned int n_vertices = 0;
      /** Owned FE nodes of the layers: (layer n_vertices + vertex, local
       * x, y and z dofs). */
      std::vector<std::pair<unsigned int, std::array<unsigned int, 3>>>
        owned_nodes;
      /** The section's projection P, n_vertices x n_fibres, row-major
       * [-]. */
      std::vector<double> projection;
      /** The layers' FE axial forces (per node) [N]. */
      std::vector<double> node_axial_force;
      /** The layers' transverse displacements (y, z per node) and the
       * bars' transverse forces on them [m], [N]. */
      std::vector<double> node_displacement, node_force;
      /** Broken bars, by index(f, k) of their first node. */
      std::vector<std::uint8_t> broken;
      /** Bar length h_b [m], stiffness E_f A_f / h_b [N/m], failure strain
       * [-] and whether bars break. */
      double h = 0., stiffness = 0., failure_strain = 0.;
      bool failure = false;
      /** Bar strains at the last compute_forces() [-]. */
      std::vector<double> strain;
      /** One fibre's transverse displacement at the layers and the bars'
       * transverse forces on them (y, z per layer) [m], [N]. */
      std::vector<double> layer_displacement, layer_force;

      /** Build the projection P from the fibres' places in the section. */
      void
      set_up_projection();

      /** Cell of bar node @p j (the last node: the last cell) and its
       * fraction xi in it [-]. */
      unsigned int
      cell_of(const unsigned int j, double &xi) const
      {
        const unsigned int c = std::min(j / bars_per_cell, n_layers - 2);
        xi                   = double(j - c * bars_per_cell) / bars_per_cell;
        return c;
      }
      double elastic = 0., dissipated = 0., largest = 0.;
    };
  } // namespace Coupling
} // namespace YarnImpact

#endif
