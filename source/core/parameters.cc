#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/core/parameters.h>

#include <deal.II/base/numbers.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <cmath>
#include <ostream>
#include <sstream>

namespace YarnImpact
{
  namespace Parameters
  {
    using namespace dealii;

    unsigned int
    symmetry_factor(const Symmetry symmetry)
    {
      switch (symmetry)
        {
          case Symmetry::none:
            return 1;
          case Symmetry::half:
            return 2;
          case Symmetry::quarter:
            return 4;
        }
      return 1;
    }


    void
    General::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry(
        "Symmetry",
        "half",
        Patterns::Selection("none|half|quarter"),
        "Part of the yarn that is modelled: the whole yarn (none), x >= 0 with "
        "the symmetry plane x = 0 (half), or x >= 0, z >= 0 with the planes "
        "x = 0 and z = 0 (quarter); with Model = fabric the patch's part "
        "x <= 0 (half) or x <= 0, z >= 0 (quarter), the planes on the "
        "middle yarns' centrelines (doc/fabric.md section 10). Reported "
        "masses, forces and energies are always those of the whole yarn "
        "or patch.");
    }

    void
    General::parse_parameters(ParameterHandler &prm)
    {
      const std::string s = prm.get("Symmetry");
      symmetry            = (s == "none"   ? Symmetry::none
                             : s == "half" ? Symmetry::half
                                           : Symmetry::quarter);
    }


    double
    Yarn::section_area() const
    {
      return numbers::PI * thickness_semi_axis * width_semi_axis;
    }

    double
    Yarn::fibre_area() const
    {
      return n_fibres * numbers::PI * fibre_diameter * fibre_diameter / 4.;
    }

    void
    Yarn::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Yarn");
      prm.declare_entry("Length",
                        "0.0254",
                        Patterns::Double(),
                        "Free length of the yarn between the two clamps [m].");
      prm.declare_entry("Thickness semi-axis",
                        "0.0575e-3",
                        Patterns::Double(),
                        "Semi-axis of the elliptical cross-section through "
                        "the yarn's thickness, along y, the impact direction "
                        "[m].");
      prm.declare_entry("Width semi-axis",
                        "0.267e-3",
                        Patterns::Double(),
                        "Semi-axis of the elliptical cross-section across the "
                        "yarn's width, along z, the projectile's axis [m].");
      prm.declare_entry("Number of fibres",
                        "400",
                        Patterns::Integer(),
                        "Number of fibres in the yarn [-].");
      prm.declare_entry("Fibre diameter",
                        "12e-6",
                        Patterns::Double(),
                        "Diameter of one fibre [m].");
      prm.declare_entry("Fibre density",
                        "1440",
                        Patterns::Double(),
                        "Density of the fibre material [kg/m^3].");
      prm.declare_entry("Fibre Young modulus",
                        "84.62e9",
                        Patterns::Double(),
                        "Young modulus of a fibre along its axis [Pa].");
      prm.declare_entry("Failure strain",
                        "0.0452",
                        Patterns::Double(),
                        "Longitudinal strain at which a fibre (DEM truss) or "
                        "the yarn (FE cell) fails [-].");
      prm.declare_entry("Failure",
                        "true",
                        Patterns::Bool(),
                        "Whether failure at the failure strain is modelled; "
                        "when false the yarn never breaks.");
      prm.leave_subsection();
    }

    void
    Yarn::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Yarn");
      length = get_positive_double(prm, "Yarn", "Length");
      thickness_semi_axis =
        get_positive_double(prm, "Yarn", "Thickness semi-axis");
      width_semi_axis = get_positive_double(prm, "Yarn", "Width semi-axis");
      n_fibres        = get_positive_integer(prm, "Yarn", "Number of fibres");
      fibre_diameter  = get_positive_double(prm, "Yarn", "Fibre diameter");
      fibre_density   = get_positive_double(prm, "Yarn", "Fibre density");
      fibre_modulus   = get_positive_double(prm, "Yarn", "Fibre Young modulus");
      failure_strain  = get_positive_double(prm, "Yarn", "Failure strain");
      failure         = prm.get_bool("Failure");
      prm.leave_subsection();
    }


    void
    Projectile::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Projectile");
      prm.declare_entry("Mass",
                        "9.91e-6",
                        Patterns::Double(),
                        "Mass of the rigid projectile [kg].");
      prm.declare_entry("Diameter",
                        "2.2e-3",
                        Patterns::Double(),
                        "Diameter of the projectile (Shape); the cylinder's "
                        "axis is z, across the yarn's width [m].");
      prm.declare_entry(
        "Initial velocity",
        "120",
        Patterns::Double(),
        "Impact speed; the projectile starts touching the top of the "
        "yarn at mid-span and moves towards -y [m/s].");
      prm.declare_entry(
        "Motion",
        "free",
        Patterns::Selection("free|prescribed velocity"),
        "free: a rigid body decelerated by the yarn (the paper); prescribed "
        "velocity: the projectile keeps its initial velocity (Smith-theory "
        "verification); the work done on the yarn is then counted in the "
        "energy balance.");
      prm.declare_entry(
        "Shape",
        "cylinder",
        Patterns::Selection("cylinder|sphere|flat cylinder"),
        "cylinder: its axis along z, across the yarn (the paper); sphere: "
        "centred above the impact point; flat cylinder: a right circular "
        "cylinder of the Diameter, its axis along y, striking with its "
        "flat face, the fragment simulant (sphere and flat cylinder: Model "
        "= fabric only).");
      prm.declare_entry("Impact offset x",
                        "0",
                        Patterns::Double(),
                        "x of the impact point: of the cylinder's axis, the "
                        "sphere's centre, the flat cylinder's axis (Model = "
                        "fabric only where not 0) [m].");
      prm.declare_entry("Impact offset z",
                        "0",
                        Patterns::Double(),
                        "z of the impact point: of the sphere's centre or "
                        "the flat cylinder's axis (Model = fabric only "
                        "where not 0; the cylinder along z has none) [m].");
      prm.leave_subsection();
    }

    void
    Projectile::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Projectile");
      mass     = get_positive_double(prm, "Projectile", "Mass");
      diameter = get_positive_double(prm, "Projectile", "Diameter");
      initial_velocity =
        get_positive_double(prm, "Projectile", "Initial velocity");
      motion =
        (prm.get("Motion") == "free" ? ProjectileMotion::free
                                     : ProjectileMotion::prescribed_velocity);
      const std::string s = prm.get("Shape");
      shape               = (s == "sphere"          ? ProjectileShape::sphere
                             : s == "flat cylinder" ? ProjectileShape::flat_cylinder
                                                    : ProjectileShape::cylinder);
      offset_x            = prm.get_double("Impact offset x");
      offset_z            = prm.get_double("Impact offset z");
      prm.leave_subsection();
    }


    void
    Time::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Time");
      prm.declare_entry("End time",
                        "40e-6",
                        Patterns::Double(),
                        "Simulated time at which the run stops [s].");
      prm.declare_entry("Safety factor",
                        "0.8",
                        Patterns::Double(),
                        "Fraction of the critical explicit time step used, "
                        "in (0, 1] [-].");
      prm.declare_entry("Time step update interval",
                        "10",
                        Patterns::Integer(),
                        "The stable time step is recomputed from the current "
                        "configuration every this many steps [-].");
      prm.declare_entry(
        "Energy error limit",
        "0.05",
        Patterns::Double(),
        "The run stops with an error when the energy balance error exceeds "
        "this fraction of the initial energy (a numerical blow-up) [-].");
      prm.declare_entry(
        "Stop when cut through",
        "false",
        Patterns::Bool(),
        "Whether the run stops as soon as the yarn is cut through (a whole "
        "section failed); otherwise it goes on to End time with the "
        "projectile flying through, and the cut time is reported.");
      prm.declare_entry(
        "Maximum number of steps",
        "10000000",
        Patterns::Integer(1),
        "A run whose stable time step would need more steps than this to "
        "reach End time is refused at set-up, and a run stops with an error "
        "if it gets there: a modulus, density or penalty with wrong units, "
        "or an impact velocity no explicit model can follow [-].");
      prm.declare_entry(
        "Time after cut through",
        "0",
        Patterns::Double(0.),
        "With 'Stop when cut through', the run goes on for this long after "
        "the cut, so that the fragments leave the projectile and its "
        "residual velocity settles [s].");
      prm.leave_subsection();
    }

    void
    Time::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Time");
      end_time      = get_positive_double(prm, "Time", "End time");
      safety_factor = get_positive_double(prm, "Time", "Safety factor");
      require(safety_factor <= 1.,
              "Time/Safety factor",
              "must not exceed 1: a larger step than the critical one is "
              "unstable");
      time_step_update_interval =
        get_positive_integer(prm, "Time", "Time step update interval");
      energy_error_limit =
        get_positive_double(prm, "Time", "Energy error limit");
      stop_at_cut_through    = prm.get_bool("Stop when cut through");
      time_after_cut_through = prm.get_double("Time after cut through");
      max_steps              = prm.get_integer("Maximum number of steps");
      prm.leave_subsection();
    }


    void
    Output::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      prm.declare_entry("Directory",
                        "results",
                        Patterns::Anything(),
                        "Directory that receives parameters.prm, the history "
                        "CSV, the VTU snapshots and the summary; created if "
                        "missing. A directory that holds the output of an "
                        "earlier run (parameters.prm, summary.txt, history, "
                        "snapshots, comparison or elementary-test files) is "
                        "refused unless Overwrite is true.");
      prm.declare_entry("Overwrite",
                        "false",
                        Patterns::Bool(),
                        "true: before the run, remove the files of an earlier "
                        "run from Directory (only the kinds of files a run "
                        "writes, never others) instead of refusing it.");
      prm.declare_entry("Snapshot interval",
                        "1e-6",
                        Patterns::Double(),
                        "Simulated time between two VTU snapshots; 0 writes "
                        "none [s].");
      prm.declare_entry("History interval",
                        "0.1e-6",
                        Patterns::Double(),
                        "Simulated time between two rows of the history CSV "
                        "[s].");
      prm.declare_entry(
        "Checkpoint interval",
        "0",
        Patterns::Double(),
        "Simulated time between two checkpoints, written at the first "
        "history row after each multiple of it; 0 writes none (a SIGTERM or "
        "SIGINT still writes one before the run stops). A run continues from "
        "its last checkpoint with yarn-impact --restart FILE.prm [s].");
      prm.declare_entry(
        "Checkpoint wall-clock interval",
        "0",
        Patterns::Double(),
        "Wall-clock time between two checkpoints (at the first history row "
        "after it); 0 writes none [s].");
      prm.declare_entry("Progress interval",
                        "2",
                        Patterns::Double(),
                        "Wall-clock time between two progress lines [s].");
      prm.declare_entry(
        "Verbosity",
        "normal",
        Patterns::Selection("normal|quiet|test|checks"),
        "normal: set-up, progress lines with ETA and a timing summary; "
        "quiet: set-up and summary; test: the deterministic, scaled summary "
        "only; checks: as test, but only the summary's titles and check "
        "lines on the screen, the whole summary in summary.txt (used by the "
        "tests).");
      prm.leave_subsection();
    }

    void
    Output::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      directory = prm.get("Directory");
      require(!directory.empty(), "Output/Directory", "must not be empty");
      overwrite         = prm.get_bool("Overwrite");
      snapshot_interval = prm.get_double("Snapshot interval");
      require(snapshot_interval >= 0.,
              "Output/Snapshot interval",
              "must not be negative");
      history_interval = get_positive_double(prm, "Output", "History interval");
      progress_interval =
        get_positive_double(prm, "Output", "Progress interval");
      checkpoint_interval = prm.get_double("Checkpoint interval");
      require(checkpoint_interval >= 0.,
              "Output/Checkpoint interval",
              "must not be negative");
      checkpoint_wall_interval =
        prm.get_double("Checkpoint wall-clock interval");
      require(checkpoint_wall_interval >= 0.,
              "Output/Checkpoint wall-clock interval",
              "must not be negative");
      const std::string v = prm.get("Verbosity");
      verbosity           = (v == "normal"  ? Verbosity::normal
                             : v == "quiet" ? Verbosity::quiet
                             : v == "test"  ? Verbosity::test
                                            : Verbosity::checks);
      prm.leave_subsection();
    }


    bool
    deterministic(const Verbosity v)
    {
      return v == Verbosity::test || v == Verbosity::checks;
    }


    void
    print_summary_text(const std::string &text,
                       const Verbosity v,
                       std::ostream &out)
    {
      if (v != Verbosity::checks)
        {
          out << text;
          return;
        }
      std::istringstream in(text);
      for (std::string line; std::getline(in, line);)
        if ((!line.empty() && line[0] != ' ') ||
            line.compare(0, 8, "  check ") == 0)
          out << line << '\n';
    }


    void
    Shared::declare_parameters(ParameterHandler &prm)
    {
      General::declare_parameters(prm);
      Yarn::declare_parameters(prm);
      Projectile::declare_parameters(prm);
      Time::declare_parameters(prm);
      Output::declare_parameters(prm);
    }

    void
    Shared::parse_parameters(ParameterHandler &prm)
    {
      general.parse_parameters(prm);
      yarn.parse_parameters(prm);
      projectile.parse_parameters(prm);
      time.parse_parameters(prm);
      output.parse_parameters(prm);

      require(yarn.width_semi_axis >= yarn.thickness_semi_axis,
              "Yarn/Width semi-axis",
              "must not be smaller than Yarn/Thickness semi-axis (the "
              "projectile hits the flat side of the yarn)");
      require(projectile.diameter < yarn.length,
              "Projectile/Diameter",
              "must be smaller than Yarn/Length");
    }
  } // namespace Parameters
} // namespace YarnImpact
