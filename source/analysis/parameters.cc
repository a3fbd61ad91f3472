#include <yarn_impact/analysis/parameters.h>
#include <yarn_impact/core/parameter_tools.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <sstream>
#include <string>

namespace YarnImpact
{
  namespace Analysis
  {
    using namespace dealii;
    using YarnImpact::Parameters::get_positive_double;
    using YarnImpact::Parameters::require;

    void
    WaveFrontThresholds::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Wave fronts");
      prm.declare_entry("Strain threshold",
                        "2e-4",
                        Patterns::Double(),
                        "Longitudinal front: the outermost axial station "
                        "whose longitudinal strain exceeds this value [-].");
      prm.declare_entry("Deflection threshold",
                        "10e-6",
                        Patterns::Double(),
                        "Transverse front: the outermost axial station whose "
                        "deflection in the impact direction exceeds this "
                        "value [m].");
      prm.declare_entry("Spreading threshold",
                        "0.02",
                        Patterns::Double(),
                        "Spreading front: the outermost axial station whose "
                        "section width exceeds its initial width by this "
                        "fraction [-].");
      prm.leave_subsection();
    }

    void
    WaveFrontThresholds::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Wave fronts");
      strain_threshold =
        get_positive_double(prm, "Wave fronts", "Strain threshold");
      deflection_threshold =
        get_positive_double(prm, "Wave fronts", "Deflection threshold");
      spreading_threshold =
        get_positive_double(prm, "Wave fronts", "Spreading threshold");
      prm.leave_subsection();
    }


    void
    Verification::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Verification");
      prm.declare_entry("Window start",
                        "1e-6",
                        Patterns::Double(),
                        "Start of the time window in which the run is "
                        "compared with Smith theory (mean deceleration, "
                        "strain behind the longitudinal front, front "
                        "speeds) [s].");
      prm.declare_entry("Window end",
                        "3e-6",
                        Patterns::Double(),
                        "End of that window; it should end before the first "
                        "longitudinal wave reflected at a clamp is back at "
                        "the impact point [s].");
      prm.declare_entry(
        "Checks",
        "",
        Patterns::MultipleSelection(
          "deceleration|plateau strain|longitudinal speed|transverse "
          "speed|energy"),
        "Checks asserted at the end of the run; the run exits with a "
        "non-zero code when one fails. deceleration: mean projectile "
        "deceleration in the window against Smith theory; plateau strain: "
        "strain behind the longitudinal front; longitudinal speed and "
        "transverse speed: front speeds fitted in the window (laboratory "
        "frame); energy: largest energy balance error of the run.");
      prm.declare_entry("Tolerance",
                        "0.03",
                        Patterns::Double(0.),
                        "Relative tolerance of the Smith-theory checks [-].");
      prm.declare_entry("Energy tolerance",
                        "0.005",
                        Patterns::Double(0.),
                        "Largest energy balance error accepted by the energy "
                        "check, as a fraction of the initial energy [-].");
      prm.leave_subsection();
    }

    void
    Verification::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Verification");
      window_start = prm.get_double("Window start");
      window_end   = prm.get_double("Window end");
      require(window_start >= 0.,
              "Verification/Window start",
              "must not be negative");
      require(window_end > window_start,
              "Verification/Window end",
              "must be later than Window start");
      const std::string checks = prm.get("Checks");
      const auto has           = [&checks](const std::string &name) {
        for (const auto &item : Utilities::split_string_list(checks))
          if (item == name)
            return true;
        return false;
      };
      check_deceleration       = has("deceleration");
      check_plateau_strain     = has("plateau strain");
      check_longitudinal_speed = has("longitudinal speed");
      check_transverse_speed   = has("transverse speed");
      check_energy             = has("energy");
      tolerance                = prm.get_double("Tolerance");
      energy_tolerance         = prm.get_double("Energy tolerance");
      prm.leave_subsection();
    }


    void
    Parameters::declare_parameters(ParameterHandler &prm)
    {
      WaveFrontThresholds::declare_parameters(prm);
      Verification::declare_parameters(prm);
    }


    void
    Parameters::parse_parameters(ParameterHandler &prm,
                                 const YarnImpact::Parameters::Shared &shared)
    {
      wave_fronts.parse_parameters(prm);
      verification.parse_parameters(prm);
      // The window quantities are measured up to the end of the run: a
      // window past Time/End time would be found out only after the whole
      // run, as a failed check on a truncated (or empty) window. The energy
      // check does not use the window.
      const auto &v = verification;
      if (v.check_deceleration || v.check_plateau_strain ||
          v.check_longitudinal_speed || v.check_transverse_speed)
        {
          std::ostringstream s;
          s << "= " << v.window_end
            << " s is after Time/End time = " << shared.time.end_time
            << " s: the checks of Verification/Checks measure in the window, "
               "which must end by the end of the run";
          require(v.window_end <= shared.time.end_time * (1. + 1e-12),
                  "Verification/Window end",
                  s.str());
        }
    }
  } // namespace Analysis
} // namespace YarnImpact
