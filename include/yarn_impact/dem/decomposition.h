#ifndef yarn_impact_dem_decomposition_h
#define yarn_impact_dem_decomposition_h

#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/dem/fibre_chains.h>
#include <yarn_impact/dem/parameters.h>

#include <mpi.h>

#include <cstddef>
#include <string>
#include <vector>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      /**
       * The decomposition of the DEM impact model over the MPI ranks: each
       * rank owns a slab of consecutive cross-sections (stations) and sees
       * ghost layers of its neighbours' slabs (doc/dem.md).
       *
       * Storage holds the stations [lo, hi): the own slab and the whole
       * slabs of both neighbours, so that the ghost layers can grow without
       * moving data. Local sphere i is fibre i % nf of station lo + i / nf.
       * The active stations [g_lo, g_hi) (spheres [act_b, act_e)) are the
       * own slab and the current ghost layers; ghost_lo/ghost_hi hold them
       * for every rank (identical on all ranks).
       */
      class Decomposition
      {
      public:
        /**
         * Cut the stations of @p chains into slabs: even, but with x symmetry
         * the first one (with the impact point) is `Impact slab share` of an
         * even one.
         * @throw InputError if `DEM/Ghost stations` is too large for the
         * slabs
         */
        Decomposition(const Parameters &prm,
                      const FibreChains &chains,
                      const MPI_Comm communicator);

        /** Local index of fibre @p f at station @p s. */
        std::size_t
        local_index(const unsigned int s, const unsigned int f) const
        {
          return static_cast<std::size_t>(s - lo) * nf + f;
        }
        /** Whether local sphere @p i is owned by this rank. */
        bool
        owned(const std::size_t i) const
        {
          return i >= own_b && i < own_e;
        }
        /** Share of this rank in a pair (i, j): a pair across a rank
         * boundary is counted half on each side [-]. */
        double
        own_factor(const std::size_t i, const std::size_t j) const
        {
          return 0.5 * (owned(i) + owned(j));
        }
        /** Station of local sphere @p i. */
        unsigned int
        station_of(const std::size_t i) const
        {
          return lo + static_cast<unsigned int>(i / nf);
        }
        /** First station of the slab of rank @p q (slab_begin(n_ranks) =
         * n_st). */
        unsigned int
        slab_begin(const unsigned int q) const
        {
          return slab_starts[q];
        }

        /** Copy the owned values of @p v (3 per sphere) of the stations in
         * the neighbours' ghost layers to them (collective). */
        void
        exchange_ghosts(std::vector<double> &v) const;

        /**
         * The x-extents [m] of every station of the model, from the extents
         * @p st_xlo, @p st_xhi of the owned stations (collective; on one rank
         * these themselves). Valid until the next call.
         */
        void
        global_extents(const std::vector<double> &st_xlo,
                       const std::vector<double> &st_xhi,
                       const std::vector<double> *&lo_x,
                       const std::vector<double> *&hi_x);

        /**
         * Grow the ghost layers of every rank to each station that comes
         * within d + L0 of the rank's slab, given the global station extents
         * @p lo_x, @p hi_x [m] (identical on all ranks, so a growth or a
         * failure is collective).
         * @return whether a layer grew (then the active range has moved)
         * @throw RunError if fibres slid across more than two slabs
         */
        bool
        grow_ghost_layers(const std::vector<double> &lo_x,
                          const std::vector<double> &hi_x);

        const MPI_Comm comm;
        const unsigned int rank, n_ranks;

        /** Sphere spacing data copied from the chains. */
        const unsigned int nf, n_st;
        const double d, L0;

        /** First station of every rank's slab, and n_st. */
        std::vector<unsigned int> slab_starts;
        /** Own slab [st_begin, st_end), storage [lo, hi), active [g_lo,
         * g_hi). */
        unsigned int st_begin = 0, st_end = 0, lo = 0, hi = 0, g_lo = 0,
                     g_hi = 0;
        /** Local spheres; owned [own_b, own_e) and active [act_b, act_e). */
        std::size_t n_local = 0, own_b = 0, own_e = 0, act_b = 0, act_e = 0;
        /** Active stations of every rank. */
        std::vector<unsigned int> ghost_lo, ghost_hi;
        /** How often the ghost layers grew. */
        unsigned long n_ghost_growths = 0;

        /** How the ghost layers grew, for the run summary (empty on one
         * rank): the growths and each slab's layers at the end. */
        std::string
        remarks() const;

        /** Write the ghost layers (what moves during a run) to a
         * checkpoint (dem/checkpoint.cc). */
        void
        save(Checkpoint::Writer &out) const;
        /** Read what save() wrote; refuses another slab layout. */
        void
        load(Checkpoint::Reader &in);

      private:
        /** Set the active range of this rank from ghost_lo/ghost_hi. */
        void
        set_active_range();

        std::vector<double> extent_buffer, glo, ghi;
      };


      /**
       * With x symmetry: throw if a sphere off the plane x = 0 crossed it,
       * given the global station extents @p lo_x [m]. A sphere off the
       * plane meets the mirror images of the others (and its own) through
       * the mirror pairs; only one that crosses the plane cannot be
       * represented: it has passed through its own mirror image (an overlap
       * of a whole diameter), and the mirror search assumes x >= 0.
       * @throw RunError
       */
      void
      check_symmetry_plane(const FibreChains &chains,
                           const std::vector<double> &lo_x);
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
