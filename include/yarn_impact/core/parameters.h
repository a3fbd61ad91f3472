#ifndef yarn_impact_core_parameters_h
#define yarn_impact_core_parameters_h

#include <iosfwd>
#include <string>

namespace dealii
{
  class ParameterHandler;
}

namespace YarnImpact
{
  /**
   * Parameters shared by every model: the yarn, the projectile, symmetry,
   * time integration and output (what is measured on a run is declared by
   * analysis/parameters.h, each model's own by its folder). One struct per
   * `.prm` subsection, in the manner of step-44. Every quantity is in SI units.
   */
  namespace Parameters
  {
    /** Symmetry used to reduce the modelled domain (doc/fe-model.md and
     * doc/dem.md, section 1). */
    enum class Symmetry
    {
      none,    ///< the whole yarn
      half,    ///< x >= 0, symmetry plane x = 0
      quarter, ///< x >= 0 and z >= 0, planes x = 0 and z = 0
    };

    /** Number of copies of the modelled part that make the whole yarn. */
    unsigned int
    symmetry_factor(const Symmetry symmetry);

    /** Top-level entries (no subsection). */
    struct General
    {
      /** Symmetry of the modelled domain. */
      Symmetry symmetry = Symmetry::half;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };

    /** The yarn: geometry and fibre data (subsection `Yarn`). */
    struct Yarn
    {
      /** Free length between the clamps [m]. */
      double length = 25.4e-3;
      /** Semi-axis of the elliptical section through the thickness, along y
       * [m]. */
      double thickness_semi_axis = 0.0575e-3;
      /** Semi-axis of the elliptical section across the width, along z [m].
       */
      double width_semi_axis = 0.267e-3;
      /** Number of fibres in the yarn [-]. */
      unsigned int n_fibres = 400;
      /** Fibre diameter [m]. */
      double fibre_diameter = 12e-6;
      /** Fibre density [kg/m^3]. */
      double fibre_density = 1440.;
      /** Fibre Young modulus along its axis [Pa]. */
      double fibre_modulus = 84.62e9;
      /** Longitudinal failure strain of fibres and yarn [-]. */
      double failure_strain = 0.0452;
      /** Whether failure (broken trusses, failed cells) is modelled. */
      bool failure = true;
      /** Area of the elliptical section, \f$\pi a_y a_z\f$ [m^2]. */
      double
      section_area() const;
      /** Total area of the fibres, \f$N \pi d^2/4\f$ [m^2]. */
      double
      fibre_area() const;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };

    /** How the projectile moves. */
    enum class ProjectileMotion
    {
      free,                ///< the paper: rigid body decelerated by the yarn
      prescribed_velocity, ///< constant velocity (Smith-theory verification)
    };

    /** The projectile's shape (`Projectile/Shape`). */
    enum class ProjectileShape
    {
      cylinder, ///< the paper's: its axis along z, across the yarn
      sphere,   ///< centred on x = z = 0 (Model = fabric only)
      /** A right circular cylinder, its axis along y, striking with its
       * flat face (the fragment simulant; Model = fabric only). */
      flat_cylinder,
    };

    /** The rigid projectile (subsection `Projectile`). */
    struct Projectile
    {
      /** Mass of the projectile [kg]. */
      double mass = 9.91e-6;
      /** Diameter of the cylinder or the sphere [m]. */
      double diameter = 2.2e-3;
      /** Cylinder along z, sphere or flat-faced cylinder. */
      ProjectileShape shape = ProjectileShape::cylinder;
      /** Where the projectile strikes: the x [m] of its axis or centre,
       * and the z [m] of the centre of the sphere or the flat cylinder's
       * axis (Model = fabric only where not 0). */
      double offset_x = 0., offset_z = 0.;
      /** Impact speed, towards -y [m/s]. */
      double initial_velocity = 120.;
      /** Free flight or prescribed constant velocity. */
      ProjectileMotion motion = ProjectileMotion::free;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };

    /** Explicit time integration (subsection `Time`). */
    struct Time
    {
      /** Simulated time at which the run stops [s]. */
      double end_time = 40e-6;
      /** Fraction of the critical time step used [-]. */
      double safety_factor = 0.8;
      /** The stable step is recomputed every this many steps [-]. */
      unsigned int time_step_update_interval = 10;
      /** A run stops when the energy balance error exceeds this fraction of
       * the initial energy [-]. */
      double energy_error_limit = 0.05;
      /** Whether the run stops when the yarn is cut through. */
      bool stop_at_cut_through = false;
      /** With stop_at_cut_through, how long the run goes on after the cut
       * [s]. */
      double time_after_cut_through = 0.;
      /** Largest number of time steps a run may take [-]. */
      unsigned long max_steps = 10000000;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };

    /** What the screen shows. */
    enum class Verbosity
    {
      normal, ///< set-up, progress line with ETA, timing summary
      quiet,  ///< set-up and summary only
      test,   ///< deterministic scaled summary only (regression tests)
      /** As test, but the screen shows only the summary's titles and check
       * lines (verdicts with their tolerance and reference, no measured
       * number); the whole summary goes to summary.txt (physics tests,
       * whose records compare summary.txt). */
      checks,
    };

    /** Whether @p v prints the deterministic, scaled summary (test and
     * checks): nothing that depends on the machine, the clock or the
     * number of ranks. */
    bool
    deterministic(Verbosity v);

    /**
     * Write the summary @p text of a run to @p out as verbosity @p v shows
     * it: whole, or with Verbosity::checks only its titles (the lines that
     * are not indented) and its check lines (those that begin with
     * "  check ").
     */
    void
    print_summary_text(const std::string &text, Verbosity v, std::ostream &out);

    /** Output (subsection `Output`). */
    struct Output
    {
      /** Directory that receives all output; created if missing. */
      std::string directory = "results";
      /**
       * Whether a run may replace the output of an earlier run in
       * #directory (its files of the kinds a run writes are removed
       * first); without it such a directory is refused.
       */
      bool overwrite = false;
      /** Simulated time between VTU snapshots [s]; 0 disables them. */
      double snapshot_interval = 1e-6;
      /** Simulated time between history rows [s]. */
      double history_interval = 0.1e-6;
      /** Wall-clock time between progress lines [s]. */
      double progress_interval = 2.;
      /** Simulated time between checkpoints [s]; 0: none (a signal still
       * writes one). */
      double checkpoint_interval = 0.;
      /** Wall-clock time between checkpoints [s]; 0: none. */
      double checkpoint_wall_interval = 0.;
      /** Screen verbosity. */
      Verbosity verbosity = Verbosity::normal;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };

    /** All shared parameters. */
    struct Shared
    {
      General general;
      Yarn yarn;
      Projectile projectile;
      Time time;
      Output output;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };
  } // namespace Parameters
} // namespace YarnImpact

#endif
