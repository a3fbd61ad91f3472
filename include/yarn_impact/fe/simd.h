#ifndef yarn_impact_fe_simd_h
#define yarn_impact_fe_simd_h

#include <cmath>

namespace YarnImpact
{
  namespace FE
  {
    // The lane functions pass Double4 by value; they are inline, so the
    // ABI note of GCC about AVX vectors does not apply.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
    namespace internal
    {
      /**
       * Four doubles in one SIMD register (GCC vector extension): the FE
       * force loop evaluates a law at four Gauss points at once. On CPUs
       * without AVX the compiler splits it into two SSE2 halves.
       */
      typedef double Double4 __attribute__((vector_size(32)));

      /** Number of lanes of a Double4. */
      constexpr unsigned int n_lanes = 4;

      // Lane-wise functions, for double and Double4 alike, so that one
      // templated law body serves the scalar and the vector path.

      /** ln x. */
      inline double
      lane_log(const double x)
      {
        return std::log(x);
      }
      /** sqrt x. */
      inline double
      lane_sqrt(const double x)
      {
        return std::sqrt(x);
      }
      /** |x|. */
      inline double
      lane_abs(const double x)
      {
        return std::abs(x);
      }
      /** x^e for x > 0, 0 for x = 0; exp(e ln x) costs less than glibc's
       * pow and is accurate to a few ulp here. */
      inline double
      lane_pow(const double x, const double e)
      {
        return x > 0. ? std::exp(e * std::log(x)) : 0.;
      }
      /** 1 for x >= 0, -1 otherwise. */
      inline double
      lane_sign(const double x)
      {
        return x >= 0. ? 1. : -1.;
      }
      /** asinh(s)/s: its Taylor series in s^2 up to s^16 is exact to
       * round-off for s < 0.1 (the usual range) and needs no division. */
      inline double
      lane_asinh_ratio(const double s, const double s2)
      {
        if (s >= 0.1)
          return std::asinh(s) / s;
        return 1. +
               s2 *
                 (-1. / 6. +
                  s2 *
                    (3. / 40. +
                     s2 * (-5. / 112. +
                           s2 * (35. / 1152. +
                                 s2 * (-63. / 2816. +
                                       s2 * (231. / 13312. +
                                             s2 * (-143. / 10240. +
                                                   s2 * 6435. / 557056.)))))));
      }

#define YARN_IMPACT_LANEWISE(name, expression) \
  inline Double4 name(const Double4 x)         \
  {                                            \
    Double4 r;                                 \
    for (unsigned int l = 0; l < 4; ++l)       \
      r[l] = expression;                       \
    return r;                                  \
  }
      YARN_IMPACT_LANEWISE(lane_log, std::log(x[l]))
      YARN_IMPACT_LANEWISE(lane_sqrt, std::sqrt(x[l]))
      YARN_IMPACT_LANEWISE(lane_abs, std::abs(x[l]))
      YARN_IMPACT_LANEWISE(lane_sign, x[l] >= 0. ? 1. : -1.)
#undef YARN_IMPACT_LANEWISE
      /** lane_pow() lane by lane. */
      inline Double4
      lane_pow(const Double4 x, const double e)
      {
        Double4 r;
        for (unsigned int l = 0; l < 4; ++l)
          r[l] = lane_pow(x[l], e);
        return r;
      }
      /** lane_asinh_ratio() lane by lane. */
      inline Double4
      lane_asinh_ratio(const Double4 s, const Double4 s2)
      {
        Double4 r;
        for (unsigned int l = 0; l < 4; ++l)
          r[l] = lane_asinh_ratio(s[l], s2[l]);
        return r;
      }
    } // namespace internal
#pragma GCC diagnostic pop
  } // namespace FE
} // namespace YarnImpact

#endif
