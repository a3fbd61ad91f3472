#ifndef yarn_impact_dem_list_check_h
#define yarn_impact_dem_list_check_h

#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/dem/decomposition.h>
#include <yarn_impact/dem/fibre_chains.h>
#include <yarn_impact/dem/neighbour_lists.h>
#include <yarn_impact/dem/parameters.h>

#include <cstdint>
#include <string>
#include <vector>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      /**
       * The diagnostics of the neighbour lists (`DEM/Check lists`, `DEM/List
       * rebuilds = missed contact`): a sweep over the spheres sorted along x
       * that knows nothing of the lists finds every pair closer than the
       * fibre diameter (and every such mirror image) and looks it up in the
       * lists. Slow (a run takes 3 to 25 times as long); for tests.
       */
      class ListCheck
      {
      public:
        /** A check of the lists of the spheres at @p pos (given at
         * construction, followed as they move) [m]. */
        ListCheck(const Parameters &prm,
                  const FibreChains &chains,
                  const Decomposition &decomposition,
                  const std::vector<double> &pos);

        /**
         * Throw if a pair of spheres closer than d, or a sphere and a mirror
         * image closer than d, with an owned sphere, is not in @p lists
         * (collective: every rank throws the first rank's message).
         * @p step_count names the force evaluation in the message.
         * @throw RunError
         */
        void
        check(const NeighbourLists &lists, const std::uint64_t step_count);

        /**
         * With `DEM/List rebuilds = missed contact`: rebuild the stale
         * blocks of @p lists and those that miss a pair closer than d, then
         * verify, as check(), unless `DEM/Check lists` verifies every step
         * anyway. Does not count as checked contacts.
         * @throw RunError
         */
        void
        rebuild_on_missed_contacts(NeighbourLists &lists,
                                   const std::uint64_t step_count);

        /** The lines of the run summary on what check() saw and, with
         * `List rebuilds = missed contact`, the block rebuilds of @p lists
         * over @p step_count force evaluations; empty when neither is on
         * (collective). */
        std::string
        remarks(const NeighbourLists &lists,
                const std::uint64_t step_count) const;

        /** Contacts (pair-steps, weighted like the energies) and mirror
         * contacts seen by check() [-]. */
        double checked_contacts = 0., checked_mirror_contacts = 0.;

        /** Write the counters to a checkpoint. */
        void
        save(Checkpoint::Writer &out) const
        {
          out.put(checked_contacts);
          out.put(checked_mirror_contacts);
        }
        /** Read what save() wrote. */
        void
        load(Checkpoint::Reader &in)
        {
          in.get(checked_contacts);
          in.get(checked_mirror_contacts);
        }

      private:
        /** Sort the spheres in check_order along x and call @p f(p, q) for
         * every pair of them (and every sphere with itself if @p with_self)
         * less than d apart in x. */
        template <typename PairFunction>
        void
        sweep_along_x(const bool with_self, const PairFunction &f);
        /** The sphere pairs of check(); @p missing(i, j, false) reports an
         * unlisted one. */
        template <typename Report>
        void
        check_pairs(const NeighbourLists &lists, const Report &missing);
        /** The mirror-image pairs of check(); @p missing(i, j, true)
         * reports an unlisted one. */
        template <typename Report>
        void
        check_mirror_pairs(const NeighbourLists &lists, const Report &missing);

        const Parameters &prm;
        const FibreChains &chains;
        const Decomposition &decomposition;
        const std::vector<double> &pos;
        /** Scratch: the spheres a sweep visits, the blocks that missed a
         * pair. */
        std::vector<std::uint32_t> check_order;
        std::vector<std::uint8_t> missed_in_block;
      };
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
