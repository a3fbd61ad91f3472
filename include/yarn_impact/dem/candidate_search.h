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
     * The filter of the candidate search of a neighbour-list build (doc/dem.md
     * section 4): appends to @p out the entries k of the @p n_runs @p runs
     * whose single-precision position (@p cx, @p cy, @p cz)[k] lies closer
     * than sqrt(@p r2) to (@p x, @p y, @p z) [m, m^2; all relative to the
     * build's origin], in the order of the runs, and returns the new end of
     * @p out. The caller enlarges the radius by the rounding bound and tests
     * the survivors in double precision, so the lists do not depend on the
     * CPU. Up to 7 entries past every run are read; @p out needs room for
     * all the candidates of the runs.
     *
     * Runs the AVX2 variant where the CPU has AVX2 and FMA (chosen once, at
     * run time), near_in_runs_generic() otherwise.
     */
    std::uint32_t *
    near_in_runs(const float *cx,
                 const float *cy,
                 const float *cz,
                 const CandidateRun *runs,
                 unsigned int n_runs,
                 float x,
                 float y,
                 float z,
                 float r2,
                 std::uint32_t *out);

    /** The portable variant of near_in_runs() (one candidate at a time). */
    std::uint32_t *
    near_in_runs_generic(const float *cx,
                         const float *cy,
                         const float *cz,
                         const CandidateRun *runs,
                         unsigned int n_runs,
                         float x,
                         float y,
                         float z,
                         float r2,
                         std::uint32_t *out);

    /**
     * The AVX2 variant of near_in_runs() (eight candidates per
     * instruction), or nullptr where it is not compiled in or the CPU lacks
     * AVX2 or FMA.
     */
    using NearInRuns = std::uint32_t *(*)(const float *,
                                          const float *,
                                          const float *,
                                          const CandidateRun *,
                                          unsigned int,
                                          float,
                                          float,
                                          float,
                                          float,
                                          std::uint32_t *);
    NearInRuns
    near_in_runs_vectorised();
  } // namespace DEM
} // namespace YarnImpact

#endif
