// ReproducibleSum (core/reproducible_sum.h): the sum of 20 000 terms
// between 2^-60 and 2^40 in magnitude, of both signs, is the same bit for bit
// whatever their order and however they are split (between accumulators
// merged in any order here, and between the MPI ranks this test runs on:
// 1 and 3, one expected output for both); it is within the stated bound
// of the exact sum (terms on a grid where the exact sum is an integer),
// and exact where a plain sum cancels. A physics-free check, not a
// regression record: every line says yes or no.

#include <yarn_impact/core/reproducible_sum.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace YarnImpact;

namespace
{
  bool
  same_bits(const double a, const double b)
  {
    return std::memcmp(&a, &b, sizeof(a)) == 0;
  }

  /** Terms k * 2^e with odd and even 40-bit k, e in [-60, 0], both signs:
   * their exact sum times 2^60 is an integer (below 2^127). */
  std::vector<double>
  make_terms(const unsigned int n, ReproducibleSum::int128 &exact_scaled)
  {
    std::mt19937_64 random(20261123);
    std::vector<double> terms(n);
    exact_scaled = 0;
    for (double &t : terms)
      {
        const std::uint64_t bits = random();
        const auto k        = static_cast<std::int64_t>(bits >> 24); // 40 bits
        const int e         = -static_cast<int>(random() % 61);
        const bool negative = random() & 1;
        t                   = std::ldexp(negative ? -double(k) : double(k), e);
        exact_scaled +=
          (negative ? -ReproducibleSum::int128(k) : ReproducibleSum::int128(k))
          << (60 + e);
      }
    return terms;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm comm        = MPI_COMM_WORLD;
  const unsigned int rank    = dealii::Utilities::MPI::this_mpi_process(comm);
  const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  const bool root            = rank == 0;
  const char *yes_no[]       = {"no", "yes"};

  const unsigned int n = 20000;
  ReproducibleSum::int128 exact_scaled;
  const std::vector<double> terms = make_terms(n, exact_scaled);

  // The serial sum: one accumulator, the terms in their order.
  ReproducibleSum serial(1);
  for (const double t : terms)
    serial.add(0, t);
  const double reference = serial.local_values()[0];

  // Shuffled and split in 1 to 7 accumulators of random sizes, merged in a
  // shuffled order: every result bitwise the serial one.
  bool all_same = true;
  std::mt19937_64 random(7);
  for (unsigned int trial = 0; trial < 20; ++trial)
    {
      std::vector<double> shuffled = terms;
      std::shuffle(shuffled.begin(), shuffled.end(), random);
      const unsigned int parts = 1 + trial % 7;
      std::vector<ReproducibleSum> part(parts, ReproducibleSum(1));
      for (const double t : shuffled)
        part[random() % parts].add(0, t);
      std::vector<unsigned int> order(parts);
      for (unsigned int p = 0; p < parts; ++p)
        order[p] = p;
      std::shuffle(order.begin(), order.end(), random);
      ReproducibleSum merged(1);
      for (const unsigned int p : order)
        merged.merge(part[p]);
      all_same = all_same && same_bits(merged.local_values()[0], reference);
    }

  // Over the MPI ranks: each rank adds a random share of the shuffled
  // terms (the same shuffle on every rank, so that each term is added
  // once), several values at once.
  bool mpi_same = true;
  for (unsigned int trial = 0; trial < 5; ++trial)
    {
      std::vector<double> shuffled = terms;
      std::mt19937_64 shared_random(100 + trial);
      std::shuffle(shuffled.begin(), shuffled.end(), shared_random);
      ReproducibleSum distributed(3);
      for (const double t : shuffled)
        if (shared_random() % n_ranks == rank)
          {
            distributed.add(0, t);
            distributed.add(1, -t);
            distributed.add(2, 0.5 * t);
          }
      const std::vector<double> s = distributed.sum(comm);
      mpi_same                    = mpi_same && same_bits(s[0], reference) &&
                 same_bits(s[1], -reference) &&
                 same_bits(s[2], 0.5 * reference);
    }
  const double from_vector =
    reproducible_sum(rank == 0 ? terms : std::vector<double>(), comm);
  mpi_same = mpi_same && same_bits(from_vector, reference);

  // The bound: |S - exact| <= 2^-53 |exact| + (2^-64 + n 2^-96) max|term|.
  double largest = 0.;
  for (const double t : terms)
    largest = std::max(largest, std::abs(t));
  const long double exact = std::ldexp((long double)exact_scaled, -60);
  const long double error = std::abs((long double)reference - exact);
  const long double bound =
    std::ldexp(std::abs(exact), -53) +
    (std::ldexp(1.L, -64) + n * std::ldexp(1.L, -96)) * largest;
  // A plain sum, for comparison.
  double plain = 0.;
  for (const double t : terms)
    plain += t;
  const long double plain_error = std::abs((long double)plain - exact);

  // Cancellation, subnormals, zeros, non-finite terms.
  const double big = 1e20;
  const bool cancel =
    reproducible_sum({big, 1., -big}, MPI_COMM_SELF) == 1. &&
    reproducible_sum({1e-310, 2e-310, -1e-310}, MPI_COMM_SELF) == 2e-310 &&
    reproducible_sum({}, MPI_COMM_SELF) == 0. &&
    reproducible_sum({0., -0.}, MPI_COMM_SELF) == 0.;
  const double inf = std::numeric_limits<double>::infinity();
  const bool special =
    reproducible_sum({1., inf}, MPI_COMM_SELF) == inf &&
    std::isnan(reproducible_sum({inf, 1., -inf}, MPI_COMM_SELF)) &&
    std::isnan(reproducible_sum({std::nan(""), 1.}, MPI_COMM_SELF));

  if (root)
    {
      std::printf("ReproducibleSum of %u terms k 2^e (k < 2^40, -60 <= e "
                  "<= 0, both signs)\n",
                  n);
      std::printf("  sum                                       %.17g\n",
                  reference);
      std::printf("  20 shuffles split in 1-7 parts: bitwise the same    %s\n",
                  yes_no[all_same]);
      std::printf("  5 random splits over the MPI ranks: bitwise the same %s\n",
                  yes_no[mpi_same]);
      std::printf("  error within 2^-53 |S| + (2^-64 + n 2^-96) max|x|   %s\n",
                  yes_no[error <= bound]);
      std::printf("  no larger than a plain sum's error                  %s\n",
                  yes_no[error <= plain_error]);
      std::printf("  1e20 + 1 - 1e20 = 1, subnormals exact, empty = 0    %s\n",
                  yes_no[cancel]);
      std::printf("  inf and NaN propagate                               %s\n",
                  yes_no[special]);
    }
  return 0;
}
