// The lane functions of the FE force loop's vector path
// (include/yarn_impact/fe/simd.h), which evaluates the Charmetant law at
// four Gauss points at once: ln, exp and x^e of all four lanes without a
// call to the C library (vector_log, vector_exp, vector_pow: the AVX2
// variant's), against the C library's std::log, std::exp and
// std::pow (glibc's are within about half an ulp of the exact values):
// - vector_log and vector_exp within 1 ulp over the ranges the law meets (a
//   stretch near 1) and far beyond them, and at the points where the
//   algorithms switch (powers of 2, sqrt(2));
// - vector_pow within (2 + 2 |e ln x|) ulp where x^e is a normal number
//   (e ln x is within 1.5 |e ln x| ulp, which exp turns into a relative
//   error), and 0 where x = 0, beside lanes that are not;
// - the C library's value, to the bit, where a lane is not a positive
//   normal number (0, negative, subnormal, infinite, NaN) or the exponent
//   is out of range;
// - asinh(s)/s: the series lane by lane as the scalar path evaluates it,
//   std::asinh(s)/s from s = 0.1 on, within 4e-16 of the latter.
// Every check runs twice: compiled for any x86-64, and for AVX2 with FMA
// as the force loop's second variant (where the CPU has them; the output
// is the same either way). A physics-free check, not a regression record:
// every line says yes or no.

#include <yarn_impact/fe/simd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

#pragma GCC diagnostic ignored "-Wpsabi"

using YarnImpact::FE::internal::Double4;

namespace
{
  /** The distance of two doubles of the same sign in units in the last
   * place. */
  std::int64_t
  ulps(const double a, const double b)
  {
    std::int64_t x, y;
    std::memcpy(&x, &a, sizeof(x));
    std::memcpy(&y, &b, sizeof(y));
    return x > y ? x - y : y - x;
  }

  bool
  same_bits(const double a, const double b)
  {
    return std::memcmp(&a, &b, sizeof(a)) == 0;
  }

  /** What one variant found. */
  struct Findings
  {
    std::int64_t log_ulps = 0, exp_ulps = 0;
    double pow_excess = 0.; // largest error / allowed error
    bool special_log = true, special_exp = true, zero_pow = true;
    bool asinh_ratio = true;
  };

  /** The checks, inlined into each variant below (flatten), so that each
   * runs the lane functions compiled for its target. */
  inline Findings
  check()
  {
    using namespace YarnImpact::FE::internal;
    Findings found;
    std::mt19937 random(20261129);
    // ln x for x = e^t, t in ranges from near 0 (the law's stretches) to
    // nearly the whole range of normal doubles.
    for (const double t_max : {1e-6, 1e-3, 0.35, 0.7, 30., 700.})
      {
        std::uniform_real_distribution<double> t(-t_max, t_max);
        for (unsigned int sample = 0; sample < 200000; ++sample)
          {
            Double4 x, y;
            for (unsigned int l = 0; l < 4; ++l)
              {
                x[l] = std::exp(t(random));
                y[l] = t(random);
              }
            const Double4 ln = vector_log(x), e = vector_exp(y);
            const double power = 1.205; // p - 1 of the paper's law
            const Double4 pw   = vector_pow(x, power);
            for (unsigned int l = 0; l < 4; ++l)
              {
                found.log_ulps =
                  std::max(found.log_ulps, ulps(ln[l], std::log(x[l])));
                found.exp_ulps =
                  std::max(found.exp_ulps, ulps(e[l], std::exp(y[l])));
                const double exact = std::pow(x[l], power);
                const double allowed =
                  (2. + 2. * std::abs(power * std::log(x[l]))) *
                  std::numeric_limits<double>::epsilon() * exact;
                // (Where x^e is not a normal number it has fewer bits than
                // any ulp bound assumes; the law never meets it.)
                if (exact >= std::numeric_limits<double>::min())
                  found.pow_excess =
                    std::max(found.pow_excess,
                             std::abs(pw[l] - exact) / allowed);
              }
          }
      }
    // The switching points: powers of 2 and sqrt(2), and their neighbours.
    for (int k = -1000; k <= 1000; k += 7)
      for (const double m : {1., std::sqrt(2.), 0.5 * std::sqrt(2.)})
        {
          const double c = std::ldexp(m, k);
          const Double4 x{std::nextafter(c, 0.),
                          c,
                          std::nextafter(c, 1e308),
                          c};
          const Double4 ln = vector_log(x);
          for (unsigned int l = 0; l < 4; ++l)
            found.log_ulps =
              std::max(found.log_ulps, ulps(ln[l], std::log(x[l])));
        }
    // Lanes the algorithms leave to the C library: the whole vector takes
    // its values.
    {
      const double nan           = std::numeric_limits<double>::quiet_NaN();
      const double inf           = std::numeric_limits<double>::infinity();
      const double specials[][4] = {{0., 1., 2., 3.},
                                    {1., -1., 2., 3.},
                                    {1., 2., 1e-310, 3.},
                                    {1., 2., 3., inf},
                                    {nan, 1., 2., 3.},
                                    {-0., 5., 6., 7.}};
      for (const auto &v : specials)
        {
          const Double4 x{v[0], v[1], v[2], v[3]};
          const Double4 ln = vector_log(x);
          for (unsigned int l = 0; l < 4; ++l)
            found.special_log =
              found.special_log && same_bits(ln[l], std::log(x[l]));
        }
      const double exp_specials[][4] = {{-800., 0., 1., 2.},
                                        {0., 710., 1., 2.},
                                        {0., 1., nan, 2.},
                                        {-708.5, 0., 1., 2.},
                                        {0., 1., 2., -inf}};
      for (const auto &v : exp_specials)
        {
          const Double4 y{v[0], v[1], v[2], v[3]};
          const Double4 e = vector_exp(y);
          for (unsigned int l = 0; l < 4; ++l)
            found.special_exp =
              found.special_exp && same_bits(e[l], std::exp(y[l]));
        }
      // x^e = 0 at x = 0, whatever the other lanes hold.
      const Double4 x{0., 0.25, 0., 1e-3};
      const Double4 pw = vector_pow(x, 1.205);
      found.zero_pow =
        pw[0] == 0. && pw[2] == 0. &&
        std::abs(pw[1] - std::pow(0.25, 1.205)) <
          1e-15 * std::pow(0.25, 1.205) &&
        std::abs(pw[3] - std::pow(1e-3, 1.205)) < 1e-14 * std::pow(1e-3, 1.205);
    }
    // asinh(s)/s: the series below 0.1, asinh above, lane by lane.
    for (const double s_max : {1e-4, 0.099, 0.3})
      {
        std::uniform_real_distribution<double> s_of(0., s_max);
        for (unsigned int sample = 0; sample < 10000; ++sample)
          {
            Double4 s;
            for (unsigned int l = 0; l < 4; ++l)
              s[l] = s_of(random);
            const Double4 r = lane_asinh_ratio(s, s * s);
            for (unsigned int l = 0; l < 4; ++l)
              {
                const double reference =
                  s[l] >= 0.1
                    ? std::asinh(s[l]) / s[l]
                    : YarnImpact::FE::internal::lane_asinh_ratio(s[l],
                                                                 s[l] * s[l]);
                found.asinh_ratio =
                  found.asinh_ratio &&
                  std::abs(r[l] - reference) <= 2.3e-16 * reference &&
                  std::abs(r[l] - std::asinh(s[l]) / s[l]) <= 4e-16 * reference;
              }
          }
      }
    return found;
  }

  Findings
  check_portable()
  {
    return check();
  }

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  __attribute__((target("avx2,fma"), flatten)) Findings
  check_avx2()
  {
    return check();
  }
#endif

  void
  report(const Findings &f)
  {
    std::printf("%-52s %s\n",
                "ln within 1 ulp of std::log",
                f.log_ulps <= 1 ? "OK" : "WRONG");
    std::printf("%-52s %s\n",
                "exp within 1 ulp of std::exp",
                f.exp_ulps <= 1 ? "OK" : "WRONG");
    std::printf("%-52s %s\n",
                "x^e within (2 + 2 |e ln x|) ulp of std::pow",
                f.pow_excess <= 1. ? "OK" : "WRONG");
    std::printf("%-52s %s\n",
                "ln of 0, negative, subnormal, inf, NaN: std::log's",
                f.special_log ? "OK" : "WRONG");
    std::printf("%-52s %s\n",
                "exp out of range, inf, NaN: std::exp's",
                f.special_exp ? "OK" : "WRONG");
    std::printf("%-52s %s\n",
                "x^e = 0 where x = 0, beside other lanes",
                f.zero_pow ? "OK" : "WRONG");
    std::printf("%-52s %s\n",
                "asinh(s)/s: the scalar path within 1 ulp",
                f.asinh_ratio ? "OK" : "WRONG");
  }
} // namespace

int
main()
{
  std::printf("portable variant\n");
  report(check_portable());
  std::printf("AVX2 and FMA variant (where the CPU has them)\n");
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    report(check_avx2());
  else
#endif
    report(check_portable());
  return 0;
}
