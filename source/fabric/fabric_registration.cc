// The woven fabric's registration: `Model = fabric` (core/model_registry.h,
// doc/fabric.md): the FE yarns of subsection `FE` on the woven patch of
// subsection `Fabric`, with the contact of their crossings.

#include <yarn_impact/core/model_registry.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/fabric/fabric_model.h>
#include <yarn_impact/fabric/mesh_file.h>
#include <yarn_impact/fabric/woven_patch.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <sstream>
#include <utility>

namespace YarnImpact
{
  namespace Fabric
  {
    namespace
    {
      /** The woven fabric with its parameters (subsection `Fabric`), as the
       * application sees it. */
      class Plugin : public ModelPlugin
      {
      public:
        /** What the model is, for the help of `Model`. */
        static std::string
        help()
        {
          return "a plain-woven patch of crimped FE yarns with the contact "
                 "of their crossings";
        }

        /** Subsection `Fabric` (the FE yarns read subsection `FE`,
         * which the FE model declares). */
        static void
        declare_parameters(dealii::ParameterHandler &prm)
        {
          using dealii::Patterns::Double;
          using dealii::Patterns::Integer;
          prm.enter_subsection("Fabric");
          prm.declare_entry("Warp yarns",
                            "2",
                            Integer(),
                            "Number of warp yarns, along x, side by side in "
                            "z [-].");
          prm.declare_entry("Weft yarns",
                            "2",
                            Integer(),
                            "Number of weft yarns, along z, side by side in "
                            "x [-].");
          prm.declare_entry("Yarn spacing",
                            "1e-3",
                            Double(),
                            "Distance between neighbouring parallel yarns; "
                            "the crimp wavelength is twice it; above the "
                            "yarn's width, 2 x Yarn/Width semi-axis [m].");
          prm.declare_entry("Crimp amplitude",
                            "0.1e-3",
                            Double(),
                            "Crimp amplitude of every yarn: crossing "
                            "centrelines are twice it apart; above "
                            "Yarn/Thickness semi-axis, so that crossing "
                            "yarns do not touch at rest [m].");
          prm.declare_entry("Cells per spacing",
                            "8",
                            Integer(),
                            "Cells along each yarn per Yarn spacing [-].");
          prm.declare_entry(
            "Clamped edges",
            "all",
            dealii::Patterns::Selection("all|warp ends|weft ends|none"),
            "Which yarn ends are clamped: all (the four edges), warp ends "
            "(the edges x = +-Weft yarns x Yarn spacing / 2), weft ends "
            "(the edges z = +-Warp yarns x Yarn spacing / 2) or none (a "
            "free patch); the other ends are free.");
          prm.declare_entry("Plies",
                            "1",
                            Integer(),
                            "Number of plies: copies of the woven layer "
                            "stacked along -y, each shifted from the one "
                            "above by Ply spacing and by Ply offset x and z, "
                            "ply 0 on top, struck first [-].");
          prm.declare_entry("Ply spacing",
                            "0.5e-3",
                            Double(),
                            "Distance along y between the mid-planes of "
                            "consecutive plies; with several plies, above a "
                            "ply's meshed thickness, 2 x (Crimp amplitude + "
                            "the meshed section's semi-thickness, "
                            "Yarn/Thickness semi-axis scaled to the "
                            "ellipse's area), so that the plies do not touch "
                            "at rest [m].");
          prm.declare_entry("Ply offset x",
                            "0",
                            Double(),
                            "Shift along x of each ply from the ply above, "
                            "with several plies: ply p is ply 0 moved by p "
                            "times it; 0 (and Ply offset z 0) stacks the "
                            "plies aligned, their crossings over each other. "
                            "0 with a symmetry plane [m].");
          prm.declare_entry("Ply offset z",
                            "0",
                            Double(),
                            "Shift along z of each ply from the ply above, "
                            "as Ply offset x [m].");
          prm.declare_entry("Cone deflection threshold",
                            "10e-6",
                            Double(),
                            "Deflection along -y above which a point of the "
                            "yarns' surface is inside the cone, for the "
                            "history's cone fronts [m].");
          prm.declare_entry(
            "Mesh file",
            "",
            dealii::Patterns::Anything(),
            "A Gmsh mesh (.msh) of hexahedra to run instead of the generated "
            "patch: physical group g >= 1 makes a cell one of yarn g - 1; "
            "physical surfaces 1 (lateral), 2 (clamped end), 3 (free end), "
            "untagged boundary faces found by their normals "
            "(doc/fabric.md section 8). Empty: the generated patch.");
          prm.declare_entry(
            "Orientation file",
            "",
            dealii::Patterns::Anything(),
            "With Mesh file: each cell's fibre direction, one line per cell "
            "in the mesh file's order, 3 numbers (a unit direction) or 24 "
            "(one per Gauss point); '#' starts a comment. Empty: estimated "
            "from the mesh.");
          prm.declare_entry(
            "Step timing",
            "false",
            dealii::Patterns::Bool(),
            "true: time the parts of the step (the yarn contact's list "
            "checks, list builds, exchange and forces; the FE forces with "
            "the projectile contact; integration; stable step; observables; "
            "output) and add their table to the run's summary; only clocks "
            "are read, the history is the same [-].");
          prm.enter_subsection("Clamp grip");
          prm.declare_entry(
            "Pull-out force",
            "0",
            Double(0.),
            "Force at which a clamped yarn end slips in its clamp: the "
            "clamp holds each node of the end section by a spring capped "
            "by Coulomb's law, this force shared by the nodes' areas "
            "(doc/fabric.md section 11). 0: the clamps hold the ends "
            "rigidly [N].");
          prm.declare_entry(
            "Stiffness",
            "0",
            Double(0.),
            "Stiffness of the grip of one yarn end before it slips, with "
            "Pull-out force > 0. 0: the axial stiffness E A / h of the "
            "yarn's end cell (E the law's axial modulus, A the section's "
            "area, h the cell's length) [N/m].");
          prm.leave_subsection();
          prm.enter_subsection("Yarn contact");
          prm.declare_entry("Penalty",
                            "5e13",
                            Double(0.),
                            "Contact pressure per penetration between "
                            "crossing yarns; each side is a slave with half "
                            "of it [Pa/m].");
          prm.declare_entry("Friction",
                            "0.2",
                            Double(0.),
                            "Coulomb friction coefficient between yarns "
                            "[-].");
          prm.declare_entry("Tangential stiffness ratio",
                            "1",
                            Double(0.),
                            "Stick spring's stiffness over the normal one "
                            "(Cundall-Strack) [-].");
          prm.declare_entry("Damping ratio",
                            "0",
                            Double(0.),
                            "Normal damping, fraction of the critical "
                            "damping of a node's mass on its spring [-].");
          prm.declare_entry("Detection depth",
                            "20e-6",
                            Double(0.),
                            "Deepest penetration at which a contact starts "
                            "[m] (a touching contact holds its node to "
                            "twice it); below the yarn's meshed thickness "
                            "semi-axis, so that a node pressed into a yarn "
                            "is not found under its far side.");
          prm.declare_entry("Skin",
                            "20e-6",
                            Double(0.),
                            "Skin of the candidate search: the lists are "
                            "built again when a node has moved half of it "
                            "[m].");
          prm.leave_subsection();
          prm.leave_subsection();
        }

        void
        parse_parameters(dealii::ParameterHandler &prm) override
        {
          using YarnImpact::Parameters::get_positive_double;
          using YarnImpact::Parameters::get_positive_integer;
          prm.enter_subsection("Fabric");
          g.n_warp    = get_positive_integer(prm, "Fabric", "Warp yarns");
          g.n_weft    = get_positive_integer(prm, "Fabric", "Weft yarns");
          g.spacing   = get_positive_double(prm, "Fabric", "Yarn spacing");
          g.amplitude = get_positive_double(prm, "Fabric", "Crimp amplitude");
          g.cells_per_spacing =
            get_positive_integer(prm, "Fabric", "Cells per spacing");
          const std::string clamped = prm.get("Clamped edges");
          g.clamp_warp_ends = (clamped == "all" || clamped == "warp ends");
          g.clamp_weft_ends = (clamped == "all" || clamped == "weft ends");
          g.n_plies         = get_positive_integer(prm, "Fabric", "Plies");
          g.ply_spacing     = get_positive_double(prm, "Fabric", "Ply spacing");
          g.ply_offset_x    = prm.get_double("Ply offset x");
          g.ply_offset_z    = prm.get_double("Ply offset z");
          fabric.cone_threshold =
            get_positive_double(prm, "Fabric", "Cone deflection threshold");
          fabric.mesh_file        = prm.get("Mesh file");
          fabric.orientation_file = prm.get("Orientation file");
          fabric.step_timing      = prm.get_bool("Step timing");
          prm.enter_subsection("Clamp grip");
          fabric.grip.pull_out_force = prm.get_double("Pull-out force");
          fabric.grip.stiffness      = prm.get_double("Stiffness");
          prm.leave_subsection();
          prm.enter_subsection("Yarn contact");
          YarnContactParameters &c = fabric.contact;
          c.penalty =
            get_positive_double(prm, "Fabric/Yarn contact", "Penalty");
          c.friction = prm.get_double("Friction");
          c.tangential_stiffness_ratio =
            prm.get_double("Tangential stiffness ratio");
          c.damping_ratio = prm.get_double("Damping ratio");
          c.detection_depth =
            get_positive_double(prm, "Fabric/Yarn contact", "Detection depth");
          c.skin = get_positive_double(prm, "Fabric/Yarn contact", "Skin");
          prm.leave_subsection();
          prm.leave_subsection();
          fe.parse_parameters(prm);
        }

        /** The patch's geometry checks, the run's (symmetry planes
         * where the weave and the impact allow them, no FE/Crimp, no global
         * refinement, a projectile narrower than the patch), then
         * FE::validate() of the FE yarns as the model will make them. */
        void
        validate(const YarnImpact::Parameters::Shared &shared) const override
        {
          using YarnImpact::Parameters::require;
          const WovenPatchGeometry p = patch(shared);
          require(fabric.orientation_file.empty() || !fabric.mesh_file.empty(),
                  "Fabric/Orientation file",
                  "needs Fabric/Mesh file: the generated patch has its own "
                  "fibre directions");
          if (!fabric.mesh_file.empty())
            {
              // Read once here, so that --check refuses a bad file.
              try
                {
                  MeshFile(fabric.mesh_file,
                           fabric.orientation_file,
                           p.clamp_warp_ends,
                           p.clamp_weft_ends);
                }
              catch (const MeshFileError &e)
                {
                  require(false, e.parameter, e.what());
                }
            }
          require(fabric.grip.pull_out_force == 0. ||
                    !fabric.mesh_file.empty() || p.clamp_warp_ends ||
                    p.clamp_weft_ends,
                  "Fabric/Clamp grip/Pull-out force",
                  "grips the clamped yarn ends, and Fabric/Clamped edges = "
                  "none clamps none: set it to 0 or clamp some edges");
          require(fabric.grip.stiffness == 0. ||
                    fabric.grip.pull_out_force > 0.,
                  "Fabric/Clamp grip/Stiffness",
                  "is the stiffness of a grip that can slip, and "
                  "Fabric/Clamp grip/Pull-out force = 0 clamps the ends "
                  "rigidly: set a pull-out force or leave it 0");
          // The meshed section's vertices reach beyond the ellipse (it is
          // scaled to the ellipse's area).
          const double meshed = WovenPatch::meshed_thickness_semi_axis(p);
          std::ostringstream touch;
          touch << "= " << p.amplitude * 1e3
                << " mm must exceed the yarn's thickness semi-axis as "
                   "meshed (Yarn/Thickness semi-axis scaled to the "
                   "ellipse's area) "
                << meshed * 1e3 << " mm, or the crossing yarns overlap at rest";
          require(p.amplitude > meshed, "Fabric/Crimp amplitude", touch.str());
          // Deeper than half a yarn's thickness, a node pressed into it
          // would be nearer its far side than its near one.
          std::ostringstream deep;
          deep << "= " << fabric.contact.detection_depth * 1e6
               << " um must be below the yarn's thickness semi-axis as meshed "
               << meshed * 1e6
               << " um, or a node pressed into a yarn is found under its far "
                  "side";
          require(fabric.contact.detection_depth < meshed,
                  "Fabric/Yarn contact/Detection depth",
                  deep.str());
          std::ostringstream wide;
          wide << "= " << p.spacing * 1e3
               << " mm must exceed the yarn's width (2 x Yarn/Width "
                  "semi-axis) "
               << 2e3 * p.width_semi_axis
               << " mm, or neighbouring parallel yarns overlap";
          require(p.spacing > 2. * p.width_semi_axis,
                  "Fabric/Yarn spacing",
                  wide.str());
          // The smallest radius of curvature of the crimp, (2 s)^2 /
          // (4 pi^2 A), at the crossings.
          const double radius =
            p.spacing * p.spacing / (M_PI * M_PI * p.amplitude);
          std::ostringstream fold;
          fold << "= " << p.amplitude * 1e3
               << " mm folds the yarns: the smallest radius of curvature "
                  "of their centrelines, "
               << radius * 1e3 << " mm, must exceed the thickness semi-axis";
          require(radius > p.thickness_semi_axis,
                  "Fabric/Crimp amplitude",
                  fold.str());
          // A ply's mesh spans its mid-plane +-(A + the meshed section's
          // semi-thickness), its crests' tops.
          const double thickness = WovenPatch::ply_thickness(p);
          std::ostringstream plies;
          plies << "= " << p.ply_spacing * 1e3
                << " mm must exceed a ply's thickness, 2 x (Fabric/Crimp "
                   "amplitude + the meshed section's semi-thickness, "
                   "Yarn/Thickness semi-axis scaled to the ellipse's area) = "
                << thickness * 1e3
                << " mm, or neighbouring plies overlap at rest";
          require(p.n_plies == 1 || p.ply_spacing > thickness,
                  "Fabric/Ply spacing",
                  plies.str());
          check_symmetry(shared, p);
          require(!fe.crimp.crimped(),
                  "FE/Crimp/Amplitude",
                  "must be 0 with Model = fabric: its yarns take their "
                  "crimp from Fabric/Crimp amplitude");
          require(fe.global_refinements == 0,
                  "FE/Global refinements",
                  "must be 0 with Model = fabric: refine along the yarns "
                  "with Fabric/Cells per spacing, across with "
                  "FE/Section refinements");
          // The cylinder spans the patch along z; along x it must stay
          // inside the warp yarns' span.
          std::ostringstream wide_projectile;
          wide_projectile
            << "= " << shared.projectile.diameter * 1e3
            << " mm must be less than the patch's extent across the "
               "projectile's axis (Fabric/Weft yarns x Fabric/Yarn spacing) "
            << p.n_weft * p.spacing * 1e3
            << " mm, or the projectile reaches the patch's edges";
          require(shared.projectile.diameter < p.n_weft * p.spacing,
                  "Projectile/Diameter",
                  wide_projectile.str());
          // The sphere and the flat cylinder must also stay inside the
          // weft yarns' span.
          std::ostringstream wide_sphere;
          wide_sphere << "= " << shared.projectile.diameter * 1e3
                      << " mm must be less than the patch's extent along z "
                         "(Fabric/Warp yarns x Fabric/Yarn spacing) "
                      << p.n_warp * p.spacing * 1e3 << " mm for a "
                      << shape_name(shared)
                      << ", or it reaches the patch's edges";
          const bool along_z =
            shared.projectile.shape ==
            YarnImpact::Parameters::ProjectileShape::cylinder;
          require(along_z || shared.projectile.diameter < p.n_warp * p.spacing,
                  "Projectile/Diameter",
                  wide_sphere.str());
          // Off the centre, the projectile must still stay inside.
          const double R  = 0.5 * shared.projectile.diameter;
          const double x0 = shared.projectile.offset_x,
                       z0 = shared.projectile.offset_z;
          std::ostringstream off_x;
          off_x << "= " << x0 * 1e3
                << " mm puts the projectile's edge at |x| = "
                << (std::abs(x0) + R) * 1e3
                << " mm, beyond the patch's edge at Fabric/Weft yarns x "
                   "Fabric/Yarn spacing / 2 = "
                << 0.5e3 * p.n_weft * p.spacing << " mm";
          require(std::abs(x0) + R < 0.5 * p.n_weft * p.spacing,
                  "Projectile/Impact offset x",
                  off_x.str());
          require(!along_z || z0 == 0.,
                  "Projectile/Impact offset z",
                  "must be 0 with Projectile/Shape = cylinder: its axis is "
                  "along z");
          std::ostringstream off_z;
          off_z << "= " << z0 * 1e3
                << " mm puts the projectile's edge at |z| = "
                << (std::abs(z0) + R) * 1e3
                << " mm, beyond the patch's edge at Fabric/Warp yarns x "
                   "Fabric/Yarn spacing / 2 = "
                << 0.5e3 * p.n_warp * p.spacing << " mm";
          require(along_z || std::abs(z0) + R < 0.5 * p.n_warp * p.spacing,
                  "Projectile/Impact offset z",
                  off_z.str());
          FE::validate(with_patch(shared), fe_of_patch());
        }

        MemoryEstimate
        memory_estimate(
          const YarnImpact::Parameters::Shared &shared) const override
        {
          const WovenPatchGeometry p = patch(shared);
          MemoryEstimate e;
          // Every yarn's 12-cell section, refined, along the patch: n s
          // long.
          e.n_elements =
            12. * std::pow(4., fe.section_refinements) * p.cells_per_spacing *
            (p.n_warp * double(p.n_weft) + p.n_weft * double(p.n_warp)) *
            p.n_plies;
          e.bytes        = 6.5e3 * e.n_elements;
          e.element_name = "cells";
          e.parameter    = "Fabric/Cells per spacing";
          return e;
        }

        std::unique_ptr<ImpactModel>
        create(const YarnImpact::Parameters::Shared &shared,
               const MPI_Comm communicator) const override
        {
          FabricParameters f = fabric;
          f.patch            = g;
          return create_fabric_model(shared, fe, f, communicator);
        }

        /** A woven patch, not the single yarn: it runs alone. */
        bool
        single_yarn() const override
        {
          return false;
        }

      private:
        /** The symmetry planes' conditions (doc/fabric.md section 10):
         * the generated patch, a plane on the middle yarn's centreline
         * (the plain weave is its own mirror image there, not between two
         * yarns, where over and under swap) and a layer of nodes, the
         * impact on the planes. */
        void
        check_symmetry(const YarnImpact::Parameters::Shared &shared,
                       const WovenPatchGeometry &p) const
        {
          using YarnImpact::Parameters::require;
          using YarnImpact::Parameters::Symmetry;
          const Symmetry symmetry = shared.general.symmetry;
          if (symmetry == Symmetry::none)
            return;
          const bool quarter = symmetry == Symmetry::quarter;
          require(fabric.mesh_file.empty(),
                  "Symmetry",
                  "must be none with Fabric/Mesh file: only the generated "
                  "patch is cut by symmetry planes");
          for (const auto &[offset, name] :
               {std::pair(p.ply_offset_x, "Fabric/Ply offset x"),
                std::pair(p.ply_offset_z, "Fabric/Ply offset z")})
            require(p.n_plies == 1 || offset == 0.,
                    name,
                    "must be 0 with Symmetry = half or quarter: plies "
                    "shifted in the fabric's plane are not mirror-symmetric");
          require(p.n_weft % 2 == 1,
                  "Fabric/Weft yarns",
                  "must be odd with Symmetry = half or quarter: the plane "
                  "x = 0 must be the middle weft yarn's centreline, about "
                  "which the plain weave is its own mirror image; between "
                  "two weft yarns the mirror image swaps over and under");
          require(!quarter || p.n_warp % 2 == 1,
                  "Fabric/Warp yarns",
                  "must be odd with Symmetry = quarter: the plane z = 0 "
                  "must be the middle warp yarn's centreline, about which "
                  "the plain weave is its own mirror image; between two "
                  "warp yarns the mirror image swaps over and under");
          require(p.cells_per_spacing % 2 == 0,
                  "Fabric/Cells per spacing",
                  "must be even with Symmetry = half or quarter, so that "
                  "the symmetry planes are layers of nodes of the yarns "
                  "they cut at mid-length");
          require(shared.projectile.offset_x == 0.,
                  "Projectile/Impact offset x",
                  "must be 0 with Symmetry = half or quarter: the "
                  "projectile must be its own mirror image in the plane "
                  "x = 0");
          require(!quarter || shared.projectile.offset_z == 0.,
                  "Projectile/Impact offset z",
                  "must be 0 with Symmetry = quarter: the projectile must "
                  "be its own mirror image in the plane z = 0");
        }

        /** The name of @p shared's projectile's shape, for messages. */
        static const char *
        shape_name(const YarnImpact::Parameters::Shared &shared)
        {
          return shared.projectile.shape ==
                     YarnImpact::Parameters::ProjectileShape::sphere
                   ? "sphere"
                   : "flat cylinder";
        }

        /** The patch of these parameters, with the section of @p shared. */
        WovenPatchGeometry
        patch(const YarnImpact::Parameters::Shared &shared) const
        {
          WovenPatchGeometry p  = g;
          p.thickness_semi_axis = shared.yarn.thickness_semi_axis;
          p.width_semi_axis     = shared.yarn.width_semi_axis;
          p.section_refinements = fe.section_refinements;
          return p;
        }

        /** @p shared with the warp yarns' span as its Yarn/Length, as
         * create_fabric_model() gives the FE model. */
        YarnImpact::Parameters::Shared
        with_patch(const YarnImpact::Parameters::Shared &shared) const
        {
          YarnImpact::Parameters::Shared copy = shared;
          copy.yarn.length                    = g.n_weft * g.spacing;
          return copy;
        }

        /** The FE parameters as create_fabric_model() gives them (the
         * cells along a warp yarn), for FE::validate(). */
        FE::Parameters
        fe_of_patch() const
        {
          FE::Parameters p = fe;
          p.n_axial_cells  = g.n_weft * g.cells_per_spacing;
          p.n_axial_cells += p.n_axial_cells % 2;
          return p;
        }

        WovenPatchGeometry g;
        FabricParameters fabric;
        FE::Parameters fe;
      };
    } // namespace
  }   // namespace Fabric
} // namespace YarnImpact

YARN_IMPACT_REGISTER_MODEL("fabric", YarnImpact::Fabric::Plugin)
