#ifndef yarn_impact_fe_parameters_h
#define yarn_impact_fe_parameters_h

#include <yarn_impact/contact/contact_law.h>
#include <yarn_impact/fe/failure_law.h>

#include <functional>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace dealii
{
  class ParameterHandler;
  template <int dim, int spacedim>
  class Triangulation;
} // namespace dealii

namespace YarnImpact
{
  namespace FE
  {
    class ExtraForces;

    /**
     * A mesh that a model made of several FE yarns gives the FE model
     * (`Model = fabric`, doc/fabric.md), never a `.prm`: then the FE
     * model meshes nothing itself, clamps the nodes on the faces of
     * BoundaryIds::clamp (whatever their position), and has no cut-through
     * (several yarns make no single load path). The stations still go by
     * the reference x, over [-L/2, L/2] in FE::Parameters::n_axial_cells,
     * L the `Yarn/Length` the model is given.
     */
    struct GivenMesh
    {
      /** Create the whole mesh, not refined, with the boundary ids
       * BoundaryIds::lateral and BoundaryIds::clamp and the material id of
       * each cell's yarn. Empty: the FE model's own yarn. */
      std::function<void(dealii::Triangulation<3, 3> &)> create;
      /** The height [m] of the reference point X [m] (the argument, 3
       * values) across its yarn towards the projectile, along its
       * section's normal: it places a cell's depth below the struck face
       * (CellData::depth). */
      std::function<double(const double *)> section_height;
      /** The section [-], below sections_per_yarn, of the cell of
       * material id m (the first argument, its yarn) whose reference
       * centre is X [m] (the second, 3 values): the layer of cells across
       * its yarn at one station along its centreline. With it the FE
       * model counts the broken yarns, the material ids below n_yarns
       * with a section whose every cell has failed (broken or fully
       * damaged) or been eroded, and gives the count as its one own
       * history column, `broken yarns` (ImpactModel::extra_column_names).
       * Empty: no count, no column. */
      std::function<unsigned int(unsigned int, const double *)> section;
      /** Sections of a yarn, at most [-] (section). */
      unsigned int sections_per_yarn = 0;
      /** Yarns [-]: the material ids are 0 to n_yarns - 1 (section). */
      unsigned int n_yarns = 0;
      /** The yarns of the whole model [-] that each material id stands
       * for in the count of broken yarns: 2 for a yarn whose mirror image
       * in a symmetry plane parallel to it is not modelled, 1 for one
       * the planes cut (at mid-length or lengthwise), 0 for one not
       * meshed. Empty: 1 each. */
      std::vector<unsigned int> yarn_copies;
      /** Cell fields of the snapshots beside `yarn` (the material id):
       * each a name and the value [-] of the cells of a material id, the
       * argument. None by default. */
      std::vector<std::pair<std::string, std::function<double(unsigned int)>>>
        material_fields;
      /** Boundary ids of faces whose nodes stay out of the projectile's
       * contact, as the clamped nodes do: the ends held in a clamp by a
       * grip of finite force (extra forces), where the projectile would
       * strike the clamp. None by default. */
      std::set<unsigned int> outside_projectile_contact;

      /** Whether a mesh is given. */
      bool
      given() const
      {
        return static_cast<bool>(create);
      }
    };

    /** Constitutive law of the continuum yarn. */
    enum class LawType
    {
      charmetant,                    ///< the paper's hyperelastic law
      linear_transversely_isotropic, ///< the classical yarn model
    };

    /**
     * Parameters of the Charmetant-type hyperelastic law
     * \f$W = \tfrac12 k_e I_e^2 + k_{tc}|I_{tc}|^p + \tfrac12 k_{td}I_{td}^2\f$
     * (paper Table 1, subsection `FE/Charmetant`).
     */
    struct CharmetantParameters
    {
      double k_e  = 80077.19e6; ///< elongation modulus [Pa]
      double k_tc = 1055.82e6;  ///< compaction modulus [Pa]
      double p    = 2.205;      ///< compaction exponent [-]
      double k_td = 649.75e6;   ///< distortion modulus [Pa]
      /** Whether the compaction term also resists the section's dilation
       * (I_tc > 0), as the identified law does; a coupling may turn it off
       * where the continuum stands for loose fibres, which spread without
       * resistance (doc/hybrid.md section 3.4). Not a `.prm` entry. */
      bool resist_dilation = true;
    };

    /**
     * Parameters of the classical linear transversely isotropic yarn law in
     * St. Venant-Kirchhoff form, fibre direction x (subsection
     * `FE/Linear transversely isotropic`).
     */
    struct LinearParameters
    {
      double E_L   = 80077.19e6; ///< longitudinal Young modulus [Pa]
      double E_T   = 650e6;      ///< transverse Young modulus [Pa]
      double G_LT  = 650e6;      ///< longitudinal shear modulus [Pa]
      double nu_LT = 0.;         ///< major Poisson ratio [-]
      double nu_TT = 0.;         ///< transverse Poisson ratio [-]
    };

    /** Projectile-yarn contact (subsection `FE/Contact`). */
    struct ContactParameters
    {
      /** Contact law of a surface node (contact/contact_law.h). */
      Contact::LawType law = Contact::LawType::penalty_coulomb;
      /** Penalty: contact pressure per unit penetration [Pa/m]. */
      double penalty = 5e13;
      /** Coulomb friction coefficient between projectile and yarn [-];
       * the DEM's projectile friction by default. */
      double friction = 0.2;
      /** Viscous damping of the contact, fraction of critical [-]. */
      double damping_ratio = 0.;
      /** Tangential stiffness over the normal one, for a law with a
       * tangential spring (Cundall-Strack) [-]. */
      double tangential_stiffness_ratio = 0.2857142857142857;
    };

    /**
     * The yarn's crimp (subsection `FE/Crimp`, doc/fe-model.md section 8):
     * its centreline c(x) = (x, A cos(2 pi x / lambda), 0) over the span
     * x in [-L/2, L/2], a crest under the projectile at x = 0, the section
     * normal to the centreline and the fibres along its tangent
     * (Fabric::CrimpedYarn). A = 0: the straight yarn.
     */
    struct CrimpParameters
    {
      /** Crimp amplitude A [m]: the centreline's largest distance from
       * the plane y = 0. */
      double amplitude = 0.;
      /** Crimp wavelength lambda [m], along x. */
      double wavelength = 2e-3;

      /** Whether the yarn is crimped (A > 0). */
      bool
      crimped() const
      {
        return amplitude > 0.;
      }
    };

    /** All parameters of the FE model (subsection `FE`). */
    struct Parameters
    {
      /** Constitutive law. */
      LawType law = LawType::charmetant;
      /** Density of the continuum yarn [kg/m^3]. */
      double density = 1267.;
      /** Derive the density from the DEM's mass per length (fibre density
       * times fibre area over section area) instead of `Density`. */
      bool density_from_fibres = false;
      /** Derive the axial modulus (Charmetant k_e, linear E_L) from the
       * DEM's axial stiffness (fibre Young modulus times fibre area over
       * section area) instead of the law's own entry. */
      bool axial_modulus_from_fibres = false;
      /** Cells along the whole yarn length [-]. */
      unsigned int n_axial_cells = 100;
      /** Refinements of the 12-cell section [-]. */
      unsigned int section_refinements = 0;
      /** Scale the polygonal section so that its area is that of the
       * ellipse (exact mass per length and axial stiffness on coarse
       * sections). */
      bool preserve_section_area = true;
      /** Refinements of the 3D mesh in all directions [-]. */
      unsigned int global_refinements = 0;

      CharmetantParameters charmetant;
      LinearParameters linear;
      ContactParameters contact;
      /** How a cell fails (entries of subsection `Yarn`). */
      FailureParameters failure;
      /** The yarn's crimp (none by default). */
      CrimpParameters crimp;

      /**
       * Set by a coupling (`Model = hybrid`, coupling/hybrid_model.h), never
       * by a `.prm`: the FE part of a hybrid yarn (half symmetry) spans
       * x in [part_begin, part_end] [m] (part_end negative: L/2, the clamp)
       * in layer_weight.size() equal cell layers, the end x = part_begin
       * free (the coupling moves it), and so the end x = part_end when it
       * is not the clamp; the cells of layer k carry the continuum weight
       * layer_weight[k] [-] in their mass, stress and energies
       * (doc/hybrid.md). Empty: the whole yarn.
       */
      double part_begin = 0., part_end = -1.;
      std::vector<double> layer_weight;
      /** Also set by a coupling: in every cell of the part, each Gauss
       * point's weight is multiplied by this factor of its reference
       * position (x, y, z) [m], so that the section's quadrature gives each
       * node the fibres' share of the axial stiffness (doc/hybrid.md
       * section 3.3). Empty: 1. */
      std::function<double(const double *)> section_quadrature_factor;
      /** Also set by a coupling: a part without fibre failure (Yarn/Failure
       * off in its problem) still erodes its crushed, inverted or
       * non-finite cells (FailureLaw::Kind::erosion), because its fibres
       * break in the other model and its cells among their broken ends
       * are crushed as those of a failing FE yarn (doc/hybrid.md section
       * 3.4). */
      bool erode_crushed_cells = false;
      /** Also set by a coupling: whether the projectile touches the yarn's
       * surface nodes. Off for the hybrid's FE part under fibre bars,
       * whose bar nodes touch it instead (doc/hybrid.md section 3.4). */
      bool projectile_contact = true;
      /** Also set by a coupling: the part models the mirror image x -> -x
       * of the yarn it stands for (the FE part on x < 0 of a whole hybrid
       * yarn is built as the one on x > 0, doc/hybrid.md section 3.1), so
       * its snapshots are written reflected back, under the file name
       * snapshot_name. */
      bool mirrored = false;
      /** Also set by a coupling: the snapshots' file name before
       * `_NNNN.pvtu` (`fe` by default). */
      std::string snapshot_name = "fe";
      /** Set by a model whose yarns are curved, never by a `.prm`: the unit
       * fibre direction M(X) [-] (written to the second argument) at a
       * reference point X = (x, y, z) [m], given to every Gauss point as
       * its fibre frame (CellData::frames, doc/theory.md section 1.8).
       * Empty: M = e_x everywhere, the straight yarn, and the force loop's
       * straight path. A cell's crack band width and the stable step's
       * fibre axis are then measured along its mean fibre direction. */
      std::function<void(const double *, double *)> fibre_direction;
      /** Set by a model made of several yarns, never by a `.prm`: its
       * mesh (GivenMesh; none by default). */
      GivenMesh mesh;
      /** Set by a model made of several yarns, never by a `.prm`: the
       * sets of forces it adds on the FE nodes, each with its energy,
       * dissipation, stable step and checkpoint (ExtraForces), in the
       * order in which the FE model calls them. None by default. */
      std::vector<std::shared_ptr<ExtraForces>> extra_forces;
      /** Set by a model made of several yarns, never by a `.prm`: the
       * group [-], below n_energy_groups, of the cells of each material
       * id, whose kinetic and strain energies Observables::
       * group_kinetic_energy and group_elastic_energy give apart (a node
       * goes with the group of the cells around it: it belongs to one
       * yarn). None by default. */
      std::function<unsigned int(unsigned int)> energy_group;
      /** The number of groups of energy_group [-]. */
      unsigned int n_energy_groups = 0;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace FE
} // namespace YarnImpact

#endif
