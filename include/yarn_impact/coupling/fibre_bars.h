#ifndef yarn_impact_coupling_fibre_bars_h
#define yarn_impact_coupling_fibre_bars_h

#include <yarn_impact/contact/contact_constants.h>
#include <yarn_impact/contact/contact_law.h>
#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/coupling/hybrid_model.h>

#include <deal.II/grid/tria.h>

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace YarnImpact
{
  namespace Coupling
  {
    /**
     * The far field of the hybrid yarn as fibres (`Hybrid/Far field =
     * fibre bars`, doc/hybrid.md section 3.4): every fibre of the DEM part
     * goes on, from the overlap's first node layer to the clamp (or, with
     * a DEM part at the clamp, to the end of its overlap), as a chain
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
     * Each rank steps the bars of its own fibres, a fixed contiguous
     * range (fibre_begin, fibre_end): every bar's arithmetic is the same on
     * any number of ranks, and what is summed over fibres (the FE nodes'
     * forces, the fit P u, the energies) is summed in fibre order from
     * per-fibre values gathered to every rank, so the run is the same bit
     * for bit on any number of ranks. Every rank holds all fibres' arrays
     * (a restart may use another number of ranks); only the own fibres' are
     * current, but for the overlap's nodes (the overlap's ties, solved on
     * every rank, need all fibres'), which are gathered each step, and the
     * broken bars, gathered on the steps that break one. The FE nodes'
     * transverse displacements are summed from their owners each step,
     * exactly (one owner, zeros elsewhere).
     */
    class FibreBars
    {
    public:
      /**
       * Lay the bars along the FE part @p fe_model (extruded from
       * @p section, node layers as in @p layout from the overlap's first),
       * layout.bars_per_cell per cell, for the fibres at (@p fibre_y,
       * @p fibre_z) [m] of the section (collective). @p failure: whether
       * bars break at @p yarn.failure_strain. @p z_symmetry: the section
       * is the half z >= 0 of a quarter model, whose fibres on z = 0 are
       * half fibres (half the mass and stiffness, as in the DEM).
       */
      void
      set_up(ImpactModel &fe_model,
             const dealii::Triangulation<2> &section,
             const HybridLayout &layout,
             const YarnImpact::Parameters::Yarn &yarn,
             const std::vector<double> &fibre_y,
             const std::vector<double> &fibre_z,
             const bool failure,
             const bool z_symmetry,
             const MPI_Comm communicator);

      /** v += dt f / m on the own fibres' bar nodes but the clamped one
       * (the last, unless a DEM part at the clamp holds the fibres) [s]. */
      void
      kick(const double dt);

      /** u += dt v on the own fibres' bar nodes [s]. */
      void
      drift(const double dt);

      /** Set the owned FE nodes' axial displacements of @p fe_model to
       * the fibres' fit, P u, and their axial velocities to zero (the bars
       * carry the axial motion); before the FE part's forces (collective:
       * gathers the fibres' displacements at the node layers). */
      void
      set_continuum_axial(ImpactModel &fe_model);

      /**
       * The bars' forces at the present displacements: the axial ones on
       * the bar nodes (replacing the last), the transverse ones added to
       * the owned FE nodes' forces of @p fe_model, the FE nodes' axial
       * forces moved to the bars through P^T (and zeroed there), and the
       * contact of @p projectile with the bar nodes over the step @p dt [s]
       * (set_projectile_contact()); breaks bars past the failure strain
       * (collective: sums the FE displacements, velocities and axial
       * forces of the node layers, gathers the fibres' forces on the
       * layers and at the overlap's nodes). After the FE part's forces.
       * @return the contact's force on the projectile along y, of the
       * modelled bars, the same on every rank [N]
       */
      double
      compute_forces(ImpactModel &fe_model,
                     const Projectile &projectile,
                     const double dt,
                     const MPI_Comm communicator);

      /**
       * The projectile touches the bar nodes (doc/hybrid.md section 3.4):
       * each node, a point of its fibre (its own axial position, the
       * continuum's transverse one), touches it as a DEM sphere of radius
       * @p radius [m] does, by the DEM's projectile law @p law with
       * @p constants (those of a sphere), its force weighted as the node's
       * mass, the axial part on the node, the transverse part on the
       * continuum through the node's layers. Radius 0 (the default): no
       * contact.
       */
      void
      set_projectile_contact(const Contact::LawType law,
                             const Contact::ContactConstants &constants,
                             const double radius);

      /** Energy stored in the projectile's contacts with the bar nodes at
       * the last compute_forces(), the same on every rank [J]. */
      double
      contact_energy() const
      {
        return contact_stored;
      }

      /** Stable step of the bar chains alone, 2 / omega_max with the
       * Gershgorin bound on the weighted stiffness over the nodes'
       * masses [s]. */
      double
      stable_time_step() const;

      /** Kinetic energy of the axial motion, 1/2 sum m v^2 [J] (modelled
       * part; collective). */
      double
      kinetic_energy() const;

      /** Strain energy of the intact bars at the last compute_forces(),
       * 1/2 sum alpha (E_f A_f / h) (eps h)^2 [J] (collective). */
      double
      elastic_energy() const;

      /** Strain energy released by the bars broken so far and energy
       * dissipated by the projectile's contacts with the bar nodes [J]
       * (collective). */
      double
      dissipated_energy() const;

      /** Largest strain of an intact bar at the last compute_forces() [-]
       * (collective). */
      double
      largest_strain() const;

      /** Broken bars [-]. */
      unsigned long
      n_broken() const;

      /** Broken bars per 1 mm of reference x of their middle, from x = 0
       * [-]. */
      std::vector<unsigned long>
      broken_per_millimetre() const;

      /** Every broken bar: its break time, fibre and the reference x of
       * its middle, in the order of break_less() (part "bars"; the same on
       * every rank; collective). */
      std::vector<FibreBreak>
      fibre_breaks(const MPI_Comm communicator) const;

      /** Whether fibre @p f has a broken bar. */
      bool
      fibre_broken(const unsigned int f) const;

      /** Largest strain over the fibres at each FE node layer (of the
       * intact bars next to its bar node), for the station profile, as the
       * DEM's profile takes the largest over its fibres [-]
       * (collective). */
      std::vector<double>
      largest_strains() const;

      /** Whether the bars stand for the mirror image x -> -x of
       * themselves (those of the FE part on x < 0 of a whole yarn,
       * FE::Parameters::mirrored): their snapshots (`bars_left_NNNN`) and
       * breaks are given at -x. */
      bool mirrored = false;

      /** Fibres, bar nodes per fibre, bars per FE cell and FE node layers
       * [-]. */
      unsigned int n_fibres = 0, n_nodes = 0, bars_per_cell = 1, n_layers = 0;

      /** The fibres this rank steps: fibre_begin <= f < fibre_end. */
      unsigned int fibre_begin = 0, fibre_end = 0;

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

      /** Axial displacement [m], velocity [m/s], force [N], weighted
       * lumped mass [kg] and its inverse [1/kg] of each bar node. */
      std::vector<double> displacement, velocity, force, mass, inverse_mass;

      /** Write (collective: gathers every fibre's state first) and read
       * the bars' state (every rank the same). */
      void
      save_state(Checkpoint::Writer &out) const;
      void
      load_state(Checkpoint::Reader &in);

      /** Memory of the bars on one rank [bytes]. */
      std::size_t
      memory_consumption() const;

      /**
       * Write a snapshot of the bars: `<directory>/bars_NNNN.pvtu` (NNNN =
       * @p snapshot; `bars_left_NNNN.pvtu` when mirrored) with one `.vtu` piece
       * per rank, its own fibres as polylines of bar nodes at their positions
       * (the axial displacement their own, the transverse the continuum's at
       * the last compute_forces()). Point data: fibre_id, displacement [m],
       * axial_velocity [m/s]; cell data per bar: strain [-], force (its
       * tension) [N], broken. Collective.
       * @return the file name of the record, relative to @p directory
       */
      std::string
      write_snapshot(const std::string &directory,
                     const unsigned int snapshot) const;

    private:
      MPI_Comm communicator = MPI_COMM_SELF;
      /** Each rank's first fibre (and n_fibres last). */
      std::vector<unsigned int> rank_fibres;
      /** Bar nodes tied in the overlap (its cells' nodes), and in the
       * overlap of the DEM part at the clamp (the last ones; 0 without such
       * a part, the last node then held at the clamp) [-]. */
      unsigned int n_overlap_nodes = 0, n_clamp_nodes = 0;

      /** Bar node of the @p t th tied node: the overlap's first, then
       * the clamp overlap's. */
      unsigned int
      tied_node(const unsigned int t) const
      {
        return t < n_overlap_nodes
                 ? t
                 : n_nodes - n_clamp_nodes + (t - n_overlap_nodes);
      }

      /** Bar nodes kicked: all, or all but the clamped last one [-]. */
      unsigned int
      n_free_nodes() const
      {
        return n_clamp_nodes > 0 ? n_nodes : n_nodes - 1;
      }
      /** Stable step of the bars alone, fixed at set-up [s]. */
      double stable_step = 0.;
      /** Per fibre, each step: its forces on the node layers (y, z per
       * layer), its overlap nodes' forces and velocities, and its bars
       * broken in this step [N], [m/s], [-]. */
      std::vector<double> fibre_record;
      /** Per fibre: its bars' displacements at the node layers [m]. */
      std::vector<double> layer_axial;
      /** Per fibre: energy released by its broken bars, and dissipated by
       * the projectile's contacts with its bar nodes [J]. */
      std::vector<double> fibre_dissipated, fibre_contact_dissipated;
      /** The projectile's contact with the bar nodes: law, constants, the
       * nodes' radius (0: none) [m], each node's law history and whether
       * it touched at the last step; the stored energy at the last
       * compute_forces() [J]. */
      Contact::LawType contact_law = Contact::LawType::cundall_strack;
      Contact::ContactConstants contact_constants;
      double contact_radius = 0.;
      std::vector<double> contact_history;
      std::vector<std::uint8_t> touching;
      double contact_stored = 0.;
      /** Doubles per FE node in node_state: transverse displacement (y,
       * z), axial force, transverse velocity (y, z). */
      static constexpr unsigned int node_stride = 5;

      /** Entry @p e of node_state (0, 1: the transverse displacement; 3,
       * 4: the transverse velocity) interpolated at fibre @p f on node
       * layer @p k, by the section's bilinear values there [m], [m/s]. */
      double
      at_fibre(const unsigned int f,
               const unsigned int k,
               const unsigned int e) const
      {
        const auto &vertex = fibre_vertices[f];
        const auto &value  = fibre_values[f];
        double s           = 0.;
        for (unsigned int v = 0; v < 4; ++v)
          s += value[v] *
               node_state[node_stride * (k * n_vertices + vertex[v]) + e];
        return s;
      }

      /** The projectile's contacts with the bar nodes of own fibre @p f
       * over the step @p dt [s]: forces added (axial to the nodes,
       * transverse to the fibre's layer forces in fibre_record), the
       * force on the projectile along y and the stored energy added to
       * @p out [N], [J]. */
      void
      projectile_contact(const unsigned int f,
                         const Projectile &projectile,
                         const double dt,
                         double *out);
      /** One fibre's bars' lengths, then their axial tensions s e_x, per
       * bar [m], [N]. */
      std::vector<double> axial_tension;

      /** Size of one fibre's record in fibre_record: its layer forces, its
       * overlap nodes' forces and velocities, then its contact force on the
       * projectile, its contact energy and its bars broken in the step. */
      unsigned int
      record_size() const
      {
        return 2 * n_layers + 2 * (n_overlap_nodes + n_clamp_nodes) + 3;
      }

      /** Sum of one value per fibre (the own fibres' set, the others'
       * gathered) in fibre order: the same on any number of ranks
       * (collective). */
      double
      sum_over_fibres(std::vector<double> per_fibre) const;

      /** Gather @p values, @p per_fibre entries per fibre, from each
       * fibre's rank to every rank (collective). */
      template <typename T>
      void
      gather_fibres(std::vector<T> &values, const unsigned int per_fibre) const;

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
      /** The layers' transverse displacements and FE axial forces (y, z,
       * f_x per node), and the bars' transverse forces on them (y, z per
       * node) [m], [N]. */
      std::vector<double> node_state, node_force;
      /** Broken bars, by index(f, k) of their first node. */
      std::vector<std::uint8_t> broken;
      /** When each broken bar of the own fibres broke [s]. */
      std::vector<double> break_time;
      /** Time of the displacements: the sum of the drifts' steps [s]. */
      double time = 0.;
      /** Each fibre's share of a whole fibre: 1/2 on the plane z = 0 of a
       * quarter model, 1 elsewhere [-]. */
      std::vector<double> fibre_weight;
      /** Bar length h_b [m], stiffness E_f A_f / h_b [N/m], failure strain
       * [-] and whether bars break. */
      double h = 0., stiffness = 0., failure_strain = 0.;
      bool failure = false;
      /** Bar strains at the last compute_forces() (the own fibres') [-]. */
      std::vector<double> strain;
      /** One fibre's transverse displacement at the layers (y, z per
       * layer) [m]. */
      std::vector<double> layer_displacement;

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
    };
  } // namespace Coupling
} // namespace YarnImpact

#endif
