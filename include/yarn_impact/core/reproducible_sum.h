#ifndef yarn_impact_core_reproducible_sum_h
#define yarn_impact_core_reproducible_sum_h

#include <mpi.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

namespace YarnImpact
{
  /**
   * Sums of doubles that do not depend on the order of the terms nor on how
   * they are split between MPI ranks: the result is a function of the
   * multiset of terms only, bit for bit. A plain floating-point sum is not
   * (its rounding depends on the order), so sums over the owned part of
   * each rank, then over the ranks, change in the last digits with the
   * number of ranks; in an explicit simulation such a difference in the
   * force on the projectile grows into a different history.
   *
   * How: each term is split into 32-bit digits on a fixed grid of binary
   * exponents (bins of 32 bits, the same for every rank and run), and the
   * digits are added as integers, which is exact and associative. Each
   * sum keeps the K = 4 bins below and including the bin of the largest
   * |term| so far; digits below them are dropped (truncated toward zero).
   * Since the kept bins are set by the largest term, which is the same
   * whatever the order or split, so is every dropped bit. The ranks'
   * accumulators are merged by one MPI_Allreduce with a merge operation
   * (aligning the bins, adding the integers); only then is the sum rounded
   * to a double.
   *
   * Accuracy: with M the largest |term| and n the number of terms,
   * |result - exact sum| <= 2^-53 |exact sum| + (2^-64 + n 2^-96) M,
   * much tighter than the (n - 1) 2^-53 sum|term| of a plain sum. At most
   * 2^31 terms per value over all ranks (the digits of a bin are summed in
   * an int64). A non-finite term makes the result the plain sum of the
   * non-finite terms (inf or NaN), as a plain sum would be.
   *
   * This is the usual "binned" reproducible summation (as in ReproBLAS),
   * here with integer digits.
   */
  class ReproducibleSum
  {
  public:
    /** @p n_values independent sums, all zero. */
    explicit ReproducibleSum(const unsigned int n_values = 1);

    /** Number of independent sums. */
    unsigned int
    size() const
    {
      return bins.size();
    }

    /** Add @p term to sum @p i (any unit; the sum has the term's). */
    inline void
    add(const unsigned int i, const double term);

    /** Add all sums of @p other (of the same size) to these; the same as
     * adding its terms here, in any order. */
    void
    merge(const ReproducibleSum &other);

    /** The sums of the terms added on this rank only, rounded to double. */
    std::vector<double>
    local_values() const;

    /** The sums of the terms added on all ranks of @p communicator,
     * rounded to double, the same on every rank. Collective (one
     * MPI_Allreduce); every rank must have the same size(). */
    std::vector<double>
    sum(const MPI_Comm communicator) const;

    /** 128-bit integers (a GCC and Clang extension). */
    __extension__ typedef unsigned __int128 uint128;
    /** 128-bit integers (a GCC and Clang extension). */
    __extension__ typedef __int128 int128;

    /** Number of bins kept per sum. */
    static constexpr int n_kept_bins = 4;
    /** Bits per bin. */
    static constexpr int bin_width = 32;
    /** Bit position 0 of bin 0: every binary exponent of a double (down to
     * the subnormal 2^-1074) lies in a bin of index >= 0. */
    static constexpr int bin_offset = 1088;

    /** One sum: the index of its highest kept bin (-1: no finite nonzero
     * term yet), the integer sums of the digits of each kept bin (lowest
     * first) and the plain sum of the non-finite terms. Plain data, so
     * that MPI can move it as bytes. */
    struct Bins
    {
      std::int64_t top = -1;
      std::array<std::int64_t, n_kept_bins> words{};
      double non_finite = 0.;

      /** Move the kept bins up so that @p new_top (>= top) is the highest,
       * dropping the lowest. */
      void
      raise_top(const std::int64_t new_top)
      {
        if (top < 0)
          words.fill(0);
        else
          {
            const std::int64_t d = new_top - top;
            for (int k = 0; k < n_kept_bins; ++k)
              words[k] = (k + d < n_kept_bins) ? words[k + d] : 0;
          }
        top = new_top;
      }
    };

  private:
    std::vector<Bins> bins;
  };


  /** The ReproducibleSum of @p terms over all ranks of @p communicator
   * (each rank gives its own). Collective. */
  double
  reproducible_sum(const std::vector<double> &terms,
                   const MPI_Comm communicator);


  // ---------------------------------------------------------------------
  // The inline member: called once per term, in loops over dofs and cells.

  inline void
  ReproducibleSum::add(const unsigned int i, const double term)
  {
    constexpr int K = n_kept_bins;
    Bins &b         = bins[i];
    std::uint64_t bits;
    std::memcpy(&bits, &term, sizeof(bits));
    const bool negative    = bits >> 63;
    const int exponent     = static_cast<int>((bits >> 52) & 0x7ff);
    std::uint64_t mantissa = bits & ((std::uint64_t(1) << 52) - 1);
    if (exponent == 0x7ff)
      {
        b.non_finite += term;
        return;
      }
    if (exponent == 0 && mantissa == 0)
      return;
    // term = +-mantissa * 2^lowest, mantissa < 2^53.
    int lowest = -1074;
    if (exponent > 0)
      {
        mantissa |= std::uint64_t(1) << 52;
        lowest = exponent - 1075;
      }
    const int highest      = lowest + 63 - __builtin_clzll(mantissa);
    const std::int64_t bin = (highest + bin_offset) / bin_width;
    if (bin > b.top)
      b.raise_top(bin);
    // The bits of |term| from the lower edge of the lowest kept bin up, as
    // one 128-bit integer (the K = 4 kept bins are 128 bits).
    const int shift =
      lowest - static_cast<int>((b.top - K + 1) * bin_width - bin_offset);
    uint128 digits;
    if (shift >= 0)
      digits = static_cast<uint128>(mantissa) << shift;
    else if (shift > -64)
      digits = mantissa >> -shift;
    else
      return;
    for (int k = 0; k < K; ++k)
      {
        const auto digit = static_cast<std::int64_t>(
          static_cast<std::uint64_t>(digits >> (bin_width * k)) & 0xffffffffu);
        b.words[k] += negative ? -digit : digit;
      }
  }
} // namespace YarnImpact

#endif
