// The build of a neighbour-list block of the DEM impact model (doc/dem.md
// section 4): bins along x, a (y, z) cell grid per bin, the candidate
// search with the single-precision filter, the exact test in double
// precision, the mirror pairs and the carrying of the tangential history.

#include <yarn_impact/dem/candidate_search.h>
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
      }


      void
      NeighbourLists::rebuild(ListBlock &B)
      {
        const unsigned int nf            = chains.nf;
        const bool x_sym                 = chains.x_sym;
        const bool z_sym                 = chains.z_sym;
        const std::vector<double> &zmask = chains.zmask;
        const unsigned int lo            = decomposition.lo;
        const auto owned                 = [this](const std::size_t i) {
          return decomposition.owned(i);
        };
        const auto local_index = [this](const unsigned int s,
                                        const unsigned int f) {
          return decomposition.local_index(s, f);
        };
        const auto station_of = [this](const std::size_t i) {
          return decomposition.station_of(i);
        };
        ++n_rebuilds;
        B.stale     = false;
        B.halo_grew = false;
        B.searched  = false; // the build covers every sphere
        B.has_grid  = false;
        // The spheres of the build: rows and halo; the rows of the list
        // being replaced.
        const std::size_t old_b = B.row_sphere_begin, old_e = B.row_sphere_end;
        B.row_sphere_begin = local_index(B.row_begin, 0);
        B.row_sphere_end   = local_index(B.row_end, 0);
        B.halo_sphere_end  = local_index(B.halo_end, 0);
        rebuilt_rows += B.row_sphere_end - B.row_sphere_begin;
        const std::size_t sb = B.row_sphere_begin, se = B.halo_sphere_end,
                          n_build = se - sb;
        const double cut2         = cutoff * cutoff;
        // Bins along x over the spheres of the block (owned and ghosts).
        double xmin = infinity, xmax = -infinity;
        for (std::size_t i = sb; i < se; ++i)
          {
            xmin = std::min(xmin, pos[3 * i]);
            xmax = std::max(xmax, pos[3 * i]);
          }
        const double bin_h = cutoff;
        B.n_bins = static_cast<unsigned int>((xmax - xmin) / bin_h) + 1;
        const unsigned int n_bins             = B.n_bins;
        std::vector<std::uint32_t> &bin_count = B.bin_count;
        bin_count.assign(n_bins, 0);
        B.bin_mean_displacement.assign(3 * n_bins, 0.);
        B.bin_displacement_sum.assign(3 * n_bins, 0.);
        B.r2_max = 0.;
        B.bin_of.resize(n_build);
        B.pos_build.resize(3 * n_build);
        const auto bin_of = [&](const std::size_t i) -> std::uint32_t & {
          return B.bin_of[i - sb];
        };
        for (std::size_t i = sb; i < se; ++i)
          {
            const auto b =
              std::min<std::uint32_t>(static_cast<std::uint32_t>(
                                        (pos[3 * i] - xmin) / bin_h),
                                      n_bins - 1);
            bin_of(i) = b;
            ++bin_count[b];
            for (unsigned int c = 0; c < 3; ++c)
              B.pos_build[3 * (i - sb) + c] =
                static_cast<float>(pos[3 * i + c]);
          }
        bin_start.assign(n_bins + 1, 0);
        for (unsigned int b = 0; b < n_bins; ++b)
          bin_start[b + 1] = bin_start[b] + bin_count[b];
        bin_sphere.resize(n_build);
        {
          std::vector<std::uint32_t> &fill = cell_sphere; // scratch
          fill.assign(bin_start.begin(), bin_start.end() - 1);
          for (std::size_t i = sb; i < se; ++i)
            bin_sphere[fill[bin_of(i)]++] = i;
        }
        // A 2D (y, z) cell grid in each bin, cells no smaller than the
        // cut-off, so a 3x3 block of cells holds every partner.
        bin_y0.resize(n_bins);
        bin_z0.resize(n_bins);
        bin_ic.resize(n_bins);
        bin_ny.resize(n_bins);
        bin_nz.resize(n_bins);
        cell_off.assign(n_bins + 1, 0);
        for (unsigned int b = 0; b < n_bins; ++b)
          {
            double y0 = infinity, y1 = -infinity, z0 = infinity, z1 = -infinity;
            for (std::uint32_t k = bin_start[b]; k < bin_start[b + 1]; ++k)
              {
                const std::size_t i = bin_sphere[k];
                y0                  = std::min(y0, pos[3 * i + 1]);
                y1                  = std::max(y1, pos[3 * i + 1]);
                z0                  = std::min(z0, pos[3 * i + 2]);
                z1                  = std::max(z1, pos[3 * i + 2]);
              }
            double c = cutoff;
            if (bin_count[b] == 0)
              y0 = y1 = z0 = z1 = 0.;
            // Limit the cells per bin (a far-flung sphere must not blow up
            // the grid).
            while ((y1 - y0) / c * (z1 - z0) / c > 16. * bin_count[b] + 64.)
              c *= 2.;
            bin_y0[b]       = y0;
            bin_z0[b]       = z0;
            bin_ic[b]       = 1. / c;
            bin_ny[b]       = static_cast<std::uint32_t>((y1 - y0) / c) + 1;
            bin_nz[b]       = static_cast<std::uint32_t>((z1 - z0) / c) + 1;
            cell_off[b + 1] = cell_off[b] + bin_ny[b] * bin_nz[b];
          }
        const std::uint32_t n_cells         = cell_off[n_bins];
        std::vector<std::uint32_t> &cell_of = near_sphere; // scratch
        cell_of.resize(n_build);
        cell_start.assign(n_cells + 1, 0);
        for (std::size_t i = sb; i < se; ++i)
          {
            const std::uint32_t b = bin_of(i);
            const auto cy         = static_cast<std::uint32_t>(
              (pos[3 * i + 1] - bin_y0[b]) * bin_ic[b]);
            const auto cz = static_cast<std::uint32_t>(
              (pos[3 * i + 2] - bin_z0[b]) * bin_ic[b]);
            const std::uint32_t c = cell_off[b] +
                                    std::min(cy, bin_ny[b] - 1) * bin_nz[b] +
                                    std::min(cz, bin_nz[b] - 1);
            cell_of[i - sb] = c;
            ++cell_start[c + 1];
          }
        for (std::uint32_t c = 0; c < n_cells; ++c)
          cell_start[c + 1] += cell_start[c];
        cell_sphere.resize(n_build);
        {
          std::vector<std::uint32_t> fill(cell_start.begin(),
                                          cell_start.end() - 1);
          for (std::size_t i = sb; i < se; ++i)
            cell_sphere[fill[cell_of[i - sb]]++] = i;
        }

        // Candidate pairs: same bin (j > i) and next bin. The positions are
        // copied in cell order, so that the three cells of a row of the
        // 3 x 3 block are one contiguous run, in single precision relative
        // to the build's origin for the vectorised filter (most candidates
        // fail it; its radius is enlarged by the rounding bound) and in
        // double for the exact test of the survivors.
        const std::size_t n_cand = cell_sphere.size();
        cell_x.resize(n_cand);
        cell_y.resize(n_cand);
        cell_z.resize(n_cand);
        cell_xf.resize(n_cand + 8);
        cell_yf.resize(n_cand + 8);
        cell_zf.resize(n_cand + 8);
        double magnitude = xmax - xmin;
        for (std::size_t k = 0; k < n_cand; ++k)
          {
            const std::size_t j = cell_sphere[k];
            cell_x[k]           = pos[3 * j];
            cell_y[k]           = pos[3 * j + 1];
            cell_z[k]           = pos[3 * j + 2];
            cell_xf[k]          = static_cast<float>(pos[3 * j] - xmin);
            cell_yf[k]          = static_cast<float>(pos[3 * j + 1]);
            cell_zf[k]          = static_cast<float>(pos[3 * j + 2]);
            magnitude           = std::max(magnitude,
                                 std::max(std::abs(pos[3 * j + 1]),
                                          std::abs(pos[3 * j + 2])));
          }
        for (std::size_t k = n_cand; k < n_cand + 8; ++k)
          cell_xf[k] = cell_yf[k] = cell_zf[k] = 0.f;
        const float r2_f        = filter_radius2(cutoff, magnitude);
        const NearInRuns filter = near_in_runs_for_this_cpu();
        candidate_k.resize(n_cand);
        // A sphere searches only the cells that hold a sphere it can be
        // listed with: an owned one if it is a ghost, one of the rows if it
        // is in the halo, an owned one of the rows if both (after fibres
        // were cut and slid, the ghost layers and halos are whole slabs, but
        // few of their spheres are near an owned one or one of the rows).
        const std::size_t row_e = B.row_sphere_end;
        cell_partners.assign(n_cells, 0);
        for (std::size_t i = sb; i < se; ++i)
          cell_partners[cell_of[i - sb]] |= (owned(i) ? 1 : 0) |
                                            (i < row_e ? 2 : 0) |
                                            (owned(i) && i < row_e ? 4 : 0);
        // The flags of the cells c0 to c1 (of one row).
        const auto flags = [&](const std::uint32_t c0, const std::uint32_t c1) {
          std::uint8_t f = 0;
          for (std::uint32_t c = c0; c <= c1; ++c)
            f |= cell_partners[c];
          return f;
        };
        // The spheres are searched in cell order: each pair is tested once.
        // In its own bin a sphere looks only forward in that order (the
        // rest of its cell, the next cell of its row, the next row's three
        // cells: the half of the 3 x 3 block after it); in the next bin at
        // the whole 3 x 3 block; pairs with the previous bin are found from
        // there. The lists do not depend on the order of the search (rows
        // are sorted by j below).
        found.clear();
        for (std::uint32_t b = 0; b < n_bins; ++b)
          for (std::uint32_t a = 0; a < bin_ny[b]; ++a)
            for (std::uint32_t cz = 0; cz < bin_nz[b]; ++cz)
              {
                const std::uint32_t nz   = bin_nz[b];
                const std::uint32_t cell = cell_off[b] + a * nz + cz;
                const std::uint32_t k_c0 = cell_start[cell],
                                    k_c1 = cell_start[cell + 1];
                if (k_c0 == k_c1)
                  continue;
                // Same bin: the run from this cell to the next one of the
                // row, and the run of the next row.
                const std::uint32_t row_last =
                  cell_off[b] + a * nz + std::min(cz + 1, nz - 1);
                const std::uint32_t k_row_end = cell_start[row_last + 1];
                const std::uint8_t row_flags  = flags(cell, row_last);
                CandidateRun next_row         = {0, 0};
                std::uint8_t next_row_flags   = 0;
                if (a + 1 < bin_ny[b])
                  {
                    const std::uint32_t row = cell_off[b] + (a + 1) * nz;
                    const std::uint32_t c0  = row + (cz > 0 ? cz - 1 : 0),
                                        c1  = row + std::min(cz + 1, nz - 1);
                    next_row       = {cell_start[c0], cell_start[c1 + 1]};
                    next_row_flags = flags(c0, c1);
                  }
                for (std::uint32_t k_i = k_c0; k_i < k_c1; ++k_i)
                  {
                    const std::size_t i = cell_sphere[k_i];
                    const bool i_owned  = owned(i);
                    const std::uint8_t need =
                      (i_owned ? (i < row_e ? 0 : 2) : (i < row_e ? 1 : 4));
                    // A run without a sphere i can be listed with is left
                    // out (need = 0: an owned sphere of the rows can be
                    // listed with any; a cell of ghosts of the halo has no
                    // flag).
                    const auto wanted = [need](const std::uint8_t f) {
                      return need == 0 || (f & need) != 0;
                    };
                    const double x_i = cell_x[k_i], y_i = cell_y[k_i],
                                 z_i = cell_z[k_i];
                    CandidateRun runs[5];
                    unsigned int n_runs = 0;
                    if (wanted(row_flags))
                      runs[n_runs++] = {k_i + 1, k_row_end};
                    if (next_row.k1 > next_row.k0 && wanted(next_row_flags))
                      runs[n_runs++] = next_row;
                    // Next bin: the rows of the 3 x 3 block.
                    const std::uint32_t bb = b + 1;
                    if (bb < n_bins && bin_count[bb] > 0)
                      {
                        const long cy = static_cast<long>(
                          std::floor((y_i - bin_y0[bb]) * bin_ic[bb]));
                        const long cz_ = static_cast<long>(
                          std::floor((z_i - bin_z0[bb]) * bin_ic[bb]));
                        const long ny = bin_ny[bb], nz_ = bin_nz[bb];
                        const long c0 = std::max(0l, cz_ - 1),
                                   c1 = std::min(nz_ - 1, cz_ + 1);
                        if (c0 <= c1)
                          for (long r = std::max(0l, cy - 1);
                               r <= std::min(ny - 1, cy + 1);
                               ++r)
                            {
                              const std::uint32_t row = cell_off[bb] + r * nz_;
                              if (wanted(flags(row + c0, row + c1)))
                                runs[n_runs++] = {cell_start[row + c0],
                                                  cell_start[row + c1 + 1]};
                            }
                      }
                    if (n_runs == 0)
                      continue;
                    ++n_searched;
                    for (unsigned int r = 0; r < n_runs; ++r)
                      n_candidates += runs[r].k1 - runs[r].k0;
                    const std::uint32_t *const k_end =
                      filter(cell_xf.data(),
                             cell_yf.data(),
                             cell_zf.data(),
                             runs,
                             n_runs,
                             cell_xf[k_i],
                             cell_yf[k_i],
                             cell_zf[k_i],
                             r2_f,
                             candidate_k.data());
                    for (const std::uint32_t *q = candidate_k.data();
                         q != k_end;
                         ++q)
                      {
                        const std::uint32_t k = *q;
                        const double ex = x_i - cell_x[k], ey = y_i - cell_y[k],
                                     ez = z_i - cell_z[k];
                        if (ex * ex + ey * ey + ez * ez >= cut2)
                          continue;
                        const std::size_t j = cell_sphere[k];
                        if ((!i_owned && !owned(j)) || j == i + nf ||
                            j + nf == i ||              // chain neighbours
                            (i >= row_e && j >= row_e)) // a later block's
                          continue;
                        found.emplace_back(std::min<std::size_t>(i, j),
                                           std::max<std::size_t>(i, j));
                      }
                  }
              }

        // New CSR list, rows sorted by j; carry the tangential history of
        // pairs that stay listed.
        std::vector<std::uint32_t> &pstart     = B.pstart,
                                   &pstart_old = B.pstart_old;
        std::vector<Pair> &pairs = B.pairs, &pairs_old = B.pairs_old;
        std::vector<double> &pair_tangential_displacement =
                              B.pair_tangential_displacement,
                            &pair_tangential_displacement_old =
                              B.pair_tangential_displacement_old;
        std::swap(pstart, pstart_old);
        std::swap(pairs, pairs_old);
        std::swap(pair_tangential_displacement,
                  pair_tangential_displacement_old);
        const std::size_t n_rows = B.row_sphere_end - B.row_sphere_begin;
        pstart.assign(n_rows + 1, 0);
        for (const auto &p : found)
          ++pstart[p.first - sb + 1];
        for (std::size_t r = 0; r < n_rows; ++r)
          pstart[r + 1] += pstart[r];
        pairs.resize(found.size());
        pair_tangential_displacement.assign(3 * found.size(), 0.);
        {
          std::vector<std::uint32_t> &fill = cell_of; // scratch again
          fill.assign(pstart.begin(), pstart.end() - 1);
          for (const auto &p : found)
            pairs[fill[p.first - sb]++] = {p.second, 1.f};
        }
        const bool have_old = pstart_old.size() == old_e - old_b + 1;
        for (std::size_t i = B.row_sphere_begin; i < B.row_sphere_end; ++i)
          {
            Pair *row             = pairs.data() + pstart[i - sb];
            const std::uint32_t n = pstart[i - sb + 1] - pstart[i - sb];
            std::sort(row, row + n, [](const Pair &a, const Pair &b) {
              return a.j < b.j;
            });
            if (x_sym && lo == 0 && i < nf)
              for (std::uint32_t k = 0; k < n; ++k)
                if (row[k].j < nf)
                  row[k].w *= 0.5f; // both on the plane x = 0
            if (z_sym && zmask[i % nf] == 0.)
              for (std::uint32_t k = 0; k < n; ++k)
                if (zmask[row[k].j % nf] == 0.)
                  row[k].w *= 0.5f; // both on the plane z = 0
            // A coupling's particle weight: the mean of the two stations'.
            if (chains.coupled)
              for (std::uint32_t k = 0; k < n; ++k)
                row[k].w *=
                  static_cast<float>(0.5 * (chains.cw[station_of(i)] +
                                            chains.cw[station_of(row[k].j)]));
            if (!have_old || i < old_b || i >= old_e)
              continue;
            // Merge with the old row.
            std::uint32_t q     = pstart_old[i - old_b],
                          q_end = pstart_old[i - old_b + 1];
            for (std::uint32_t k = 0; k < n; ++k)
              {
                while (q < q_end && pairs_old[q].j < row[k].j)
                  ++q;
                if (q < q_end && pairs_old[q].j == row[k].j &&
                    pairs_old[q].w < 0.f)
                  {
                    row[k].w            = -row[k].w;
                    const std::size_t p = pstart[i - sb] + k;
                    for (unsigned int c = 0; c < 3; ++c)
                      pair_tangential_displacement[3 * p + c] =
                        pair_tangential_displacement_old[3 * q + c];
                  }
              }
          }

        // Mirror pairs: spheres with the image of another one, or of
        // themselves, in the symmetry planes (doc/dem.md section 4: the
        // candidates below are every pair whose image distance can drop
        // below d while the criterion holds).
        std::vector<MirrorPair> &mpairs = B.mpairs, &mpairs_old = B.mpairs_old;
        std::vector<double> &mirror_tangential_displacement =
                              B.mirror_tangential_displacement,
                            &mirror_tangential_displacement_old =
                              B.mirror_tangential_displacement_old;
        std::swap(mpairs, mpairs_old);
        std::swap(mirror_tangential_displacement,
                  mirror_tangential_displacement_old);
        mpairs.clear();
        // Pairs in z = 0 belong to the block of the lower index; pairs in
        // x = 0 all to the block holding the plane, whose build holds every
        // sphere that can come near the plane.
        const auto add_mirror = [&](const std::size_t i,
                                    const std::size_t j,
                                    const std::uint8_t axes,
                                    const double w) {
          add_mirror_pair_if_near(i,
                                  j,
                                  axes,
                                  w,
                                  pos.data(),
                                  cut2,
                                  row_e,
                                  owned,
                                  mpairs);
        };
        // In z = 0 (quarter): spheres off that plane within the cut-off of
        // it, in the same or the next bin.
        if (z_sym)
          {
            near_sphere.clear(); // cell_of no longer needed
            for (std::uint32_t k = 0; k < bin_sphere.size(); ++k)
              {
                const std::size_t i = bin_sphere[k];
                if (zmask[i % nf] != 0. && pos[3 * i + 2] < cutoff)
                  near_sphere.push_back(i);
              }
            // near_sphere is ordered by bin.
            for (std::size_t a = 0; a < near_sphere.size(); ++a)
              for (std::size_t c = a; c < near_sphere.size(); ++c)
                {
                  const std::size_t i = near_sphere[a], j = near_sphere[c];
                  if (bin_of(j) > bin_of(i) + 1)
                    break;
                  add_mirror(i,
                             j,
                             2,
                             x_sym && station_of(i) == 0 && station_of(j) == 0
                               ? 0.5
                               : 1.);
                }
          }
        // In x = 0 (half, quarter; only the block holding the plane, whose
        // bin 0 starts at x = 0): spheres off that plane in bins 0 and 1,
        // every pair; with quarter symmetry also the images in both planes
        // of spheres off both planes and within the cut-off of z = 0. An
        // image distance below the cut-off needs x_i + x_j < h, so only
        // bin 0 can contribute, and |y_i - y_j| < cut-off: the candidates
        // are swept in order of y (thousands of spheres gather at the plane
        // once the fibres are cut there).
        if (B.holds_plane)
          {
            near_x.clear();
            const std::uint32_t k_end = bin_start[std::min(1u, n_bins)];
            for (std::uint32_t k = 0; k < k_end; ++k)
              if (bin_sphere[k] >= nf)
                near_x.push_back(bin_sphere[k]);
            std::sort(near_x.begin(),
                      near_x.end(),
                      [&](const std::uint32_t a, const std::uint32_t b) {
                        return pos[3 * a + 1] < pos[3 * b + 1];
                      });
            for (std::size_t a = 0; a < near_x.size(); ++a)
              for (std::size_t c = a;
                   c < near_x.size() &&
                   pos[3 * near_x[c] + 1] < pos[3 * near_x[a] + 1] + cutoff;
                   ++c)
                {
                  const std::size_t i = near_x[a], j = near_x[c];
                  const bool zi = z_sym && zmask[i % nf] == 0.,
                             zj = z_sym && zmask[j % nf] == 0.;
                  add_mirror(i, j, 1, zi && zj ? 0.5 : 1.);
                  if (z_sym && !zi && !zj && pos[3 * i + 2] < cutoff &&
                      pos[3 * j + 2] < cutoff)
                    add_mirror(i, j, 3, 1.);
                }
          }
        std::sort(mpairs.begin(), mpairs.end(), mirror_less);
        mirror_tangential_displacement.assign(3 * mpairs.size(), 0.);
        std::size_t q = 0;
        for (std::size_t p = 0; p < mpairs.size(); ++p)
          {
            while (q < mpairs_old.size() &&
                   mirror_less(mpairs_old[q], mpairs[p]))
              ++q;
            if (q < mpairs_old.size() && mpairs_old[q].i == mpairs[p].i &&
                mpairs_old[q].j == mpairs[p].j &&
                mpairs_old[q].axes == mpairs[p].axes && mpairs_old[q].active)
              {
                mpairs[p].active = true;
                for (unsigned int c = 0; c < 3; ++c)
                  mirror_tangential_displacement[3 * p + c] =
                    mirror_tangential_displacement_old[3 * q + c];
              }
          }

        // The partial searches look up the spheres that are not fast in
        // this build's cell grid: the block keeps it (exchanged with the
        // scratch, not copied).
        if (prm.partial_search_fraction > 0.)
          {
            B.grid_x0      = xmin;
            B.grid_x_slack = 0.;
            std::swap(B.grid_y0, bin_y0);
            std::swap(B.grid_z0, bin_z0);
            std::swap(B.grid_ic, bin_ic);
            std::swap(B.grid_ny, bin_ny);
            std::swap(B.grid_nz, bin_nz);
            std::swap(B.grid_cell_off, cell_off);
            std::swap(B.grid_cell_start, cell_start);
            std::swap(B.grid_cell_sphere, cell_sphere);
            B.has_grid = true;
          }
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
