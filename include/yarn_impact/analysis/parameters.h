#ifndef yarn_impact_analysis_parameters_h
#define yarn_impact_analysis_parameters_h

#include <yarn_impact/core/parameters.h>

namespace dealii
{
  class ParameterHandler;
}

namespace YarnImpact
{
  namespace Analysis
  {
    /**
     * Thresholds that define the wave fronts, identical for every model
     * (subsection `Wave fronts`, see analysis/wave_fronts.h).
     */
    struct WaveFrontThresholds
    {
      /** Longitudinal front: outermost station whose axial strain exceeds
       * this value [-]. */
      double strain_threshold = 2e-4;
      /** Transverse front: outermost station whose deflection (towards -y)
       * exceeds this value [m]. */
      double deflection_threshold = 10e-6;
      /** Spreading front: outermost station whose section width exceeds the
       * initial width by this fraction [-]. */
      double spreading_threshold = 0.02;

      /** Declare the entries of the subsection. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);
      /** Parse them; throws InputError naming a bad entry. */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };

    /**
     * Time window in which the run is compared with Smith theory (subsection
     * `Verification`): before the first reflected longitudinal wave returns
     * to the impact point the yarn behaves as an infinite one.
     */
    struct Verification
    {
      /** Start of the window [s]. */
      double window_start = 1e-6;
      /** End of the window [s]. */
      double window_end = 3e-6;
      /** Checks to assert at the end of the run; a failed check makes the
       * run exit with a non-zero code. */
      bool check_deceleration       = false;
      bool check_plateau_strain     = false;
      bool check_longitudinal_speed = false;
      bool check_transverse_speed   = false;
      bool check_energy             = false;
      /** Relative tolerance of the Smith-theory checks [-]. */
      double tolerance = 0.03;
      /** Largest energy error allowed by the energy check, as a fraction of
       * the initial energy [-]. */
      double energy_tolerance = 0.005;

      /** Declare the entries of the subsection. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);
      /** Parse them; throws InputError naming a bad entry. */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };

    /** What is measured on a run and what it is checked against: the
     * parameters that analysis/ declares, whatever the model. */
    struct Parameters
    {
      WaveFrontThresholds wave_fronts;
      Verification verification;

      /** Declare the subsections `Wave fronts` and `Verification`. */
      static void
      declare_parameters(dealii::ParameterHandler &prm);
      /** Parse them and check the window against the run's end time
       * (@p shared, already parsed); throws InputError. */
      void
      parse_parameters(dealii::ParameterHandler &prm,
                       const YarnImpact::Parameters::Shared &shared);
    };
  } // namespace Analysis
} // namespace YarnImpact

#endif
