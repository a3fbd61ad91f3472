// The filter of the neighbour-list search (candidate_search.h) against an
// exhaustive double-precision search, for the portable variant and, where
// the CPU has it, the AVX2 variant: every candidate closer than the cut-off
// is kept (also on a shell within 1e-9 of it, with coordinates of 10 mm as
// after the impact), none beyond the enlarged radius, in the order of the
// runs, with runs of every length (the tails of the eight-wide loads).
#include <yarn_impact/dem/candidate_search.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <vector>

using namespace YarnImpact::DEM;

namespace
{
  /** Entries of @p sub that are not found, in their order, in @p seq: 0
   * if and only if @p sub is a subsequence of @p seq. */
  unsigned long
  not_in_order(const std::vector<std::uint32_t> &sub,
               const std::vector<std::uint32_t> &seq)
  {
    unsigned long n = 0;
    std::size_t a   = 0;
    for (const std::uint32_t k : sub)
      {
        while (a < seq.size() && seq[a] != k)
          ++a;
        if (a == seq.size())
          ++n;
        else
          ++a;
      }
    return n;
  }
} // namespace

int
main()
{
  const double cutoff = 16e-6; // d + skin [m]
  const double offset = 10e-3; // coordinates as far as 10 mm
  const double box[3] = {200e-6, 120e-6, 300e-6};
  std::mt19937 random(2026);
  std::uniform_real_distribution<double> unit(0., 1.);

  // Candidates: random points and, around some query points, points on a
  // shell just inside and just outside the cut-off.
  std::vector<double> px, py, pz;
  const auto add = [&](const double x, const double y, const double z) {
    px.push_back(x);
    py.push_back(y);
    pz.push_back(z);
  };
  // Random points sorted along x, so that runs near a query's x hold
  // partners; then the shells, after them.
  std::vector<std::array<double, 3>> points(3000);
  for (auto &p : points)
    p = {offset + box[0] * unit(random),
         box[1] * unit(random),
         offset + box[2] * unit(random)};
  std::sort(points.begin(), points.end());
  for (const auto &p : points)
    add(p[0], p[1], p[2]);
  std::vector<std::array<double, 3>> queries;
  std::vector<std::uint32_t> first_shell_point;
  for (unsigned int q = 0; q < 400; ++q)
    {
      const std::array<double, 3> c = {offset + box[0] * unit(random),
                                       box[1] * unit(random),
                                       offset + box[2] * unit(random)};
      queries.push_back(c);
      first_shell_point.push_back(static_cast<std::uint32_t>(px.size()));
      if (q % 2 == 0)
        for (unsigned int s = 0; s < 6; ++s)
          {
            double e[3]    = {unit(random) - 0.5,
                              unit(random) - 0.5,
                              unit(random) - 0.5};
            const double n = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
            const double r = cutoff * (s % 2 == 0 ? 1. - 1e-9 : 1. + 1e-9);
            add(c[0] + r * e[0] / n, c[1] + r * e[1] / n, c[2] + r * e[2] / n);
          }
    }
  const std::size_t n = px.size();

  // Relative to the origin (0, 0, 0) as the largest magnitude M: the radius
  // enlarged as in the list build.
  double magnitude = 0.;
  for (std::size_t k = 0; k < n; ++k)
    magnitude = std::max({magnitude, px[k], py[k], pz[k]});
  const float r2_f      = filter_radius2(cutoff, magnitude);
  const double radius_f = std::sqrt(static_cast<double>(r2_f));
  std::vector<float> cx(n + 8, 0.f), cy(n + 8, 0.f), cz(n + 8, 0.f);
  for (std::size_t k = 0; k < n; ++k)
    {
      cx[k] = static_cast<float>(px[k]);
      cy[k] = static_cast<float>(py[k]);
      cz[k] = static_cast<float>(pz[k]);
    }

  std::vector<NearInRuns> filters = {&near_in_runs_generic};
  if (near_in_runs_vectorised() != nullptr)
    filters.push_back(near_in_runs_vectorised());

  // Runs: up to six per query, of every length from 0 to 40, near the
  // query's x in the sorted points (or anywhere, up to the array's end);
  // the first one holds the query's shell, if it has one.
  std::uniform_int_distribution<std::uint32_t> length(0, 40), n_runs_of(0, 6);
  std::uniform_int_distribution<int> shift(-50, 10);
  unsigned long within = 0, shell = 0, candidates = 0, missed = 0, beyond = 0;
  // A kept entry that is not next in the order of the runs counts as
  // beyond (the walks below are subsequence tests).
  std::vector<std::uint32_t> out(n);
  for (std::size_t q = 0; q < queries.size(); ++q)
    {
      const auto &c = queries[q];
      CandidateRun runs[6];
      unsigned int n_runs = n_runs_of(random);
      const auto near =
        static_cast<int>(std::lower_bound(points.begin(),
                                          points.end(),
                                          std::array<double, 3>{c[0], 0., 0.}) -
                         points.begin());
      for (unsigned int r = 0; r < n_runs; ++r)
        {
          const std::uint32_t l = length(random);
          const int start = (r % 3 == 2 ? static_cast<int>(unit(random) * n)
                                        : near + shift(random));
          const auto k0   = static_cast<std::uint32_t>(
            std::clamp(start, 0, static_cast<int>(n - l)));
          runs[r] = {k0, k0 + l};
        }
      if (q % 2 == 0)
        {
          n_runs  = std::max(n_runs, 1u);
          runs[0] = {first_shell_point[q] - 3, first_shell_point[q] + 6};
        }
      // Exhaustive search, in the order of the runs.
      std::vector<std::uint32_t> inside, maybe;
      for (unsigned int r = 0; r < n_runs; ++r)
        for (std::uint32_t k = runs[r].k0; k < runs[r].k1; ++k)
          {
            ++candidates;
            const double ex = c[0] - px[k], ey = c[1] - py[k],
                         ez   = c[2] - pz[k];
            const double dist = std::sqrt(ex * ex + ey * ey + ez * ez);
            if (dist < cutoff)
              {
                inside.push_back(k);
                ++within;
                shell += (dist > cutoff * (1. - 1e-8));
              }
            if (dist < radius_f * (1. + 1e-5))
              maybe.push_back(k);
          }
      for (const NearInRuns filter : filters)
        {
          std::uint32_t *end = filter(cx.data(),
                                      cy.data(),
                                      cz.data(),
                                      runs,
                                      n_runs,
                                      static_cast<float>(c[0]),
                                      static_cast<float>(c[1]),
                                      static_cast<float>(c[2]),
                                      r2_f,
                                      out.data());
          const std::vector<std::uint32_t> kept(out.data(), end);
          // kept must be a subsequence of maybe containing all of inside.
          beyond += not_in_order(kept, maybe);
          missed += not_in_order(inside, kept);
        }
    }
  std::cout << "queries " << queries.size() << ", candidates " << candidates
            << ", closer than the cut-off " << within << " (" << shell
            << " within 1e-8 of it)\n"
            << "every filter keeps all of them: "
            << (missed == 0 ? "PASSED" : "FAILED") << "\n"
            << "none beyond the enlarged radius, in the order of the runs: "
            << (beyond == 0 ? "PASSED" : "FAILED") << "\n";
  return 0;
}
