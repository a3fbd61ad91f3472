#ifndef yarn_impact_analysis_wave_fronts_h
#define yarn_impact_analysis_wave_fronts_h

#include <yarn_impact/analysis/parameters.h>
#include <yarn_impact/core/observables.h>

namespace YarnImpact
{
  namespace Analysis
  {
    /**
     * Measure the fronts on @p profile (a model's, ImpactModel::
     * observables()) with the thresholds of @p thresholds, the same way
     * for every model. A front that has not started yet is at 0.
     */
    WaveFrontPositions
    measure_wave_fronts(const StationProfile &profile,
                        const WaveFrontThresholds &thresholds);
  } // namespace Analysis
} // namespace YarnImpact

#endif
