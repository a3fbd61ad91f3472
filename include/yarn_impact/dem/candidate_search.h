#ifndef yarn_impact_dem_candidate_search_h
#define yarn_impact_dem_candidate_search_h

#include <cstdint>

namespace YarnImpact
{
  namespace DEM
  {
    /**
     * A run [k0, k1) of consecutive entries of the cell-ordered positions
     * of a neighbour-list build (the cells of one row of a 3 x 3 block).
     */
    struct CandidateRun
    {
      std::uint32_t k0, k1;
    };

    /**
     * The filter of the candidate search of a neighbour-list build
     * (doc/dem.md section 4): appends to @p out the entries k of the
     * @p n_runs @p runs whose single-precision position (@p cx, @p cy,
     * @p cz)[k] lies closer than sqrt(@p r2) to (@p x, @p y, @p z) [m, m^2;
     * all relative to the build's origin], in the order of the runs, and
     * returns the new end of @p out. The caller takes @p r2 from
     * filter_radius2() and tests the survivors in double precision, so the
     * lists do not depend on the CPU. Up to 7 entries past every run are
     * read; @p out needs room for all the candidates of the runs.
     */
    using NearInRunsFunction = std::uint32_t *(const float *cx,
                                               const float *cy,
                                               const float *cz,
                                               const CandidateRun *runs,
                                               unsigned int n_runs,
                                               float x,
                                               float y,
                                               float z,
                                               float r2,
                                               std::uint32_t *out);
    /** A filter (see NearInRunsFunction). */
    using NearInRuns = NearInRunsFunction *;

    /** The portable filter (one candidate at a time). */
    NearInRunsFunction near_in_runs_generic;

    /**
     * The AVX2 filter (eight candidates per instruction), or nullptr where
     * it is not compiled in or the CPU lacks AVX2 or FMA.
     */
    NearInRuns
    near_in_runs_vectorised();

    /** The filter this CPU runs: the AVX2 one if it has it (chosen once, at
     * run time), near_in_runs_generic() otherwise. */
    NearInRuns
    near_in_runs_for_this_cpu();

    /**
     * Squared radius [m^2] of the single-precision filter for a search
     * radius @p cutoff [m] among coordinates of magnitude at most
     * @p magnitude [m]: enlarged so that no pair closer than @p cutoff is
     * lost to rounding. Each coordinate and the query point are off by at
     * most 2^-24 of the magnitude M, a distance by sqrt(3) 2^-23 M plus the
     * rounding of the differences; 4e-7 (M + cut-off) is twice that.
     */
    inline float
    filter_radius2(const double cutoff, const double magnitude)
    {
      const double r = cutoff + 4e-7 * (magnitude + cutoff);
      return static_cast<float>(r * r * (1. + 1e-6));
    }
  } // namespace DEM
} // namespace YarnImpact

#endif
