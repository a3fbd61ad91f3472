// The filter of the DEM neighbour-list search: eight candidates per
// instruction where the CPU allows (doc/dem.md section 4).

#include <yarn_impact/dem/candidate_search.h>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#  define YARN_IMPACT_DEM_AVX2 1
#  include <immintrin.h>
#endif

namespace YarnImpact
{
  namespace DEM
  {
    std::uint32_t *
    near_in_runs_generic(const float *cx,
                         const float *cy,
                         const float *cz,
                         const CandidateRun *runs,
                         const unsigned int n_runs,
                         const float x,
                         const float y,
                         const float z,
                         const float r2,
                         std::uint32_t *out)
    {
      for (unsigned int r = 0; r < n_runs; ++r)
        for (std::uint32_t k = runs[r].k0; k < runs[r].k1; ++k)
          {
            const float ex = x - cx[k], ey = y - cy[k], ez = z - cz[k];
            *out = k;
            out += (ex * ex + ey * ey + ez * ez < r2);
          }
      return out;
    }


#ifdef YARN_IMPACT_DEM_AVX2
    namespace
    {
      // The search is about 70 % of a rebuild and most candidates fail the
      // test (a sphere has 30-50 candidates and about 6 partners). Compiled
      // for AVX2 and FMA and dispatched on the CPU's features like the FE
      // cell kernel.
      __attribute__((target("avx2,fma"))) std::uint32_t *
      near_in_runs_avx2(const float *cx,
                        const float *cy,
                        const float *cz,
                        const CandidateRun *runs,
                        const unsigned int n_runs,
                        const float x,
                        const float y,
                        const float z,
                        const float r2,
                        std::uint32_t *out)
      {
        const __m256 X = _mm256_set1_ps(x), Y = _mm256_set1_ps(y),
                     Z = _mm256_set1_ps(z), R = _mm256_set1_ps(r2);
        for (unsigned int r = 0; r < n_runs; ++r)
          for (std::uint32_t k = runs[r].k0; k < runs[r].k1; k += 8)
            {
              const __m256 ex = _mm256_sub_ps(X, _mm256_loadu_ps(cx + k));
              const __m256 ey = _mm256_sub_ps(Y, _mm256_loadu_ps(cy + k));
              const __m256 ez = _mm256_sub_ps(Z, _mm256_loadu_ps(cz + k));
              __m256 e2       = _mm256_mul_ps(ex, ex);
              e2              = _mm256_fmadd_ps(ey, ey, e2);
              e2              = _mm256_fmadd_ps(ez, ez, e2);
              unsigned int m  = static_cast<unsigned int>(
                _mm256_movemask_ps(_mm256_cmp_ps(e2, R, _CMP_LT_OQ)));
              const std::uint32_t left = runs[r].k1 - k;
              if (left < 8)
                m &= (1u << left) - 1u;
              while (m != 0)
                {
                  *out++ = k + static_cast<std::uint32_t>(__builtin_ctz(m));
                  m &= m - 1u;
                }
            }
        return out;
      }

      const NearInRuns vectorised =
        (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
          ? &near_in_runs_avx2
          : nullptr;
    } // namespace
#endif


    NearInRuns
    near_in_runs_vectorised()
    {
#ifdef YARN_IMPACT_DEM_AVX2
      return vectorised;
#else
      return nullptr;
#endif
    }


    NearInRuns
    near_in_runs_for_this_cpu()
    {
      const NearInRuns v = near_in_runs_vectorised();
      return v != nullptr ? v : &near_in_runs_generic;
    }
  } // namespace DEM
} // namespace YarnImpact
