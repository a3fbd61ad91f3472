#include <yarn_impact/analysis/wave_fronts.h>

#include <algorithm>

namespace YarnImpact
{
  namespace Analysis
  {
    WaveFrontPositions
    measure_wave_fronts(const StationProfile &profile,
                        const WaveFrontThresholds &thresholds)
    {
      WaveFrontPositions fronts;
      const unsigned int n = profile.size();
      if (n == 0)
        return fronts;

      fronts.width_at_impact     = profile.width[0];
      fronts.rms_width_at_impact = profile.rms_width[0];
      for (unsigned int i = 0; i < n; ++i)
        {
          const double x = profile.position[i];
          if (profile.axial_strain[i] > thresholds.strain_threshold)
            fronts.longitudinal = std::max(fronts.longitudinal, x);
          if (profile.deflection[i] > thresholds.deflection_threshold)
            fronts.transverse = std::max(fronts.transverse, x);
          if (profile.width[i] >
              (1. + thresholds.spreading_threshold) * profile.initial_width[i])
            fronts.spreading = std::max(fronts.spreading, x);
        }

      // Smith's plateau: the middle half between the two fronts, away from
      // the kink at the transverse front and from the longitudinal fan.
      const double lo =
        fronts.transverse + 0.25 * (fronts.longitudinal - fronts.transverse);
      const double hi =
        fronts.transverse + 0.75 * (fronts.longitudinal - fronts.transverse);
      double sum         = 0.;
      unsigned int count = 0;
      for (unsigned int i = 0; i < n; ++i)
        if (profile.position[i] >= lo && profile.position[i] <= hi)
          {
            sum += profile.axial_strain[i];
            ++count;
          }
      fronts.plateau_strain = (count > 0 ? sum / count : 0.);
      return fronts;
    }
  } // namespace Analysis
} // namespace YarnImpact
