#ifndef yarn_impact_dem_neighbour_lists_h
#define yarn_impact_dem_neighbour_lists_h

#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/dem/decomposition.h>
#include <yarn_impact/dem/fibre_chains.h>
#include <yarn_impact/dem/parameters.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      /** A listed sphere pair (partner j of the row's sphere); a negative
       * weight marks an active contact (one with tangential history). The
       * weight [-] is 1/2 for a pair of spheres both on a symmetry plane. */
      struct Pair
      {
        std::uint32_t j;
        float w;
      };

      /** A pair of a sphere with the mirror image of another one, or of
       * itself: in x = 0 (half and quarter symmetry, axes bit 1), in z = 0
       * (quarter, bit 2) or in both (quarter, bits 1 | 2). The image of j is
       * (sx x_j, y_j, sz z_j) with sx = -1 for bit 1 and sz = -1 for bit 2.
       */
      struct MirrorPair
      {
        std::uint32_t i, j;
        float w;
        std::uint8_t axes;
        bool active;
      };

      /** The order of the mirror pairs of a block (by i, j, axes). */
      inline bool
      mirror_less(const MirrorPair &a, const MirrorPair &b)
      {
        return a.i < b.i ||
               (a.i == b.i && (a.j < b.j || (a.j == b.j && a.axes < b.axes)));
      }

      /** The rule of the list builds for a mirror pair candidate (i, j,
       * axes) of weight w [-]: kept, as (min, max), when one of i and j is
       * owned, when a pair in z = 0 only (axes without bit 1) has its
       * lower index below row_end (such pairs belong to the block of the
       * lower index), and when the sphere i and the image of j are closer
       * than the cut-off, cut2 its square [m^2]. x holds the positions
       * [m], 3 per sphere. */
      template <typename Owned>
      inline void
      add_mirror_pair_if_near(const std::size_t i,
                              const std::size_t j,
                              const std::uint8_t axes,
                              const double w,
                              const double *x,
                              const double cut2,
                              const std::size_t row_end,
                              const Owned &owned,
                              std::vector<MirrorPair> &pairs)
      {
        if ((!owned(i) && !owned(j)) ||
            (!(axes & 1) && std::min(i, j) >= row_end))
          return;
        const double sx = (axes & 1) ? -1. : 1., sz = (axes & 2) ? -1. : 1.;
        const double ex = x[3 * i] - sx * x[3 * j],
                     ey = x[3 * i + 1] - x[3 * j + 1],
                     ez = x[3 * i + 2] - sz * x[3 * j + 2];
        if (ex * ex + ey * ey + ez * ez < cut2)
          pairs.push_back({static_cast<std::uint32_t>(std::min(i, j)),
                           static_cast<std::uint32_t>(std::max(i, j)),
                           static_cast<float>(w),
                           axes,
                           false});
      }


      /** The neighbour list of a block of consecutive cross-sections of a
       * rank (doc/dem.md section 4): the pairs whose lower sphere index is
       * in the block's rows, found among the rows and a halo of the
       * following cross-sections, and the rebuild criterion of these
       * spheres. A block is rebuilt on its own when its criterion fails, so
       * that a few fast spheres under the projectile do not rebuild the
       * lists of the whole slab (on every rank, the others wait for it). */
      struct ListBlock
      {
        /** Storage cross-sections of the block (fixed). */
        unsigned int s_begin = 0, s_end = 0;
        /** Active cross-sections of the rows, and the end of the halo
         * (which grows when other cross-sections come near the rows). */
        unsigned int row_begin = 0, row_end = 0, halo_end = 0;
        /** Local indices of the spheres of the rows, [row_sphere_begin,
         * row_sphere_end), and of the halo, [row_sphere_end,
         * halo_sphere_end), at the last build [-]. */
        std::size_t row_sphere_begin = 0, row_sphere_end = 0,
                    halo_sphere_end = 0;
        /** The cross-sections changed since the last build. */
        bool stale = true;
        /** Stale only because the halo grew: a partial search can take
         * the new halo spheres in as fast ones. */
        bool halo_grew = false;
        /** The rows hold the plane x = 0 (mirror pairs in x). */
        bool holds_plane = false;
        /** Pairs in CSR by the row of the lower index; mirror pairs
         * likewise. The _old arrays hold the previous build's, whose
         * histories a rebuild carries over. */
        std::vector<std::uint32_t> pstart, pstart_old;
        std::vector<Pair> pairs, pairs_old;
        /** Tangential history xi_t of each pair's contact: the elastic
         * tangential displacement of its Cundall-Strack spring [m], 3 per
         * pair (0 while the pair does not touch). */
        std::vector<double> pair_tangential_displacement,
          pair_tangential_displacement_old;
        std::vector<MirrorPair> mpairs, mpairs_old;
        /** The same for each mirror pair (a sphere and its image in x = 0
         * or z = 0) [m], 3 per mirror pair. */
        std::vector<double> mirror_tangential_displacement,
          mirror_tangential_displacement_old;
        /** Build positions [m] and build bins of the spheres
         * [row_sphere_begin, halo_sphere_end). */
        std::vector<float> pos_build;
        std::vector<std::uint32_t> bin_of;
        /** Bins along x of the build (width d + skin, from the lowest
         * sphere) and the number of spheres in each [-]. */
        unsigned int n_bins = 0;
        std::vector<std::uint32_t> bin_count;
        /** Per bin, 3 components: the mean displacement of its spheres
         * since the build, at the last evaluation of the bound (the
         * reference each sphere's displacement is measured from) [m]; and
         * the sum of their displacements that the current step gathers for
         * the next mean [m]. */
        std::vector<double> bin_mean_displacement, bin_displacement_sum;
        /** Largest squared displacement relative to its bin [m^2]. */
        double r2_max = 0.;
        /** The criterion's bound of this step [m]. */
        double bound = 0.;

        /** Partial searches (doc/dem.md section 4): whether one was made
         * since the build; then the spheres of the build searched again
         * (fast, 1 per sphere of [row_sphere_begin, halo_sphere_end)),
         * which the criterion of the build leaves out (bin_count and the
         * reference displacements count only the others), and the
         * criterion of the last partial search: the positions [m] and bins
         * of all the build's spheres then, and the same terms as above
         * with their displacements since then. */
        bool searched = false;
        std::vector<std::uint8_t> fast;
        std::vector<float> pos_search;
        std::vector<std::uint32_t> bin_of_search;
        unsigned int n_bins_search = 0;
        std::vector<std::uint32_t> bin_count_search;
        std::vector<double> search_mean_displacement, search_displacement_sum;
        /** Largest squared displacement relative to its bin since the
         * partial search, over all the spheres and over the fast ones
         * [m^2]. */
        double r2_search = 0., r2_search_fast = 0.;

        /** The (y, z) cell grid of the build's positions, kept for the
         * partial searches, which look up the spheres that are not fast
         * there (shifted by their bin's reference displacement) instead of
         * binning the whole block again: origin of the bins along x [m],
         * per bin the lower corner [m], inverse cell size [1/m] and cell
         * counts, the first cell of each bin, the spheres (local indices)
         * in cell order and where each cell starts among them. Derived
         * data: made by the build, or from the build positions at the
         * first partial search after a restart (has_grid false). */
        bool has_grid = false;
        /** Bin b of the grid spans x from grid_x0 + b h - grid_x_slack to
         * grid_x0 + (b + 1) h [m] (h = d + skin; the slack is 0 after a
         * build, h for a grid made from the build positions). */
        double grid_x0 = 0., grid_x_slack = 0.;
        std::vector<double> grid_y0, grid_z0, grid_ic;
        std::vector<std::uint32_t> grid_ny, grid_nz, grid_cell_off,
          grid_cell_start, grid_cell_sphere;

        /** Whether the block has rows on this rank. */
        bool
        active() const
        {
          return row_end > row_begin;
        }
      };


      /**
       * Add the displacement of sphere @p i (positions @p pos [m]) since the
       * build of block @p B to the block's rebuild criterion. Inline: the
       * drift calls it for every owned sphere.
       */
      template <bool searched>
      inline void
      accumulate_criterion_of(ListBlock &B,
                              const double *pos,
                              const std::size_t i)
      {
        const std::size_t k = i - B.row_sphere_begin;
        if (!searched || !B.fast[k])
          {
            const std::uint32_t b = B.bin_of[k];
            const double dx       = pos[3 * i] - B.pos_build[3 * k];
            const double dy       = pos[3 * i + 1] - B.pos_build[3 * k + 1];
            const double dz       = pos[3 * i + 2] - B.pos_build[3 * k + 2];
            const double rx       = dx - B.bin_mean_displacement[3 * b];
            const double ry       = dy - B.bin_mean_displacement[3 * b + 1];
            const double rz       = dz - B.bin_mean_displacement[3 * b + 2];
            B.r2_max = std::max(B.r2_max, rx * rx + ry * ry + rz * rz);
            B.bin_displacement_sum[3 * b] += dx;
            B.bin_displacement_sum[3 * b + 1] += dy;
            B.bin_displacement_sum[3 * b + 2] += dz;
          }
        if constexpr (!searched)
          return;
        // Since the last partial search: every sphere of the build.
        const std::uint32_t b = B.bin_of_search[k];
        const double dx       = pos[3 * i] - B.pos_search[3 * k];
        const double dy       = pos[3 * i + 1] - B.pos_search[3 * k + 1];
        const double dz       = pos[3 * i + 2] - B.pos_search[3 * k + 2];
        const double rx       = dx - B.search_mean_displacement[3 * b];
        const double ry       = dy - B.search_mean_displacement[3 * b + 1];
        const double rz       = dz - B.search_mean_displacement[3 * b + 2];
        const double r2       = rx * rx + ry * ry + rz * rz;
        B.r2_search           = std::max(B.r2_search, r2);
        if (B.fast[k])
          B.r2_search_fast = std::max(B.r2_search_fast, r2);
        B.search_displacement_sum[3 * b] += dx;
        B.search_displacement_sum[3 * b + 1] += dy;
        B.search_displacement_sum[3 * b + 2] += dz;
      }

      /** accumulate_criterion_of() for a block that a partial search has
       * searched or not: the drift, which calls it for every owned sphere,
       * picks the variant once per cross-section, so that the lists of
       * whole-block builds (the default) cost no test per sphere. */
      inline void
      accumulate_criterion(ListBlock &B, const double *pos, const std::size_t i)
      {
        if (B.searched)
          accumulate_criterion_of<true>(B, pos, i);
        else
          accumulate_criterion_of<false>(B, pos, i);
      }


      /**
       * The Verlet neighbour lists of a rank, in blocks of `DEM/List block`
       * storage cross-sections (doc/dem.md section 4): the blocks, their
       * rebuild criterion and the build (list_build.cc). The lists refer to
       * the positions @p pos given at construction.
       */
      class NeighbourLists
      {
      public:
        /** Blocks over the storage cross-sections of @p decomposition; the
         * first build is left to rebuild(). */
        NeighbourLists(const Parameters &prm,
                       const YarnImpact::Parameters::Shared &shared,
                       const FibreChains &chains,
                       const Decomposition &decomposition,
                       const std::vector<double> &pos);

        /** The block whose storage holds local sphere @p i. */
        ListBlock &
        block_of(const std::size_t i)
        {
          return blocks[station_block[i / chains.nf]];
        }
        /** The block whose storage holds local sphere @p i. */
        const ListBlock &
        block_of(const std::size_t i) const
        {
          return blocks[station_block[i / chains.nf]];
        }

        /** Pairs in the neighbour lists of this rank. */
        unsigned long
        n_listed_pairs() const;

        /** Rows and halos of the blocks after a change of the active range;
         * every block is stale after this. */
        void
        set_block_ranges();

        /**
         * Every cross-section above the rows of a block that comes within
         * d + L0 of their x-range (global extents @p lo_x, @p hi_x [m])
         * joins the block's halo, and the block becomes stale; a block whose
         * halo covers the next block takes it over.
         */
        void
        grow_halos(const std::vector<double> &lo_x,
                   const std::vector<double> &hi_x);

        /** Add the displacements of the ghosts and the halos to the
         * criteria (the owned ones were added during the drift). */
        void
        accumulate_ghost_criteria();

        /**
         * Evaluate the criterion of every active block if
         * @p check_criterion (it moves the reference displacements on;
         * otherwise the bound is 0).
         * @return whether a block is stale or fails its criterion
         */
        bool
        evaluate_criteria(const bool check_criterion);

        /**
         * Rebuild the blocks that are stale or fail their criterion. On
         * several ranks, when @p check_criterion and any rank must rebuild
         * (@p must_rebuild on one of them, collective), also those that
         * used `DEM/Joint rebuild fraction` of the skin.
         */
        void
        rebuild_failing(const bool must_rebuild, const bool check_criterion);

        /** Rebuild the lists of block @p B, carrying the tangential history
         * of the pairs that stay listed (list_build.cc). */
        void
        rebuild(ListBlock &B);

        /**
         * Search again only the fast spheres of block @p B, whose criterion
         * failed at this step or whose halo grew (list_partial.cc,
         * doc/dem.md section 4, "Partial searches"): the spheres that moved
         * farther than the threshold since the build (relative to their
         * bin) and those of the cross-sections that joined the halo are
         * searched among all the block's spheres at their current
         * positions, and the pairs of two other spheres are kept, with the
         * tangential history of the pairs that stay listed.
         * @return false, with the lists unchanged, where the block must be
         * rebuilt whole (rebuild() then resets its criterion): it is stale
         * otherwise, more than `DEM/Partial search fraction` of its spheres
         * are fast, or the spheres left out of the search would not keep
         * the criterion of the build.
         */
        bool
        search_fast(ListBlock &B);

        /** Counters for the benchmark after @p step_count force evaluations
         * (collective). */
        std::string
        statistics(const std::uint64_t step_count) const;

        /** The blocks of the rank (a block taken over by the one before it
         * is left empty). */
        /** Write the blocks (pairs, tangential histories, build positions
         * and criteria) and the counters to a checkpoint: the next steps
         * then visit the pairs in the same order (dem/checkpoint.cc). */
        void
        save(Checkpoint::Writer &out) const;
        /** Read what save() wrote. */
        void
        load(Checkpoint::Reader &in);

        std::vector<ListBlock> blocks;
        /** Block of each storage station. */
        std::vector<unsigned int> station_block;
        /** Block rebuilds, and the rows they rebuilt [spheres]. */
        unsigned long n_rebuilds = 0, rebuilt_rows = 0;
        /** Spheres searched and candidates tested by the rebuilds. */
        unsigned long n_searched = 0, n_candidates = 0;
        /** Partial searches, and the fast spheres they searched. */
        unsigned long n_partial = 0, partial_spheres = 0;

      private:
        /** The bound on the relative motion of the pairs of block @p B
         * since its build [m]; the lists hold while it is below the skin.
         * Moves the block's reference displacements on. */
        double
        list_bound(ListBlock &B);
        /** The terms of the bound over bins @p n_bins with counts
         * @p count and reference displacements @p mean [m]: g, the largest
         * difference of consecutive non-empty bins, and the largest |D_b,z|
         * (@p dz). */
        static double
        bin_terms(const unsigned int n_bins,
                  const std::vector<std::uint32_t> &count,
                  const std::vector<double> &mean,
                  double &dz);
        /** The lists of block @p B after a partial search: its pairs of two
         * spheres that are not fast and the pairs found for the fast ones
         * (list_partial.cc). */
        void
        merge_fast(ListBlock &B);
        /** Make the cell grid of block @p B's build from its build
         * positions (after a restart, which does not store it). */
        void
        make_build_grid(ListBlock &B);
        /** Call @p f(j) for every sphere j of block @p B's build that may
         * be closer than the cut-off to the point @p q [m] at this step:
         * the spheres that are not fast from the build's grid, around q
         * shifted back by their bin's reference displacement with a radius
         * enlarged by what they may have moved relative to it
         * (@p slow_reach [m]), and the fast ones from their own grid at
         * their current positions. */
        template <typename F>
        void
        for_each_near(const ListBlock &B,
                      const double q[3],
                      const double slow_reach,
                      const F &f) const;
        /** Append the rows of block @p C (which follow those of @p B) to
         * @p B. */
        void
        absorb(ListBlock &B, ListBlock &C);

        const Parameters &prm;
        const FibreChains &chains;
        const Decomposition &decomposition;
        const std::vector<double> &pos;
        /** Yarn length [m] (the rounding margin of the criterion). */
        const double length;
        /** Search radius d + skin [m]. */
        const double cutoff;
        /** Largest bound terms of the last criterion evaluation [m]. */
        double last_r = 0., last_g = 0.;

        // Scratch of the build (kept to avoid reallocation).
        std::vector<std::uint32_t> bin_start, bin_sphere, cell_off, cell_start,
          cell_sphere, near_sphere, near_x;
        std::vector<double> bin_y0, bin_z0, bin_ic;
        std::vector<std::uint32_t> bin_ny, bin_nz;
        std::vector<std::pair<std::uint32_t, std::uint32_t>> found;
        std::vector<double> cell_x, cell_y, cell_z;
        std::vector<float> cell_xf, cell_yf, cell_zf;
        std::vector<std::uint32_t> candidate_k;
        std::vector<std::uint8_t> cell_partners;
        // Scratch of the partial search.
        std::vector<std::pair<std::uint32_t, std::uint32_t>> found_fast;
        std::vector<MirrorPair> found_mirror;
        /** The fast spheres (local indices) by the key of their cell at
         * their current positions (cubic cells of the cut-off from
         * fast_origin [m]), and the bins of the build that hold spheres
         * that are not fast. */
        std::vector<std::pair<std::uint64_t, std::uint32_t>> fast_cells;
        double fast_origin[3] = {0., 0., 0.};
        std::vector<std::uint32_t> slow_bins;
      };
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
