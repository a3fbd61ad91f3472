#ifndef yarn_impact_source_fe_yarn_model_h
#define yarn_impact_source_fe_yarn_model_h

// The FE model's class, shared by the source files that define its
// members (fe_model.cc, fe_observables.cc); not part of the public
// interface, which is fe/fe_model.h.

#include <yarn_impact/core/crimped_yarn.h>
#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/fe/cell_kernel.h>
#include <yarn_impact/fe/contact.h>
#include <yarn_impact/fe/extra_forces.h>
#include <yarn_impact/fe/fe_model.h>
#include <yarn_impact/fe/parameters.h>

#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace YarnImpact
{
  namespace FE
  {
    /**
     * The FE yarn: Q1 hexahedra, 2x2x2 Gauss points, row-sum lumped mass,
     * explicit central difference driven by ImpactSimulation, penalty
     * contact with the rigid cylinder (ProjectileContact), cell failure at
     * a longitudinal strain, sudden or progressive (FailureLaw). The force loop
     * (internal_forces()) works on pre-computed shape gradients and local
     * indices into deal.II's distributed vectors. A template on the
     * constitutive law, so that the law inlines into that loop
     * (constitutive_law.h).
     *
     * The set-up is in fe_setup.cc; the stable step, the step phases and
     * create_model() in fe_model.cc; observables and output in
     * fe_observables.cc.
     */
    template <class Law>
    class YarnModel : public ImpactModel
    {
    public:
      /** deal.II's distributed vector, with ghosts. */
      using VectorType = dealii::LinearAlgebra::distributed::Vector<double>;

      /** @param law the constitutive law, density included */
      YarnModel(const YarnImpact::Parameters::Shared &shared,
                const Parameters &parameters,
                const Law &law,
                const MPI_Comm communicator);

      /** "fe". */
      std::string
      name() const override
      {
        return "fe";
      }

      /** Mesh, dofs, lumped mass, constraints, contact nodes, in the steps
       * make_grid(), setup_system(), setup_cells(), setup_nodes() and
       * setup_initial_state(); reports the mesh and the contact step to
       * @p out. */
      void
      setup(const Projectile &projectile, std::ostream &out) override;

      /** Highest reference y of the yarn [m]. */
      double
      yarn_top() const override
      {
        return top;
      }

      /** Stable explicit step [s] of the current (deformed) mesh and of
       * the contact springs. */
      double
      stable_time_step() const override;

      /** Internal and contact forces at the current state; returns the
       * yarn's force on the projectile along y [N], whole yarn. */
      double
      compute_forces(const Projectile &projectile, const double dt) override;

      /** v += dt M^-1 f over the step @p dt [s]. */
      void
      kick(const double dt) override;

      /** u += dt v over the step @p dt [s]. */
      void
      drift(const double dt) override;

      /** Energies [J], strains, failed cells, cut-through and the station
       * profile of the whole yarn; on a given mesh with sections
       * (GivenMesh::section), the broken yarns as its one extra column.
       * Collective. */
      Observables
      observables() const override;

      /** `broken yarns` on a given mesh with sections
       * (GivenMesh::section), none otherwise. */
      std::vector<std::string>
      extra_column_names() const override
      {
        if (parameters.mesh.section)
          return {"broken yarns"};
        return {};
      }

      /** Density, area and axial law of the discretised yarn (Smith). */
      AxialProperties
      axial_properties() const override;

      /** Mass of the whole yarn [kg]. */
      double
      mass() const override
      {
        return total_mass;
      }

      /** Write the deformed mesh with cell fields as VTU in
       * @p directory; returns the record's file name. */
      std::string
      write_snapshot(const std::string &directory,
                     const unsigned int index,
                     const double time) const override;

      /** Displacements, velocities and forces of the owned dofs, the cells'
       * failure state and strains, the energies and the contact's state. */
      void
      save_state(Checkpoint::Writer &out) const override;

      /** Read what save_state() wrote (collective: refreshes the ghost
       * values). */
      void
      load_state(Checkpoint::Reader &in) override;

      /** Crushed, inverted or non-finite cells are eroded. */
      bool
      erodes_cells() const override
      {
        return true;
      }

      /** Number of cells of the modelled part. */
      unsigned long
      n_elements() const override
      {
        return tria.n_global_active_cells();
      }

      /** See FE::coupling_view(). */
      CouplingView
      coupling_view()
      {
        CouplingView v;
        v.nodes                = &nodes;
        v.reference_coordinate = &reference_coordinate;
        v.displacement         = displacement.begin();
        v.velocity             = velocity.begin();
        v.force                = force.begin();
        v.mass                 = lumped_mass.begin();
        v.inverse_mass         = inverse_mass.begin();
        return v;
      }

    private:
      /** Whether this is a part of a hybrid yarn (FE::Parameters::
       * layer_weight), not the whole yarn. */
      bool
      is_part() const
      {
        return !parameters.layer_weight.empty();
      }

      /** Whether a symmetry plane x = 0 bounds the whole yarn's model. */
      bool
      reduced() const
      {
        return shared.general.symmetry !=
               YarnImpact::Parameters::Symmetry::none;
      }

      /** Reference x where a hybrid's part ends [m]. */
      double
      part_end() const
      {
        return parameters.part_end < 0. ? 0.5 * shared.yarn.length
                                        : parameters.part_end;
      }

      /** Reference x where the modelled length begins [m]: the start of a
       * hybrid's part, the symmetry plane, or the left clamp. */
      double
      x_begin() const
      {
        return is_part()   ? parameters.part_begin
               : reduced() ? 0.
                           : -0.5 * shared.yarn.length;
      }

      /** The abscissa [m] of the reference point @p X [m] along the yarn:
       * X_x on the straight yarn, the centreline abscissa of its section
       * on a crimped one (CrimpedYarn::abscissa_of). The stations, layers
       * and clamps are placed by it. */
      double
      abscissa(const dealii::Point<3> &X) const
      {
        return crimped ? crimped->abscissa_of(X) : X[0];
      }

      /** The station [-] of the profile nearest the abscissa @p x [m]
       * (by |x| from station_origin); the last one for a point beyond it
       * (a fabric's plies shifted along x reach past the span the
       * stations cover). */
      unsigned int
      station_of(const double x) const
      {
        return std::min(n_stations - 1,
                        static_cast<unsigned int>(std::round(
                          (std::abs(x) - station_origin) / station_spacing)));
      }

      /** The height [m] of the reference point @p X [m] across the yarn,
       * towards the projectile: X_y on the straight yarn, along the
       * centreline's normal at its section on a crimped one. */
      double
      section_height(const dealii::Point<3> &X) const
      {
        if (parameters.mesh.section_height)
          {
            const double xyz[3] = {X[0], X[1], X[2]};
            return parameters.mesh.section_height(xyz);
          }
        if (!crimped)
          return X[1];
        const double s = crimped->abscissa_of(X);
        return (X - crimped->centreline(s)) * crimped->normal(s);
      }

      /** Set-up step 1: the coarse mesh of the yarn (or of a hybrid's part),
       * refined globally. */
      void
      make_grid();

      /** Set-up step 2: the dofs, the distributed vectors with their
       * ghosts, and the layers and stations along the modelled length. */
      void
      setup_system();

      /**
       * Set-up step 3: the data of the owned and ghost cells in the force
       * loop's order (by CellId; the body says why): their dofs, shape
       * gradients and weights at the quadrature points (CellData), local
       * axis, layer and volume, and the lumped mass. Returns the lumped
       * area [m^2] of the lateral surface by node (on its x dof); throws
       * if an owned node lacks a cell.
       */
      VectorType
      setup_cells();

      /** For setup_cells(): the dofs of @p cell, its reference coordinates
       * and its nodes' lumped mass [kg], of the continuum weight @p weight
       * [-], also into @p mass_check if the cell is owned. */
      void
      add_cell_nodes(
        const typename dealii::DoFHandler<3>::active_cell_iterator &cell,
        const dealii::FEValues<3> &fe_values,
        const double weight,
        VectorType &mass_check);

      /** For setup_cells(): the shape gradients [1/m] and quadrature
       * weights JxW [m^3] of the cell of @p fe_values, of the continuum
       * weight @p weight [-] (and a hybrid's section quadrature). */
      void
      add_cell_quadrature(const dealii::FEValues<3> &fe_values,
                          const double weight);

      /** For setup_cells(): the local fibre axis, fibre length [m], depth
       * below the struck face [-], volume [m^3] and layer of @p cell. */
      void
      add_cell_geometry(
        const typename dealii::DoFHandler<3>::active_cell_iterator &cell,
        const dealii::FEValues<3> &fe_values);

      /** For setup_cells(): the lumped area [m^2] of the lateral faces of
       * @p cell, added to @p area on its nodes' x dofs. */
      void
      add_lateral_area(
        const typename dealii::DoFHandler<3>::active_cell_iterator &cell,
        dealii::FEFaceValues<3> &fe_face_values,
        VectorType &area) const;

      /** Set-up step 4: the owned nodes, their stations, their constraints
       * (clamps, symmetry planes: inverse mass 0) and the projectile
       * contact of the free lateral ones, of lumped area @p area [m^2]. */
      void
      setup_nodes(const VectorType &area);

      /** For setup_nodes() on a given mesh (GivenMesh): whether each local
       * dof lies on a boundary face of one of the boundary ids @p ids, on
       * its x dof. */
      std::vector<bool>
      dofs_on_faces(const std::set<unsigned int> &ids) const;

      /** For setup_initial_state(): the owned nodes that each set of extra
       * forces (FE::Parameters::extra_forces) acts on, from their
       * reference positions. */
      void
      setup_extra_forces();

      /** For compute_forces(): the extra forces at the current state,
       * over the step @p dt [s], added to the owned dofs, after they have
       * been told the owned cells that failed since the last call
       * (ExtraForces::remove_cells). */
      void
      add_extra_forces(const double dt);

      /** Tell the extra forces the owned cells that have failed and are
       * not yet reported (all of them with @p restored, after a restart),
       * and mark them reported. Collective. */
      void
      report_failed_cells(const bool restored);

      /** Set-up step 5: the mass [kg] and top [m] of the yarn, the contact's
       * stable step [s], the state at rest and its section widths. */
      void
      setup_initial_state();

      /** Whether some cell layer has broken through, leaving no load path
       * between the clamps. Collective. */
      bool
      yarn_cut_through() const;

      /** On a given mesh with sections (GivenMesh::section): the yarns
       * [-] with a section whose every cell has failed (broken or fully
       * damaged) or been eroded, the same on every rank. Collective. */
      unsigned int
      broken_yarns() const;

      /** Current positions [m] of the 8 vertices of cell c. */
      void
      vertex_positions(const unsigned int c, double (&p)[n_nodes][3]) const;

      const YarnImpact::Parameters::Shared &shared;
      const Parameters parameters;
      const Law law;
      const MPI_Comm communicator;
      const double symmetry;

      dealii::parallel::distributed::Triangulation<3> tria;
      dealii::FESystem<3> fe;
      dealii::DoFHandler<3> dof_handler;

      mutable VectorType displacement;
      mutable VectorType velocity;
      VectorType force;
      VectorType lumped_mass;
      VectorType inverse_mass;
      /** Reference coordinate of each local dof (its own component). */
      std::vector<double> reference_coordinate;
      /** The crimped yarn of FE/Crimp; none: the straight yarn. */
      std::optional<Fabric::CrimpedYarn> crimped;
      /** Abscissa (abscissa()) [m] of each local dof's vertex, on its x
       * dof; on the straight yarn its reference x, bit for bit. */
      std::vector<double> reference_abscissa;

      /** Owned and ghost cells, in the order of their CellIds, as the
       * force loop sees them (setup_cells() says why). */
      CellData cells;
      /** The owned ones among them (indices into cells). */
      std::vector<unsigned int> owned_cells;
      // The same cells, besides: active_cell_index, local axis along x,
      // axial cell layer, reference volume [m^3].
      std::vector<unsigned int> cell_index;
      std::vector<unsigned char> cell_axis;
      std::vector<unsigned int> cell_layer;
      std::vector<double> cell_volume;
      /** The energy group of each cell and of each owned node
       * (Parameters::energy_group); empty without groups. */
      std::vector<unsigned int> cell_group, node_group;
      /** On a given mesh with sections (GivenMesh::section): each cell's
       * section over the whole mesh, material id x sections_per_yarn +
       * its section, and every section's number of cells over all ranks;
       * empty otherwise. */
      std::vector<unsigned int> cell_section, section_cells;
      /** The failure law of the force loop (make_failure_law() of
       * Yarn/Failure, Failure strain and the FE's FailureParameters). */
      FailureLaw failure_law;

      // Owned nodes: local indices of their x, y, z dofs and their station.
      std::vector<std::array<unsigned int, 3>> nodes;
      std::vector<unsigned int> node_station;
      /** The projectile contact of the owned surface nodes. */
      ProjectileContact contact;
      /** The owned nodes (indices into `nodes`) of one set of extra
       * forces, and their positions [m], velocities [m/s] and forces [N],
       * 3 each. */
      struct ExtraNodes
      {
        std::vector<unsigned int> nodes;
        std::vector<double> x, v, f;
      };
      /** Those of each of FE::Parameters::extra_forces, in its order. */
      std::vector<ExtraNodes> extra;
      /** Per owned or ghost cell: whether its failure has been reported to
       * the extra forces (report_failed_cells()). */
      std::vector<unsigned char> failure_reported;
      /** On a given mesh: each cell's mean fibre direction [-], for the
       * snapshots. */
      std::vector<std::array<double, 3>> cell_fibre;

      unsigned int n_stations      = 0;
      unsigned int n_layers        = 0;
      unsigned int cells_per_layer = 0;
      double station_spacing       = 0.;
      /** |x| of station 0 [m]: 0, or the start of a hybrid's part. */
      double station_origin = 0.;
      std::vector<double> initial_width;
      double total_mass        = 0.;
      double top               = 0.;
      double contact_time_step = 0.;
      /** Speed of the projectile at the last compute_forces() [m/s]. */
      double projectile_speed = 0.;
      /** Largest fraction of the smallest cell size a node may close in one
       * step [-] (stable_time_step()). */
      static constexpr double closing_fraction = 0.25;
    };
    // Here, not in fe_model.cc: fe_observables.cc calls it too.
    template <class Law>
    inline void
    YarnModel<Law>::vertex_positions(const unsigned int c,
                                     double (&p)[n_nodes][3]) const
    {
      const unsigned int *dofs = &cells.dofs[c * n_cell_dofs];
      for (unsigned int a = 0; a < n_nodes; ++a)
        for (unsigned int d = 0; d < 3; ++d)
          p[a][d] = reference_coordinate[dofs[3 * a + d]] +
                    displacement.local_element(dofs[3 * a + d]);
    }
  } // namespace FE
} // namespace YarnImpact

#endif
