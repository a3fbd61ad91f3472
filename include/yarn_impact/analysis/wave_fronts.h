#ifndef yarn_impact_analysis_wave_fronts_h
#define yarn_impact_analysis_wave_fronts_h

#include <yarn_impact/core/parameters.h>

#include <vector>

namespace YarnImpact
{
  namespace Analysis
  {
    /**
     * The yarn seen station by station along its axis, the same way in both
     * models: a station is an FE node layer or a DEM cross-section of
     * spheres. Stations are ordered by increasing distance from the impact
     * point and cover one side of the yarn (x >= 0); values of the side
     * x < 0, when modelled, are folded onto it by taking the larger one.
     */
    struct StationProfile
    {
      /** Current (laboratory-frame) distance |x| of the station from the
       * impact plane [m]. */
      std::vector<double> position;
      /** Longitudinal (fibre) strain, \f$\lambda_f - 1\f$, averaged over the
       * section at the station (area-weighted, so that it is the yarn's
       * tension over its axial stiffness) [-]. */
      std::vector<double> axial_strain;
      /** Deflection in the impact direction, \f$-u_y\f$, the largest over
       * the station [m]. */
      std::vector<double> deflection;
      /** Current width of the section (extent along z) [m]. */
      std::vector<double> width;
      /** Width of the section at t = 0 [m]. */
      std::vector<double> initial_width;
      /** Second-moment width of the section, \f$4\sqrt{\langle z^2
       * \rangle}\f$ about the plane z = 0, area-weighted (FE: lumped nodal
       * masses; DEM: one weight per fibre centre). It is the full width
       * 2 a_z of a uniformly filled ellipse, and means the same in both
       * models (doc/identification.md section 2.4) [m]. */
      std::vector<double> rms_width;

      /** Resize all arrays to @p n stations, filled with zeros. */
      void
      resize(const unsigned int n);

      /** Number of stations. */
      unsigned int
      size() const
      {
        return position.size();
      }
    };

    /** Wave fronts and section data measured on a StationProfile. */
    struct WaveFrontPositions
    {
      /** Longitudinal (strain) front: outermost station with axial strain
       * above the strain threshold [m]. */
      double longitudinal = 0.;
      /** Transverse front: outermost station deflected by more than the
       * deflection threshold [m]. */
      double transverse = 0.;
      /** Spreading front: outermost station whose width grew by more than
       * the spreading threshold [m]. */
      double spreading = 0.;
      /** Section width at the impact point (first station) [m]. */
      double width_at_impact = 0.;
      /** Second-moment width at the impact point (first station) [m]. */
      double rms_width_at_impact = 0.;
      /** Mean axial strain in the middle half of the region between the
       * transverse and the longitudinal fronts: Smith's strain behind the
       * longitudinal front [-]. */
      double plateau_strain = 0.;
    };

    /**
     * Measure the fronts on @p profile with the thresholds of @p thresholds.
     * A front that has not started yet is at 0.
     */
    WaveFrontPositions
    measure_wave_fronts(const StationProfile &profile,
                        const Parameters::WaveFronts &thresholds);
  } // namespace Analysis
} // namespace YarnImpact

#endif
