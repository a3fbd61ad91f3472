#ifndef yarn_impact_fe_simd_h
#define yarn_impact_fe_simd_h

#include <cmath>
#include <cstdlib>
#include <cstring>

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
      /** The Taylor series of asinh(s)/s in s^2 up to s^16, for double
       * and Double4 alike: exact to round-off for s < 0.1 (the usual
       * range), and no division. */
      template <typename V>
      inline V
      asinh_ratio_series(const V s2)
      {
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

      /** asinh(s)/s: its series below s = 0.1 (asinh_ratio_series()). */
      inline double
      lane_asinh_ratio(const double s, const double s2)
      {
        if (s >= 0.1)
          return std::asinh(s) / s;
        return asinh_ratio_series(s2);
      }

#define YARN_IMPACT_LANEWISE(name, expression) \
  inline Double4 name(const Double4 x)         \
  {                                            \
    Double4 r;                                 \
    for (unsigned int l = 0; l < 4; ++l)       \
      r[l] = expression;                       \
    return r;                                  \
  }
      YARN_IMPACT_LANEWISE(log_by_lane, std::log(x[l]))
      YARN_IMPACT_LANEWISE(exp_by_lane, std::exp(x[l]))
      YARN_IMPACT_LANEWISE(lane_sqrt, std::sqrt(x[l]))
      YARN_IMPACT_LANEWISE(lane_abs, std::abs(x[l]))
      YARN_IMPACT_LANEWISE(lane_sign, x[l] >= 0. ? 1. : -1.)
#undef YARN_IMPACT_LANEWISE
      /** Four 64-bit integers, the bits of a Double4's lanes. */
      typedef long long Int4 __attribute__((vector_size(32)));

      /** The bits of @p x. */
      inline Int4
      bits_of(const Double4 x)
      {
        Int4 b;
        std::memcpy(&b, &x, sizeof(b));
        return b;
      }

      /** The Double4 whose bits are @p b. */
      inline Double4
      from_bits(const Int4 b)
      {
        Double4 x;
        std::memcpy(&x, &b, sizeof(x));
        return x;
      }

      /** Whether every lane of a comparison's result is true. */
      inline bool
      all_lanes(const Int4 mask)
      {
        return (mask[0] & mask[1] & mask[2] & mask[3]) != 0;
      }

      /** The integers @p k (|k| < 2^51) as doubles, exactly: the bits of
       * 1.5 2^52 + k less 1.5 2^52 (AVX2 has no 64-bit conversion). */
      inline Double4
      to_double(const Int4 k)
      {
        constexpr long long magic_bits = 0x4338000000000000LL;
        constexpr double magic         = 6755399441055744.; // 1.5 2^52
        return from_bits(k + magic_bits) - magic;
      }

      /**
       * ln x in all four lanes at once: fdlibm's algorithm (e_log.c,
       * Sun Microsystems 1993), x = 2^k (1 + f) with sqrt(2)/2 <= 1 + f <
       * sqrt(2), s = f / (2 + f), ln(1 + f) = f - (f^2/2 - s (f^2/2 +
       * R(s^2))), R a minimax polynomial of degree 14 in s; within 1 ulp
       * of the correctly rounded value (test unit/simd_functions). A lane
       * that is not a positive normal number (0, negative, subnormal,
       * infinite, NaN) sends the whole vector to std::log.
       */
      inline Double4
      vector_log(const Double4 x)
      {
        const Int4 bits     = bits_of(x);
        const Int4 exponent = bits >> 52; // sign included: < 0 if x < 0
        if (!all_lanes((exponent > 0) & (exponent < 2047)))
          return log_by_lane(x);
        constexpr long long mantissa_mask = 0x000FFFFFFFFFFFFFLL;
        constexpr long long one_bits      = 0x3FF0000000000000LL;
        constexpr long long sqrt2_bits    = 0x0006A09E667F3BCDLL;
        const Int4 mantissa               = bits & mantissa_mask;
        // Mantissas above sqrt(2) are halved (-1 in a comparison's lane).
        const Int4 above = mantissa > sqrt2_bits;
        const Double4 m =
          from_bits(mantissa | (one_bits + (above & -0x0010000000000000LL)));
        const Double4 k    = to_double(exponent - 1023 - above);
        const Double4 f    = m - 1.;
        const Double4 hfsq = 0.5 * f * f;
        const Double4 s    = f / (2. + f);
        const Double4 z    = s * s;
        const Double4 w    = z * z;
        const Double4 t1 =
          w * (3.999999999940941908e-01 +
               w * (2.222219843214978396e-01 + w * 1.531383769920937332e-01));
        const Double4 t2 =
          z *
          (6.666666666666735130e-01 +
           w * (2.857142874366239149e-01 +
                w * (1.818357216161805012e-01 + w * 1.479819860511658591e-01)));
        const Double4 R         = t2 + t1;
        constexpr double ln2_hi = 6.93147180369123816490e-01;
        constexpr double ln2_lo = 1.90821492927058770002e-10;
        return k * ln2_hi - ((hfsq - (s * (hfsq + R) + k * ln2_lo)) - f);
      }

      /**
       * e^y in all four lanes at once: fdlibm's algorithm (e_exp.c), y = k
       * ln 2 + r with |r| <= ln(2)/2, e^r from a rational approximation,
       * times 2^k; within 1 ulp (test unit/simd_functions). A lane outside
       * (-708, 709), where the result would not be a normal number, or a
       * NaN sends the whole vector to std::exp.
       */
      inline Double4
      vector_exp(const Double4 y)
      {
        const Int4 in_range = (y > -708.) & (y < 709.);
        if (!all_lanes(in_range))
          return exp_by_lane(y);
        constexpr double magic  = 6755399441055744.; // 1.5 2^52
        constexpr double ln2_hi = 6.93147180369123816490e-01;
        constexpr double ln2_lo = 1.90821492927058770002e-10;
        // k = y / ln 2 rounded to the nearest integer.
        const Double4 kd = (y * 1.44269504088896338700e+00 + magic) - magic;
        const Double4 hi = y - kd * ln2_hi;
        const Double4 lo = kd * ln2_lo;
        const Double4 r  = hi - lo;
        const Double4 t  = r * r;
        const Double4 c =
          r - t * (1.66666666666666019037e-01 +
                   t * (-2.77777777770155933842e-03 +
                        t * (6.61375632143793436117e-05 +
                             t * (-1.65339022054652515390e-06 +
                                  t * 4.13813679705723846039e-08))));
        const Double4 e_r = 1. - ((lo - (r * c) / (2. - c)) - hi);
        // Times 2^k: k added to the exponent's bits.
        const Int4 k = bits_of(kd + magic) - bits_of(Double4{} + magic);
        return from_bits(bits_of(e_r) + (k << 52));
      }

      /** x^e = exp(e ln x) in all four lanes at once by vector_log() and
       * vector_exp(); 0 where x = 0. */
      inline Double4
      vector_pow(const Double4 x, const double e)
      {
        const Int4 positive = x > 0.;
        // Zero lanes take x = 1 and are set to 0 after.
        const Double4 safe = positive ? x : Double4{} + 1.;
        const Double4 r    = vector_exp(e * vector_log(safe));
        return positive ? r : Double4{};
      }

      /**
       * Whether the lane functions below take the vector algorithms above:
       * where the CPU has AVX2 and FMA, the FE force loop runs its AVX2
       * variant (cell_kernel.cc dispatches on this flag too), and there
       * the 4-wide algorithms cost a third of four calls to glibc; the two
       * SSE2 halves of the portable variant make them slower than glibc
       * (doc/performance.md section 1), so there the lanes call glibc.
       * YARN_IMPACT_PORTABLE_KERNEL=1 sets it false.
       */
      inline const bool avx2_fma_kernel =
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
        __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
        std::getenv("YARN_IMPACT_PORTABLE_KERNEL") == nullptr;
#else
        false;
#endif

      /** ln x lane by lane: vector_log() in the AVX2 variant, glibc's
       * otherwise (avx2_fma_kernel). */
      inline Double4
      lane_log(const Double4 x)
      {
        return avx2_fma_kernel ? vector_log(x) : log_by_lane(x);
      }

      /** lane_pow() lane by lane: vector_pow() in the AVX2 variant, glibc's
       * exp(e ln x) otherwise (avx2_fma_kernel). */
      inline Double4
      lane_pow(const Double4 x, const double e)
      {
        if (avx2_fma_kernel)
          return vector_pow(x, e);
        Double4 r;
        for (unsigned int l = 0; l < 4; ++l)
          r[l] = lane_pow(x[l], e);
        return r;
      }

      /** lane_asinh_ratio() in all four lanes: the series in every lane,
       * std::asinh only where s >= 0.1. */
      inline Double4
      lane_asinh_ratio(const Double4 s, const Double4 s2)
      {
        Double4 r = asinh_ratio_series(s2);
        if (!all_lanes(s < 0.1))
          for (unsigned int l = 0; l < 4; ++l)
            if (s[l] >= 0.1)
              r[l] = std::asinh(s[l]) / s[l];
        return r;
      }
    } // namespace internal
#pragma GCC diagnostic pop
  } // namespace FE
} // namespace YarnImpact

#endif
