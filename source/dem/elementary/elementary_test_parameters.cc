#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/dem/elementary/elementary_test.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <cmath>

namespace YarnImpact
{
  namespace DEM
  {
    using namespace dealii;

    void
    ElementaryTestParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Elementary test");
      prm.declare_entry(
        "Loading",
        "none",
        Patterns::Selection("none|tension|compaction|distortion"),
        "With Model = dem: none runs the impact; otherwise a periodic "
        "segment of the yarn (Yarn and DEM subsections: the impact model's "
        "fibres, packing and contacts) is loaded quasi-statically and its "
        "homogenised stress written to elementary_<loading>.csv "
        "(doc/identification.md). tension: stretched along the fibres; "
        "compaction: squeezed between rigid frictionless plates normal to "
        "y, free in z, then unloaded; distortion: the same under each "
        "confining pressure in z, held by servo-controlled side walls. "
        "An elementary test does not use Symmetry, Yarn/Length, Projectile "
        "or Time other than Time/Safety factor.");
      prm.declare_entry("Cross-sections",
                        "4",
                        Patterns::Integer(),
                        "Cross-sections of the periodic segment, at "
                        "DEM/Sphere spacing, at least 3 [-].");
      prm.declare_entry("Strain rate",
                        "2e3",
                        Patterns::Double(),
                        "Rate of the imposed strain: of the segment length "
                        "(tension) or of the plate gap (compaction, "
                        "distortion) [1/s].");
      prm.declare_entry("Largest strain",
                        "0.4",
                        Patterns::Double(),
                        "Largest imposed strain: axial engineering strain "
                        "(tension) or plate strain 1 - gap/gap_0 "
                        "(compaction, distortion), below 1 [-].");
      prm.declare_entry("Unload",
                        "true",
                        Patterns::Bool(),
                        "Whether the plates reopen to their starting gap "
                        "after loading (compaction, distortion).");
      prm.declare_entry("Side walls",
                        "none",
                        Patterns::Selection("none|fixed"),
                        "Compaction: none leaves the section free to spread "
                        "in z; fixed holds its width with rigid frictionless "
                        "walls where its edges start (uniaxial transverse "
                        "strain).");
      prm.declare_entry("Local damping",
                        "0.7",
                        Patterns::Double(),
                        "Coefficient alpha of the local (non-viscous) "
                        "damping of the quasi-static tests, in [0, 1): every "
                        "force component on a sphere is reduced by alpha "
                        "|F| against its velocity. It does not drag a "
                        "sphere at rest or in steady motion, and drains "
                        "the energy that a collapsing packing throws off "
                        "[-].");
      prm.declare_entry("Background damping time",
                        "2e-6",
                        Patterns::Double(),
                        "Time constant of a viscous damping of every "
                        "sphere's velocity, which stops the spheres that a "
                        "collapsing packing throws off (no force acts on "
                        "them, so local damping does not); 0 turns it off. "
                        "Its drag on spheres moving at the plates' speed is "
                        "given in the summary [s].");
      prm.declare_entry("Confining pressures",
                        "2e6, 10e6, 50e6",
                        Patterns::List(Patterns::Double(), 1),
                        "Distortion: the confining pressures, one run each "
                        "from the packed state [Pa].");
      prm.declare_entry("Consolidation time",
                        "10e-6",
                        Patterns::Double(),
                        "Distortion: time during which plates and side "
                        "walls hold the yarn at the confining pressure "
                        "before the plates close [s].");
      prm.declare_entry("Output strain interval",
                        "0.005",
                        Patterns::Double(),
                        "Imposed-strain increment between two rows of the "
                        "CSV [-].");
      prm.leave_subsection();
    }


    void
    ElementaryTestParameters::parse_parameters(ParameterHandler &prm)
    {
      using YarnImpact::Parameters::require;
      const std::string s = "Elementary test";
      prm.enter_subsection(s);
      const std::string l = prm.get("Loading");
      loading             = (l == "tension"      ? ElementaryLoading::tension
                             : l == "compaction" ? ElementaryLoading::compaction
                             : l == "distortion" ? ElementaryLoading::distortion
                                                 : ElementaryLoading::none);
      const int n_st      = prm.get_integer("Cross-sections");
      require(n_st >= 3,
              s + "/Cross-sections",
              "= " + std::to_string(n_st) +
                " must be at least 3 (a sphere must meet a single periodic "
                "image of another)");
      stations = static_cast<unsigned int>(n_st);
      strain_rate =
        YarnImpact::Parameters::get_positive_double(prm, s, "Strain rate");
      max_strain =
        YarnImpact::Parameters::get_positive_double(prm, s, "Largest strain");
      require(loading == ElementaryLoading::tension || max_strain < 0.9,
              s + "/Largest strain",
              "= " + std::to_string(max_strain) +
                " would close the plates (at most 0.9)");
      unload = prm.get_bool("Unload");
      side_walls =
        (prm.get("Side walls") == "fixed" ? SideWalls::fixed : SideWalls::none);
      local_damping = prm.get_double("Local damping");
      require(std::isfinite(local_damping) && local_damping >= 0. &&
                local_damping < 1.,
              s + "/Local damping",
              "must lie in [0, 1) (got " + prm.get("Local damping") + ")");
      damping_time = prm.get_double("Background damping time");
      require(std::isfinite(damping_time) && damping_time >= 0.,
              s + "/Background damping time",
              "must be zero or positive (got " +
                prm.get("Background damping time") + ")");
      confining_pressures.clear();
      for (const auto &item :
           Utilities::split_string_list(prm.get("Confining pressures")))
        {
          const double p = Utilities::string_to_double(item);
          require(p > 0.,
                  s + "/Confining pressures",
                  "must all be positive (got " + item + ")");
          confining_pressures.push_back(p);
        }
      consolidation_time =
        YarnImpact::Parameters::get_positive_double(prm,
                                                    s,
                                                    "Consolidation time");
      output_strain_interval =
        YarnImpact::Parameters::get_positive_double(prm,
                                                    s,
                                                    "Output strain interval");
      prm.leave_subsection();
    }
  } // namespace DEM
} // namespace YarnImpact
