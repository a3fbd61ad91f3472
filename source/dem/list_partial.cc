// The partial search of a neighbour-list block of the DEM impact model
// (doc/dem.md section 4, "Partial searches"): where a block's criterion
// fails, only its spheres that moved farther than a threshold since the
// build are searched again, among all the block's spheres at their current
// positions; the pairs of two other spheres keep the build's lists and
// criterion.

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

        /** A pair of a row being merged, with its tangential history. */
        struct RowEntry
        {
          std::uint32_t j;
          float w;
          double xi_t[3];
        };

        /** A mirror pair being merged, with its tangential history. */
        struct MirrorEntry
        {
          MirrorPair p;
          double xi_t[3];
        };
      } // namespace


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
        // build's criterion knows nothing of them).
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
        std::size_t n_fast = 0;
        for (std::size_t k = 0; k < n; ++k)
          {
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
        double r2 = 0.;
        for (std::size_t k = 0; k < n; ++k)
          if (!B.fast[k])
            r2 = std::max(r2, relative2(k));
        if (!(2. * std::sqrt(r2) < room()))
          return false;
        std::fill(B.bin_displacement_sum.begin(),
                  B.bin_displacement_sum.end(),
                  0.);
        B.r2_max = 0.;
        ++n_partial;
        partial_spheres += n_fast;

        // The criterion of this search: bins along x over all the build's
        // spheres at their current positions, references 0.
        B.searched  = true;
        double xmin = infinity, xmax = -infinity;
        for (std::size_t i = sb; i < se; ++i)
          {
            xmin = std::min(xmin, x[3 * i]);
            xmax = std::max(xmax, x[3 * i]);
          }
        const unsigned int n_bins =
          static_cast<unsigned int>((xmax - xmin) / cutoff) + 1;
        B.n_bins_search = n_bins;
        B.bin_count_search.assign(n_bins, 0);
        B.search_mean_displacement.assign(3 * n_bins, 0.);
        B.search_displacement_sum.assign(3 * n_bins, 0.);
        B.r2_search = B.r2_search_fast = 0.;
        B.pos_search.resize(3 * n);
        B.bin_of_search.resize(n);
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
          }
        // A (y, z) grid of cells no smaller than the cut-off in each bin,
        // as in the build.
        bin_y0.assign(n_bins, infinity);
        bin_z0.assign(n_bins, infinity);
        std::vector<double> &y1 = cell_y, &z1 = cell_z; // scratch
        y1.assign(n_bins, -infinity);
        z1.assign(n_bins, -infinity);
        for (std::size_t k = 0; k < n; ++k)
          {
            const std::size_t i   = sb + k;
            const std::uint32_t b = B.bin_of_search[k];
            bin_y0[b]             = std::min(bin_y0[b], x[3 * i + 1]);
            y1[b]                 = std::max(y1[b], x[3 * i + 1]);
            bin_z0[b]             = std::min(bin_z0[b], x[3 * i + 2]);
            z1[b]                 = std::max(z1[b], x[3 * i + 2]);
          }
        bin_ic.resize(n_bins);
        bin_ny.resize(n_bins);
        bin_nz.resize(n_bins);
        cell_off.assign(n_bins + 1, 0);
        for (unsigned int b = 0; b < n_bins; ++b)
          {
            if (B.bin_count_search[b] == 0)
              bin_y0[b] = y1[b] = bin_z0[b] = z1[b] = 0.;
            double c = cutoff;
            while ((y1[b] - bin_y0[b]) / c * (z1[b] - bin_z0[b]) / c >
                   16. * B.bin_count_search[b] + 64.)
              c *= 2.;
            bin_ic[b] = 1. / c;
            bin_ny[b] = static_cast<std::uint32_t>((y1[b] - bin_y0[b]) / c) + 1;
            bin_nz[b] = static_cast<std::uint32_t>((z1[b] - bin_z0[b]) / c) + 1;
            cell_off[b + 1] = cell_off[b] + bin_ny[b] * bin_nz[b];
          }
        std::vector<std::uint32_t> &cell_of = near_sphere; // scratch
        cell_of.resize(n);
        cell_start.assign(cell_off[n_bins] + 1, 0);
        for (std::size_t k = 0; k < n; ++k)
          {
            const std::size_t i   = sb + k;
            const std::uint32_t b = B.bin_of_search[k];
            const auto cy         = static_cast<std::uint32_t>(
              (x[3 * i + 1] - bin_y0[b]) * bin_ic[b]);
            const auto cz = static_cast<std::uint32_t>(
              (x[3 * i + 2] - bin_z0[b]) * bin_ic[b]);
            cell_of[k] = cell_off[b] + std::min(cy, bin_ny[b] - 1) * bin_nz[b] +
                         std::min(cz, bin_nz[b] - 1);
            ++cell_start[cell_of[k] + 1];
          }
        for (std::uint32_t c = 0; c < cell_off[n_bins]; ++c)
          cell_start[c + 1] += cell_start[c];
        cell_sphere.resize(n);
        {
          std::vector<std::uint32_t> fill(cell_start.begin(),
                                          cell_start.end() - 1);
          for (std::size_t k = 0; k < n; ++k)
            cell_sphere[fill[cell_of[k]]++] = sb + k;
        }
        // Every sphere of bins b0 to b1 whose cell is in the 3 x 3 block
        // around (py, pz): all those closer than the cut-off in y and z.
        const auto visit = [&](const double py,
                               const double pz,
                               const unsigned int b0,
                               const unsigned int b1,
                               const auto &f) {
          for (unsigned int bb = b0; bb <= b1; ++bb)
            {
              if (B.bin_count_search[bb] == 0)
                continue;
              const long cy =
                static_cast<long>(std::floor((py - bin_y0[bb]) * bin_ic[bb]));
              const long cz =
                static_cast<long>(std::floor((pz - bin_z0[bb]) * bin_ic[bb]));
              const long ny = bin_ny[bb], nz = bin_nz[bb];
              const long c0 = std::max(0l, cz - 1),
                         c1 = std::min(nz - 1, cz + 1);
              if (c0 > c1)
                continue;
              for (long r = std::max(0l, cy - 1); r <= std::min(ny - 1, cy + 1);
                   ++r)
                {
                  const std::uint32_t row = cell_off[bb] + r * nz;
                  for (std::uint32_t q = cell_start[row + c0];
                       q < cell_start[row + c1 + 1];
                       ++q)
                    f(cell_sphere[q]);
                }
            }
        };

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
        for (std::size_t k = 0; k < n; ++k)
          {
            if (!B.fast[k])
              continue;
            const std::size_t i   = sb + k;
            const std::uint32_t b = B.bin_of_search[k];
            const unsigned int b0 = (b > 0 ? b - 1 : 0),
                               b1 = std::min(b + 1, n_bins - 1);
            const bool i_owned    = owned(i);
            // Listed once: from the lower of two fast spheres.
            const auto other = [&](const std::size_t j) {
              return !(B.fast[j - sb] && j < i);
            };
            visit(x[3 * i + 1], x[3 * i + 2], b0, b1, [&](const std::size_t j) {
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
            const bool zi = chains.z_sym && zmask[i % nf] == 0.;
            if (chains.z_sym && !zi)
              visit(x[3 * i + 1],
                    -x[3 * i + 2],
                    b0,
                    b1,
                    [&](const std::size_t j) {
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
            // In x = 0: only spheres within the cut-off of the plane, in
            // the bins from x = 0 (bin 0, and 1 for safety).
            if (B.holds_plane && i >= nf)
              {
                const unsigned int bx = std::min(1u, n_bins - 1);
                visit(x[3 * i + 1], x[3 * i + 2], 0, bx, [&](std::size_t j) {
                  if (j < nf || !other(j))
                    return;
                  const bool zj = chains.z_sym && zmask[j % nf] == 0.;
                  add_mirror(i, j, 1, zi && zj ? 0.5 : 1.);
                });
                if (chains.z_sym && !zi)
                  visit(x[3 * i + 1], -x[3 * i + 2], 0, bx, [&](std::size_t j) {
                    if (j >= nf && other(j) && zmask[j % nf] != 0.)
                      add_mirror(i, j, 3, 1.);
                  });
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
        B.pstart.assign(n_rows + 1, 0);
        B.pairs.clear();
        B.pair_tangential_displacement.clear();
        std::sort(found_fast.begin(), found_fast.end());
        std::vector<RowEntry> row;
        std::size_t q = 0;
        for (std::size_t r = 0; r < n_rows; ++r)
          {
            const std::size_t i = sb + r;
            row.clear();
            const std::uint32_t p0 = pstart_old[r], p1 = pstart_old[r + 1];
            if (!B.fast[r])
              for (std::uint32_t p = p0; p < p1; ++p)
                if (!B.fast[pairs_old[p].j - sb])
                  row.push_back(
                    {pairs_old[p].j,
                     pairs_old[p].w,
                     {xi_old[3 * p], xi_old[3 * p + 1], xi_old[3 * p + 2]}});
            for (; q < found_fast.size() && found_fast[q].first == i; ++q)
              {
                const std::uint32_t j = found_fast[q].second;
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
                RowEntry e = {j, w, {0., 0., 0.}};
                const Pair *old =
                  std::lower_bound(pairs_old.data() + p0,
                                   pairs_old.data() + p1,
                                   j,
                                   [](const Pair &a, const std::uint32_t v) {
                                     return a.j < v;
                                   });
                if (old != pairs_old.data() + p1 && old->j == j && old->w < 0.f)
                  {
                    const std::size_t p = old - pairs_old.data();
                    e.w                 = -e.w;
                    for (unsigned int c = 0; c < 3; ++c)
                      e.xi_t[c] = xi_old[3 * p + c];
                  }
                row.push_back(e);
              }
            std::sort(row.begin(),
                      row.end(),
                      [](const RowEntry &a, const RowEntry &b) {
                        return a.j < b.j;
                      });
            for (const RowEntry &e : row)
              {
                B.pairs.push_back({e.j, e.w});
                B.pair_tangential_displacement.insert(
                  B.pair_tangential_displacement.end(),
                  e.xi_t,
                  e.xi_t + 3);
              }
            B.pstart[r + 1] = B.pairs.size();
          }

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
