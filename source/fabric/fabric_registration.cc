// The woven fabric's registration: `Model = fabric` (core/model_registry.h).
// Its patch is built and checked, but the model is refused before it runs:
// the contact of its crossing yarns exists (Fabric::YarnContact,
// doc/fe-model.md section 8.4), but no model steps the yarns with it yet
// (doc/fe-model.md section 8.3).

#include <yarn_impact/core/model_registry.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/fabric/woven_patch.h>

#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

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
          return "a plain-woven patch of crimped yarns (refused for now: "
                 "no model steps its yarns with their contact yet)";
        }

        /** Subsection `Fabric`. */
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
          prm.leave_subsection();
        }

        /** The patch's geometry checks, then the refusal of the run. */
        void
        validate(const YarnImpact::Parameters::Shared &shared) const override
        {
          using YarnImpact::Parameters::require;
          const WovenPatchGeometry p = patch(shared);
          std::ostringstream touch;
          touch << "= " << p.amplitude * 1e3
                << " mm must exceed the yarn's thickness semi-axis "
                   "(Yarn/Thickness semi-axis) "
                << p.thickness_semi_axis * 1e3
                << " mm, or the crossing yarns overlap at rest";
          require(p.amplitude > p.thickness_semi_axis,
                  "Fabric/Crimp amplitude",
                  touch.str());
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
          std::ostringstream refused;
          refused << "= fabric cannot run yet: its woven patch of "
                  << memory_estimate(shared).n_elements
                  << " cells is checked, but its crossing yarns press on "
                     "each other under the projectile and no model steps "
                     "them with their contact yet (a single crimped yarn "
                     "runs with Model = fe and FE/Crimp)";
          require(false, "Model", refused.str());
        }

        MemoryEstimate
        memory_estimate(
          const YarnImpact::Parameters::Shared &shared) const override
        {
          const WovenPatchGeometry p = patch(shared);
          MemoryEstimate e;
          // Every yarn's 12-cell section along the patch: n s long.
          e.n_elements =
            12. * p.cells_per_spacing *
            (p.n_warp * double(p.n_weft) + p.n_weft * double(p.n_warp));
          e.bytes        = 6.5e3 * e.n_elements;
          e.element_name = "cells";
          e.parameter    = "Fabric/Cells per spacing";
          return e;
        }

        /** Never reached: validate() refuses every fabric. */
        std::unique_ptr<ImpactModel>
        create(const YarnImpact::Parameters::Shared &,
               const MPI_Comm) const override
        {
          throw std::logic_error("Model = fabric: refused by validate()");
        }

      private:
        /** The patch of these parameters, with the section of @p shared. */
        WovenPatchGeometry
        patch(const YarnImpact::Parameters::Shared &shared) const
        {
          WovenPatchGeometry p  = g;
          p.thickness_semi_axis = shared.yarn.thickness_semi_axis;
          p.width_semi_axis     = shared.yarn.width_semi_axis;
          return p;
        }

        WovenPatchGeometry g;
      };
    } // namespace
  }   // namespace Fabric
} // namespace YarnImpact

YARN_IMPACT_REGISTER_MODEL("fabric", YarnImpact::Fabric::Plugin)
