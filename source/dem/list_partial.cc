// The partial search of a neighbour-list block of the DEM impact model
// (doc/dem.md section 4, "Partial searches"): where a block's criterion
// fails, only its spheres that moved farther than a threshold since the
// build are searched again, among all the block's spheres at their current
// positions; the pairs of two other spheres keep the build's lists and
// criterion. The work follows the fast spheres: the others are looked up
// in the build's cell grid (they are within the threshold of where their
// bin's reference displacement puts them), the fast ones in a grid of
// their own, and the lists are merged in one pass in the order of a build.

#include <yarn_impact/dem/neighbour_lists.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      namespace
      {
        constexpr double infinity = std::numeric_limits<double>::infinity();

        /** The key of a cell (cx, cy, cz) >= 0 of the fast spheres' grid,
         * in the order of cx, cy, cz (so that the cells cz - 1 to cz + 1
         * of a column are one run of keys). */
        inline std::uint64_t
        fast_key(const long cx, const long cy, const long cz)
        {
          return (static_cast<std::uint64_t>(cx) << 42) |
                 (static_cast<std::uint64_t>(cy) << 21) |
                 static_cast<std::uint64_t>(cz);
        }

        /** A mirror pair being merged, with its tangential history. */
        struct MirrorEntry
        {
          MirrorPair p;
          double xi_t[3];
        };
      } // namespace


      template <typename F>
      void
      NeighbourLists::for_each_near(const ListBlock &B,
                                    const double q[3],
                                    const double slow_reach,
                                    const F &f) const
      {
        // Spheres that are not fast: j lies within slow_reach of q - D_b
        // in the build's grid if it is now within the cut-off of q, D_b
        // the reference of its bin b. Over the bins that hold such spheres
        // x0 + b h + D_b,x grows with b (consecutive references differ by
        // at most g < skin < h), so those within reach of q are a run.
        const double h   = cutoff;
        const auto below = [&](const std::uint32_t b) {
          // Bin b lies wholly above q's reach.
          return q[0] - B.bin_mean_displacement[3 * b] + slow_reach <
                 B.grid_x0 - B.grid_x_slack + b * h;
        };
        const auto above = [&](const std::uint32_t b) {
          return q[0] - B.bin_mean_displacement[3 * b] - slow_reach >
                 B.grid_x0 + (b + 1) * h;
        };
        auto it =
          std::partition_point(slow_bins.begin(), slow_bins.end(), above);
        for (; it != slow_bins.end() && !below(*it); ++it)
          {
            const std::uint32_t b = *it;
            if (above(b))
              continue;
            const double qy = q[1] - B.bin_mean_displacement[3 * b + 1],
                         qz = q[2] - B.bin_mean_displacement[3 * b + 2];
            const double ic = B.grid_ic[b];
            const long ny = B.grid_ny[b], nz = B.grid_nz[b];
            const long y0 = std::max(0l,
                                     static_cast<long>(std::floor(
                                       (qy - slow_reach - B.grid_y0[b]) * ic)));
            const long y1 = std::min(ny - 1,
                                     static_cast<long>(std::floor(
                                       (qy + slow_reach - B.grid_y0[b]) * ic)));
            const long z0 = std::max(0l,
                                     static_cast<long>(std::floor(
                                       (qz - slow_reach - B.grid_z0[b]) * ic)));
            const long z1 = std::min(nz - 1,
                                     static_cast<long>(std::floor(
                                       (qz + slow_reach - B.grid_z0[b]) * ic)));
            if (z0 > z1)
              continue;
            for (long r = y0; r <= y1; ++r)
              {
                const std::uint32_t row = B.grid_cell_off[b] + r * nz;
                for (std::uint32_t p = B.grid_cell_start[row + z0];
                     p < B.grid_cell_start[row + z1 + 1];
                     ++p)
                  {
                    const std::uint32_t j = B.grid_cell_sphere[p];
                    if (!B.fast[j - B.row_sphere_begin])
                      f(j);
                  }
              }
          }
        // Fast spheres: cubic cells of the cut-off at their current
        // positions, the 3 x 3 x 3 around q.
        long c[3];
        for (unsigned int d = 0; d < 3; ++d)
          c[d] = static_cast<long>(std::floor((q[d] - fast_origin[d]) / h));
        for (long cx = c[0] - 1; cx <= c[0] + 1; ++cx)
          for (long cy = c[1] - 1; cy <= c[1] + 1; ++cy)
            {
              if (cx < 0 || cy < 0 || c[2] + 1 < 0)
                continue;
              const std::uint64_t k0 = fast_key(cx, cy, std::max(0l, c[2] - 1)),
                                  k1 = fast_key(cx, cy, c[2] + 1);
              auto p                 = std::lower_bound(
                fast_cells.begin(),
                fast_cells.end(),
                k0,
                [](const std::pair<std::uint64_t, std::uint32_t> &a,
                   const std::uint64_t v) { return a.first < v; });
              for (; p != fast_cells.end() && p->first <= k1; ++p)
                f(p->second);
            }
      }


      bool
      NeighbourLists::search_fast(ListBlock &B)
      {
        // With `List rebuilds = missed contact` every block that is stale
        // or misses a contact is rebuilt whole: that mode counts the
        // rebuilds the contacts need.
        if ((B.stale && !B.halo_grew) || !(prm.partial_search_fraction > 0.) ||
            prm.list_rebuilds == Parameters::ListRebuilds::missed_contact ||
            B.n_bins == 0)
          return false;
        // Cross-sections that joined the halo: their spheres are fast (the
        // build's criterion, its counts and its grid know nothing of them).
        const std::size_t sb = B.row_sphere_begin;
        if (!B.searched)
          B.fast.assign(B.halo_sphere_end - sb, 0);
        if (B.halo_grew)
          {
            B.halo_sphere_end   = decomposition.local_index(B.halo_end, 0);
            const std::size_t n = B.halo_sphere_end - sb;
            B.fast.resize(n, 1);
            B.pos_build.resize(3 * n, 0.f);
            B.bin_of.resize(n, 0);
            B.stale     = false;
            B.halo_grew = false;
          }
        const unsigned int nf = chains.nf;
        const std::size_t se = B.halo_sphere_end, n = se - sb,
                          row_e = B.row_sphere_end;
        const double *x         = pos.data();
        const double margin     = 8. * 6e-8 * length;
        const double cut2       = cutoff * cutoff;

        // The threshold tau: 2 tau is half of what the build's criterion
        // leaves to 2 r besides g and the mirror terms, so that the spheres
        // left out of the search start at r <= tau and keep the criterion
        // for some steps.
        const auto room = [&]() {
          double dz = 0.;
          const double g =
            bin_terms(B.n_bins, B.bin_count, B.bin_mean_displacement, dz);
          const double dx0 =
            (B.holds_plane ? std::abs(B.bin_mean_displacement[0]) : 0.);
          return prm.skin - margin - 2. * g - (chains.z_sym ? 2. * dz : 0.) -
                 2. * dx0;
        };
        const double free = room();
        if (!(free > 0.))
          return false;
        const double tau2 = 0.0625 * free * free; // tau = free / 4
        // The displacement of sphere k of the build since the build,
        // relative to its bin's reference, squared.
        const auto relative2 = [&](const std::size_t k) {
          const std::size_t i   = sb + k;
          const std::uint32_t b = B.bin_of[k];
          double r2             = 0.;
          for (unsigned int c = 0; c < 3; ++c)
            {
              const double e = x[3 * i + c] - B.pos_build[3 * k + c] -
                               B.bin_mean_displacement[3 * b + c];
              r2 += e * e;
            }
          return r2;
        };

        // One pass over the build's spheres: the new fast ones, and the
        // x-range of all for the bins of this search.
        std::size_t n_fast = 0;
        double xmin = infinity, xmax = -infinity;
        for (std::size_t k = 0; k < n; ++k)
          {
            const std::size_t i = sb + k;
            xmin                = std::min(xmin, x[3 * i]);
            xmax                = std::max(xmax, x[3 * i]);
            if (!B.fast[k] && relative2(k) > tau2)
              B.fast[k] = 1;
            n_fast += B.fast[k];
          }
        if (static_cast<double>(n_fast) >
            prm.partial_search_fraction * static_cast<double>(n))
          return false;

        // The build's criterion over the other spheres, with references
        // from them alone; it must hold at this step.
        std::fill(B.bin_count.begin(), B.bin_count.end(), 0u);
        std::fill(B.bin_mean_displacement.begin(),
                  B.bin_mean_displacement.end(),
                  0.);
        for (std::size_t k = 0; k < n; ++k)
          if (!B.fast[k])
            {
              const std::uint32_t b = B.bin_of[k];
              ++B.bin_count[b];
              for (unsigned int c = 0; c < 3; ++c)
                B.bin_mean_displacement[3 * b + c] +=
                  x[3 * (sb + k) + c] - B.pos_build[3 * k + c];
            }
        for (unsigned int b = 0; b < B.n_bins; ++b)
          if (B.bin_count[b] > 0)
            for (unsigned int c = 0; c < 3; ++c)
              B.bin_mean_displacement[3 * b + c] /= B.bin_count[b];
        // Mirror pairs in x = 0 measure from bin 0, which must keep spheres.
        if (B.holds_plane && B.bin_count[0] == 0)
          return false;
        double r2_slow = 0.;
        for (std::size_t k = 0; k < n; ++k)
          if (!B.fast[k])
            r2_slow = std::max(r2_slow, relative2(k));
        if (!(2. * std::sqrt(r2_slow) < room()))
          return false;
        std::fill(B.bin_displacement_sum.begin(),
                  B.bin_displacement_sum.end(),
                  0.);
        B.r2_max = 0.;
        ++n_partial;
        partial_spheres += n_fast;
        if (!B.has_grid)
          make_build_grid(B);

        // The criterion of this search: bins along x over all the build's
        // spheres at their current positions, references 0.
        B.searched = true;
        const unsigned int n_bins =
          static_cast<unsigned int>((xmax - xmin) / cutoff) + 1;
        B.n_bins_search = n_bins;
        B.bin_count_search.assign(n_bins, 0);
        B.search_mean_displacement.assign(3 * n_bins, 0.);
        B.search_displacement_sum.assign(3 * n_bins, 0.);
        B.r2_search = B.r2_search_fast = 0.;
        B.pos_search.resize(3 * n);
        B.bin_of_search.resize(n);
        // The fast spheres (by their cells' keys below) and the lowest
        // corner of their grid.
        fast_cells.clear();
        for (unsigned int d = 0; d < 3; ++d)
          fast_origin[d] = infinity;
        for (std::size_t k = 0; k < n; ++k)
          {
            const std::size_t i = sb + k;
            const auto b =
              std::min<std::uint32_t>(static_cast<std::uint32_t>(
                                        (x[3 * i] - xmin) / cutoff),
                                      n_bins - 1);
            B.bin_of_search[k] = b;
            ++B.bin_count_search[b];
            for (unsigned int c = 0; c < 3; ++c)
              B.pos_search[3 * k + c] = static_cast<float>(x[3 * i + c]);
            if (B.fast[k])
              {
                fast_cells.emplace_back(0, i);
                for (unsigned int d = 0; d < 3; ++d)
                  fast_origin[d] = std::min(fast_origin[d], x[3 * i + d]);
              }
          }

        // The grid of the fast spheres at their current positions (cubic
        // cells of the cut-off), and the build's bins that keep spheres.
        for (auto &fc : fast_cells)
          {
            long c[3];
            for (unsigned int d = 0; d < 3; ++d)
              c[d] = static_cast<long>(
                std::floor((x[3 * fc.second + d] - fast_origin[d]) / cutoff));
            fc.first = fast_key(c[0], c[1], c[2]);
          }
        std::sort(fast_cells.begin(), fast_cells.end());
        slow_bins.clear();
        for (unsigned int b = 0; b < B.n_bins; ++b)
          if (B.bin_count[b] > 0)
            slow_bins.push_back(b);
        // The others are within sqrt(r2_slow) < tau of their bin's
        // reference (the new one), the grid's positions within the rounding
        // of the build positions (margin).
        const double slow_reach = cutoff + std::sqrt(r2_slow) + 2. * margin;

        // The pairs of each fast sphere i with every sphere of the build
        // closer than the cut-off (a pair of two fast spheres once, from
        // the lower one), with the rules of the build (list_build.cc).
        const auto owned = [this](const std::size_t i) {
          return decomposition.owned(i);
        };
        found_fast.clear();
        found_mirror.clear();
        const auto add_mirror = [&](const std::size_t i,
                                    const std::size_t j,
                                    const std::uint8_t axes,
                                    const double w) {
          add_mirror_pair_if_near(i,
                                  j,
                                  axes,
                                  w,
                                  x,
                                  cut2,
                                  row_e,
                                  owned,
                                  found_mirror);
        };
        const std::vector<double> &zmask = chains.zmask;
        for (const auto &fc : fast_cells)
          {
            const std::size_t i = fc.second;
            const bool i_owned  = owned(i);
            // Listed once: from the lower of two fast spheres.
            const auto other = [&](const std::size_t j) {
              return !(B.fast[j - sb] && j < i);
            };
            const double q[3] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
            for_each_near(B, q, slow_reach, [&](const std::size_t j) {
              if (j == i || !other(j))
                return;
              const double ex = x[3 * i] - x[3 * j],
                           ey = x[3 * i + 1] - x[3 * j + 1],
                           ez = x[3 * i + 2] - x[3 * j + 2];
              if (ex * ex + ey * ey + ez * ez >= cut2 ||
                  (!i_owned && !owned(j)) || j == i + nf || j + nf == i ||
                  (i >= row_e && j >= row_e))
                return;
              found_fast.emplace_back(std::min(i, j), std::max(i, j));
            });
            // Mirror pairs: the spheres near the image of i are those whose
            // image is near i.
            const bool zi = chains.z_sym && zmask[i % nf] == 0.;
            if (chains.z_sym && !zi)
              {
                const double qz[3] = {q[0], q[1], -q[2]};
                for_each_near(B, qz, slow_reach, [&](const std::size_t j) {
                  if (zmask[j % nf] != 0. && other(j))
                    add_mirror(i,
                               j,
                               2,
                               chains.x_sym &&
                                   decomposition.station_of(i) == 0 &&
                                   decomposition.station_of(j) == 0
                                 ? 0.5
                                 : 1.);
                });
              }
            if (B.holds_plane && i >= nf)
              {
                const double qx[3] = {-q[0], q[1], q[2]};
                for_each_near(B, qx, slow_reach, [&](const std::size_t j) {
                  if (j < nf || !other(j))
                    return;
                  const bool zj = chains.z_sym && zmask[j % nf] == 0.;
                  add_mirror(i, j, 1, zi && zj ? 0.5 : 1.);
                });
                if (chains.z_sym && !zi)
                  {
                    const double qxz[3] = {-q[0], q[1], -q[2]};
                    for_each_near(B, qxz, slow_reach, [&](const std::size_t j) {
                      if (j >= nf && other(j) && zmask[j % nf] != 0.)
                        add_mirror(i, j, 3, 1.);
                    });
                  }
              }
          }
        merge_fast(B);
        return true;
      }


      void
      NeighbourLists::merge_fast(ListBlock &B)
      {
        // The lists: the pairs of two spheres that are not fast, as they
        // were, and the pairs found for the fast ones, with the weights of
        // the build and the tangential history of those listed before;
        // rows sorted by j, mirror pairs by (i, j, axes), as in the build.
        // Both are sorted, so each row is one merge of two runs, in one
        // pass over the old lists.
        const unsigned int nf            = chains.nf;
        const std::vector<double> &zmask = chains.zmask;
        const std::size_t sb             = B.row_sphere_begin;
        const std::size_t n_rows         = B.row_sphere_end - sb;
        std::swap(B.pstart, B.pstart_old);
        std::swap(B.pairs, B.pairs_old);
        std::swap(B.pair_tangential_displacement,
                  B.pair_tangential_displacement_old);
        const std::vector<std::uint32_t> &pstart_old = B.pstart_old;
        const std::vector<Pair> &pairs_old           = B.pairs_old;
        const std::vector<double> &xi_old = B.pair_tangential_displacement_old;
        std::sort(found_fast.begin(), found_fast.end());
        B.pstart.resize(n_rows + 1);
        B.pstart[0] = 0;
        B.pairs.resize(pairs_old.size() + found_fast.size());
        B.pair_tangential_displacement.resize(3 * B.pairs.size());
        Pair *const out   = B.pairs.data();
        double *const xio = B.pair_tangential_displacement.data();
        std::size_t m = 0, q = 0;
        const auto keep = [&](const std::uint32_t p, const float w) {
          out[m] = {pairs_old[p].j, w};
          for (unsigned int c = 0; c < 3; ++c)
            xio[3 * m + c] = xi_old[3 * p + c];
          ++m;
        };
        for (std::size_t r = 0; r < n_rows; ++r)
          {
            const std::size_t i   = sb + r;
            const bool i_fast     = B.fast[r];
            std::uint32_t p       = pstart_old[r];
            const std::uint32_t e = pstart_old[r + 1];
            for (; q < found_fast.size() && found_fast[q].first == i; ++q)
              {
                const std::uint32_t j = found_fast[q].second;
                // The old pairs before j: kept if neither sphere is fast.
                for (; p < e && pairs_old[p].j < j; ++p)
                  if (!i_fast && !B.fast[pairs_old[p].j - sb])
                    keep(p, pairs_old[p].w);
                // The weights of the build, in its order (list_build.cc).
                float w = 1.f;
                if (chains.x_sym && decomposition.lo == 0 && i < nf && j < nf)
                  w *= 0.5f;
                if (chains.z_sym && zmask[i % nf] == 0. && zmask[j % nf] == 0.)
                  w *= 0.5f;
                if (chains.coupled)
                  w *= static_cast<float>(
                    0.5 * (chains.cw[decomposition.station_of(i)] +
                           chains.cw[decomposition.station_of(j)]));
                if (p < e && pairs_old[p].j == j)
                  {
                    // Listed before (one of the two is fast): its history
                    // if it is an active contact.
                    if (pairs_old[p].w < 0.f)
                      keep(p, -w);
                    else
                      {
                        out[m] = {j, w};
                        std::fill(xio + 3 * m, xio + 3 * m + 3, 0.);
                        ++m;
                      }
                    ++p;
                  }
                else
                  {
                    out[m] = {j, w};
                    std::fill(xio + 3 * m, xio + 3 * m + 3, 0.);
                    ++m;
                  }
              }
            if (!i_fast)
              for (; p < e; ++p)
                if (!B.fast[pairs_old[p].j - sb])
                  keep(p, pairs_old[p].w);
            B.pstart[r + 1] = m;
          }
        B.pairs.resize(m);
        B.pair_tangential_displacement.resize(3 * m);

        std::swap(B.mpairs, B.mpairs_old);
        std::swap(B.mirror_tangential_displacement,
                  B.mirror_tangential_displacement_old);
        const std::vector<MirrorPair> &mold = B.mpairs_old;
        const std::vector<double> &mxi_old =
          B.mirror_tangential_displacement_old;
        std::vector<MirrorEntry> mirror;
        for (std::size_t p = 0; p < mold.size(); ++p)
          if (!B.fast[mold[p].i - sb] && !B.fast[mold[p].j - sb])
            mirror.push_back(
              {mold[p],
               {mxi_old[3 * p], mxi_old[3 * p + 1], mxi_old[3 * p + 2]}});
        for (const MirrorPair &m : found_mirror)
          {
            MirrorEntry e = {m, {0., 0., 0.}};
            const auto old =
              std::lower_bound(mold.begin(), mold.end(), m, mirror_less);
            if (old != mold.end() && old->i == m.i && old->j == m.j &&
                old->axes == m.axes && old->active)
              {
                const std::size_t p = old - mold.begin();
                e.p.active          = true;
                for (unsigned int c = 0; c < 3; ++c)
                  e.xi_t[c] = mxi_old[3 * p + c];
              }
            mirror.push_back(e);
          }
        std::sort(mirror.begin(),
                  mirror.end(),
                  [](const MirrorEntry &a, const MirrorEntry &b) {
                    return mirror_less(a.p, b.p);
                  });
        B.mpairs.resize(mirror.size());
        B.mirror_tangential_displacement.resize(3 * mirror.size());
        for (std::size_t p = 0; p < mirror.size(); ++p)
          {
            B.mpairs[p] = mirror[p].p;
            for (unsigned int c = 0; c < 3; ++c)
              B.mirror_tangential_displacement[3 * p + c] = mirror[p].xi_t[c];
          }
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
