// The neighbour-list blocks of the DEM impact model: their ranges, halos,
// rebuild criterion and which blocks are rebuilt when (doc/dem.md
// section 4). The build itself is in list_build.cc.

#include <yarn_impact/dem/neighbour_lists.h>

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

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


      NeighbourLists::NeighbourLists(
        const Parameters &prm,
        const YarnImpact::Parameters::Shared &shared,
        const FibreChains &chains,
        const Decomposition &decomposition,
        const std::vector<double> &pos)
        : prm(prm)
        , chains(chains)
        , decomposition(decomposition)
        , pos(pos)
        , length(shared.yarn.length)
        , cutoff(chains.d + prm.skin)
      {
        // List blocks over the storage cross-sections.
        const unsigned int K  = prm.list_block;
        const unsigned int lo = decomposition.lo, hi = decomposition.hi;
        for (unsigned int s = lo; s < hi; s += K)
          {
            ListBlock B;
            B.s_begin = s;
            B.s_end   = std::min(hi, s + K);
            for (unsigned int t = B.s_begin; t < B.s_end; ++t)
              station_block.push_back(blocks.size());
            blocks.push_back(std::move(B));
          }
        set_block_ranges();
      }


      unsigned long
      NeighbourLists::n_listed_pairs() const
      {
        unsigned long n = 0;
        for (const ListBlock &B : blocks)
          n += B.pairs.size();
        return n;
      }


      void
      NeighbourLists::set_block_ranges()
      {
        // Rows: the active part of each block. Halo: at least the next
        // `Ghost stations` cross-sections (more after a growth), within the
        // active range. Every block is rebuilt after this.
        const unsigned int g_lo = decomposition.g_lo, g_hi = decomposition.g_hi;
        for (ListBlock &B : blocks)
          {
            B.row_begin   = std::max(B.s_begin, g_lo);
            B.row_end     = std::min(B.s_end, g_hi);
            B.holds_plane = chains.x_sym && B.row_begin == 0 && B.active();
            if (!B.active())
              {
                B.row_end  = B.row_begin;
                B.halo_end = B.row_begin;
                continue;
              }
            B.halo_end =
              std::min(g_hi,
                       std::max(B.halo_end, B.row_end + prm.ghost_stations));
            B.stale     = true;
            B.halo_grew = false;
          }
      }


      void
      NeighbourLists::grow_halos(const std::vector<double> &lo_x,
                                 const std::vector<double> &hi_x)
      {
        // Cross-sections below the rows list their pairs with the rows in
        // their own block; for those above, the same argument as for the
        // ghost layers (Decomposition::grow_ghost_layers()), with two more.
        const double reach      = chains.d + chains.L0;
        const unsigned int g_hi = decomposition.g_hi;
        for (ListBlock &B : blocks)
          {
            if (!B.active())
              continue;
            double Xlo = infinity, Xhi = -infinity;
            for (unsigned int s = B.row_begin; s < B.row_end; ++s)
              {
                Xlo = std::min(Xlo, lo_x[s]);
                Xhi = std::max(Xhi, hi_x[s]);
              }
            for (unsigned int t = B.halo_end; t < g_hi; ++t)
              if (!(lo_x[t] > Xhi + reach || hi_x[t] < Xlo - reach))
                {
                  B.halo_end  = std::min(g_hi, t + 3);
                  B.halo_grew = !B.stale || B.halo_grew;
                  B.stale     = true;
                }
            // A block whose halo covers the next block takes it over: its
            // criterion already follows those spheres, so the other block's
            // own lists would only be rebuilt as often at extra cost (after
            // fibres were cut and slid, halos span many blocks).
            for (ListBlock *C = &B + 1; C < blocks.data() + blocks.size(); ++C)
              {
                if (C->s_begin == C->s_end)
                  continue; // taken over before
                if (!C->active() || B.halo_end < C->row_end)
                  break;
                absorb(B, *C);
              }
          }
      }


      void
      NeighbourLists::accumulate_ghost_criteria()
      {
        const double *x = pos.data();
        for (std::size_t i = decomposition.act_b; i < decomposition.own_b; ++i)
          accumulate_criterion(block_of(i), x, i);
        for (std::size_t i = decomposition.own_e; i < decomposition.act_e; ++i)
          accumulate_criterion(block_of(i), x, i);
        for (ListBlock &B : blocks)
          for (std::size_t i = B.row_sphere_end; i < B.halo_sphere_end; ++i)
            accumulate_criterion(B, x, i);
      }


      double
      NeighbourLists::bin_terms(const unsigned int n_bins,
                                const std::vector<std::uint32_t> &count,
                                const std::vector<double> &mean,
                                double &dz)
      {
        double g = 0.;
        dz       = 0.;
        int prev = -1;
        for (unsigned int b = 0; b < n_bins; ++b)
          {
            if (count[b] == 0)
              continue;
            if (prev >= 0)
              {
                const double ex = mean[3 * b] - mean[3 * prev];
                const double ey = mean[3 * b + 1] - mean[3 * prev + 1];
                const double ez = mean[3 * b + 2] - mean[3 * prev + 2];
                g = std::max(g, std::sqrt(ex * ex + ey * ey + ez * ez));
              }
            dz   = std::max(dz, std::abs(mean[3 * b + 2]));
            prev = b;
          }
        return g;
      }


      double
      NeighbourLists::list_bound(ListBlock &B)
      {
        // Criterion (doc/dem.md, "Neighbour lists"): with D_b the reference
        // displacement of build bin b (bin_mean_displacement),
        // r = max |Delta_i - D_b(i)| and
        // g = max |D_{b+1} - D_b| over consecutive non-empty bins, no
        // unlisted pair can touch while 2 r + 2 g (+ 2 max|D_b,z| for mirror
        // pairs in z = 0, + 2 |D_0,x| for mirror pairs in x = 0) < skin.
        // After a partial search the spheres it searched are left out of
        // r, g and the references, and the pairs with one of them are
        // bounded in the same way from the positions of that search, with
        // r_all + r_fast in place of 2 r.
        double dz = 0.;
        const double g =
          bin_terms(B.n_bins, B.bin_count, B.bin_mean_displacement, dz);
        // Rounding of the single-precision build positions.
        const double margin = 8. * 6e-8 * length;
        last_r              = std::max(last_r, std::sqrt(B.r2_max));
        last_g              = std::max(last_g, g);
        // Mirror pairs in x = 0: 2 |D_0,x| of bin 0 (which starts at x = 0).
        const double dx0 =
          (B.holds_plane && B.n_bins > 0 ? std::abs(B.bin_mean_displacement[0])
                                         : 0.);
        double bound = 2. * std::sqrt(B.r2_max) + 2. * g +
                       (chains.z_sym ? 2. * dz : 0.) + 2. * dx0 + margin;
        // New reference: the mean displacement of each bin.
        for (unsigned int b = 0; b < B.n_bins; ++b)
          if (B.bin_count[b] > 0)
            for (unsigned int c = 0; c < 3; ++c)
              B.bin_mean_displacement[3 * b + c] =
                B.bin_displacement_sum[3 * b + c] / B.bin_count[b];
        std::fill(B.bin_displacement_sum.begin(),
                  B.bin_displacement_sum.end(),
                  0.);
        B.r2_max = 0.;
        if (!B.searched)
          return bound;

        double dz_s        = 0.;
        const double g_s   = bin_terms(B.n_bins_search,
                                     B.bin_count_search,
                                     B.search_mean_displacement,
                                     dz_s);
        const double dx0_s = (B.holds_plane && B.n_bins_search > 0
                                ? std::abs(B.search_mean_displacement[0])
                                : 0.);
        bound              = std::max(bound,
                         std::sqrt(B.r2_search) + std::sqrt(B.r2_search_fast) +
                           2. * g_s + (chains.z_sym ? 2. * dz_s : 0.) +
                           2. * dx0_s + margin);
        for (unsigned int b = 0; b < B.n_bins_search; ++b)
          if (B.bin_count_search[b] > 0)
            for (unsigned int c = 0; c < 3; ++c)
              B.search_mean_displacement[3 * b + c] =
                B.search_displacement_sum[3 * b + c] / B.bin_count_search[b];
        std::fill(B.search_displacement_sum.begin(),
                  B.search_displacement_sum.end(),
                  0.);
        B.r2_search = B.r2_search_fast = 0.;
        return bound;
      }


      void
      NeighbourLists::absorb(ListBlock &B, ListBlock &C)
      {
        // C's rows follow B's: its lists append to B's, with their
        // tangential history, and B is rebuilt from them.
        AssertThrow(B.row_sphere_end == C.row_sphere_begin,
                    dealii::ExcInternalError());
        const auto offset = static_cast<std::uint32_t>(B.pairs.size());
        for (std::size_t r = 1; r < C.pstart.size(); ++r)
          B.pstart.push_back(C.pstart[r] + offset);
        B.pairs.insert(B.pairs.end(), C.pairs.begin(), C.pairs.end());
        B.pair_tangential_displacement.insert(
          B.pair_tangential_displacement.end(),
          C.pair_tangential_displacement.begin(),
          C.pair_tangential_displacement.end());
        if (!C.mpairs.empty())
          {
            std::vector<std::size_t> order(B.mpairs.size() + C.mpairs.size());
            std::vector<MirrorPair> mp(B.mpairs);
            mp.insert(mp.end(), C.mpairs.begin(), C.mpairs.end());
            std::vector<double> merged_xi_t(B.mirror_tangential_displacement);
            merged_xi_t.insert(merged_xi_t.end(),
                               C.mirror_tangential_displacement.begin(),
                               C.mirror_tangential_displacement.end());
            for (std::size_t k = 0; k < order.size(); ++k)
              order[k] = k;
            std::sort(order.begin(),
                      order.end(),
                      [&](const std::size_t a, const std::size_t b) {
                        return mirror_less(mp[a], mp[b]);
                      });
            B.mpairs.resize(order.size());
            B.mirror_tangential_displacement.resize(3 * order.size());
            for (std::size_t k = 0; k < order.size(); ++k)
              {
                B.mpairs[k] = mp[order[k]];
                for (unsigned int c = 0; c < 3; ++c)
                  B.mirror_tangential_displacement[3 * k + c] =
                    merged_xi_t[3 * order[k] + c];
              }
          }
        B.row_sphere_end      = C.row_sphere_end;
        B.s_end               = C.s_end;
        B.row_end             = C.row_end;
        B.halo_end            = std::max(B.halo_end, C.halo_end);
        B.stale               = true;
        B.halo_grew           = false;
        const unsigned int lo = decomposition.lo;
        for (unsigned int t = C.s_begin; t < C.s_end; ++t)
          station_block[t - lo] = station_block[B.s_begin - lo];
        C         = ListBlock();
        C.s_begin = C.s_end = B.s_end;
      }


      bool
      NeighbourLists::evaluate_criteria(const bool check_criterion)
      {
        // The criterion is evaluated for every block, also a stale one: it
        // moves the reference displacements on.
        last_r = last_g  = 0.;
        int must_rebuild = 0;
        for (ListBlock &B : blocks)
          if (B.active())
            {
              B.bound = (check_criterion ? list_bound(B) : 0.);
              must_rebuild |= (B.stale || !(B.bound < prm.skin));
            }
        return must_rebuild != 0;
      }


      void
      NeighbourLists::rebuild_failing(const bool must_rebuild,
                                      const bool check_criterion)
      {
        // A rank's rebuild stalls the others (every step ends in a
        // collective): when any rank must rebuild, the others rebuild their
        // blocks that would fail soon in the same step.
        double joint_bound = infinity;
        if (decomposition.n_ranks > 1 && check_criterion &&
            prm.joint_rebuild_fraction < 1.)
          {
            int any = must_rebuild ? 1 : 0;
            MPI_Allreduce(MPI_IN_PLACE,
                          &any,
                          1,
                          MPI_INT,
                          MPI_LOR,
                          decomposition.comm);
            if (any)
              joint_bound = prm.joint_rebuild_fraction * prm.skin;
          }
        for (ListBlock &B : blocks)
          if (B.active() &&
              (B.stale || !(B.bound < prm.skin) || B.bound >= joint_bound) &&
              !search_fast(B))
            rebuild(B);
      }


      std::string
      NeighbourLists::statistics(const std::uint64_t step_count) const
      {
        // Collective: every rank's rebuilds and pairs. Rebuilds are
        // counted per block and in whole-rank equivalents (rebuilt rows
        // divided by the rows of the rank).
        const unsigned int n_ranks = decomposition.n_ranks;
        std::vector<unsigned long> counts(3 * n_ranks, 0);
        const unsigned long n_pairs = n_listed_pairs();
        unsigned long n_rows        = 0;
        for (const ListBlock &B : blocks)
          n_rows += B.row_sphere_end - B.row_sphere_begin;
        const unsigned long mine[3] = {n_rebuilds,
                                       (rebuilt_rows + n_rows / 2) /
                                         std::max(1ul, n_rows),
                                       n_pairs};
        MPI_Allgather(mine,
                      3,
                      MPI_UNSIGNED_LONG,
                      counts.data(),
                      3,
                      MPI_UNSIGNED_LONG,
                      decomposition.comm);
        std::ostringstream s;
        s << step_count << " force evaluations; block rebuilds, in whole-"
          << "rank equivalents (listed pairs), per rank:";
        for (unsigned int q = 0; q < n_ranks; ++q)
          s << " " << counts[3 * q] << ", " << counts[3 * q + 1] << " ("
            << counts[3 * q + 2] << ")";
        s << "; rank " << decomposition.rank << " last bound terms r " << last_r
          << " g " << last_g << " m, candidates per searched sphere "
          << static_cast<double>(n_candidates) / std::max(1ul, n_searched);
        return s.str();
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
