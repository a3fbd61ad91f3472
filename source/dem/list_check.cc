// The list check of the DEM impact model (a diagnostic): every contact
// found by a sweep that knows nothing of the neighbour lists must be listed.

#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/dem/contact_kernels.h>
#include <yarn_impact/dem/list_check.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      ListCheck::ListCheck(const Parameters &prm,
                           const FibreChains &chains,
                           const Decomposition &decomposition,
                           const std::vector<double> &pos)
        : prm(prm)
        , chains(chains)
        , decomposition(decomposition)
        , pos(pos)
      {}


      std::string
      ListCheck::remarks(const NeighbourLists &lists,
                         const std::uint64_t step_count) const
      {
        const MPI_Comm comm = decomposition.comm;
        std::ostringstream s;
        const char *separator = "";
        if (prm.check_lists)
          {
            // Collective: the contacts of every rank, a pair across a
            // rank boundary half on each.
            const double n[2] = {
              dealii::Utilities::MPI::sum(checked_contacts, comm),
              dealii::Utilities::MPI::sum(checked_mirror_contacts, comm)};
            s << "neighbour lists checked at " << step_count
              << " force evaluations: " << std::llround(n[0])
              << " contacts and " << std::llround(n[1])
              << " mirror-image contacts (summed over the evaluations), "
                 "all listed";
            separator = "\n  ";
            // Collective: the partial searches of all ranks, which the
            // check covers as it covers the rebuilds.
            const unsigned long m[2] = {
              dealii::Utilities::MPI::sum(lists.n_partial, comm),
              dealii::Utilities::MPI::sum(lists.partial_spheres, comm)};
            if (m[0] > 0)
              s << separator << "neighbour-list blocks searched again at "
                << "their fast spheres only: " << m[0] << " times, " << m[1]
                << " spheres (all ranks)";
          }
        if (prm.list_rebuilds == Parameters::ListRebuilds::missed_contact)
          {
            // Collective: the block rebuilds of all ranks.
            const unsigned long n =
              dealii::Utilities::MPI::sum(lists.n_rebuilds, comm);
            s << separator
              << "neighbour-list blocks rebuilt only for missed contacts: " << n
              << " block rebuilds (all ranks) in " << step_count
              << " force evaluations";
          }
        return s.str();
      }


      void
      ListCheck::rebuild_on_missed_contacts(NeighbourLists &lists,
                                            const std::uint64_t step_count)
      {
        std::vector<ListBlock> &blocks = lists.blocks;
        // The blocks that must list a missed pair: that of the lower index
        // (its rows), and for a mirror image also the block holding the
        // plane x = 0 (which lists all mirror pairs in that plane).
        std::vector<std::uint8_t> &missed = missed_in_block;
        missed.assign(blocks.size(), 0);
        const auto mark =
          [&](const std::size_t i, const std::size_t, const bool mirror) {
            missed[&lists.block_of(i) - blocks.data()] = 1;
            if (mirror)
              for (std::size_t k = 0; k < blocks.size(); ++k)
                missed[k] |= (blocks[k].holds_plane ? 1 : 0);
          };
        // Not counted as checked contacts of `Check lists`.
        const double counted[2] = {checked_contacts, checked_mirror_contacts};
        check_pairs(lists, mark);
        check_mirror_pairs(lists, mark);
        bool rebuilt = false;
        for (std::size_t k = 0; k < blocks.size(); ++k)
          if (blocks[k].active() && (blocks[k].stale || missed[k]))
            {
              rebuilt = true;
              lists.rebuild(blocks[k]);
            }
        // A rebuilt block lists every pair of its rows and halo closer than
        // d + skin; a pair still missing would be one that the halos or the
        // ghost layers failed to bring in, which the locality check
        // forbids. Verified (collectively) after every rebuild, unless
        // `Check lists` verifies every step anyway.
        if (!prm.check_lists)
          {
            if (decomposition.n_ranks > 1)
              rebuilt = (dealii::Utilities::MPI::max(rebuilt ? 1 : 0,
                                                     decomposition.comm) > 0);
            if (rebuilt)
              check(lists, step_count);
          }
        checked_contacts        = counted[0];
        checked_mirror_contacts = counted[1];
      }


      template <typename PairFunction>
      void
      ListCheck::sweep_along_x(const bool with_self, const PairFunction &f)
      {
        const double d = chains.d;
        std::sort(check_order.begin(),
                  check_order.end(),
                  [&](const std::uint32_t a, const std::uint32_t b) {
                    return pos[3 * a] < pos[3 * b];
                  });
        for (std::size_t a = 0; a < check_order.size(); ++a)
          for (std::size_t b = (with_self ? a : a + 1);
               b < check_order.size() &&
               pos[3 * check_order[b]] - pos[3 * check_order[a]] < d;
               ++b)
            f(check_order[a], check_order[b]);
      }


      template <typename Report>
      void
      ListCheck::check_pairs(const NeighbourLists &lists, const Report &missing)
      {
        // Every pair closer than d is within d along x.
        const Decomposition &dec = decomposition;
        const double d2          = chains.d * chains.d;
        const unsigned int nf    = chains.nf;
        check_order.clear();
        for (std::size_t i = dec.act_b; i < dec.act_e; ++i)
          check_order.push_back(static_cast<std::uint32_t>(i));
        sweep_along_x(false, [&](const std::size_t p, const std::size_t q) {
          const std::size_t i = std::min(p, q), j = std::max(p, q);
          if ((!dec.owned(i) && !dec.owned(j)) || j == i + nf)
            return;
          double e[3];
          if (separation(pos[3 * i],
                         pos[3 * i + 1],
                         pos[3 * i + 2],
                         &pos[3 * j],
                         1.,
                         1.,
                         e) >= d2)
            return;
          checked_contacts += dec.own_factor(i, j);
          // Row i of the block whose rows hold i, sorted by j.
          const ListBlock &B = lists.block_of(i);
          if (i < B.row_sphere_begin || i >= B.row_sphere_end)
            {
              missing(i, j, false);
              return;
            }
          const Pair *row0 = B.pairs.data() + B.pstart[i - B.row_sphere_begin],
                     *row1 =
                       B.pairs.data() + B.pstart[i - B.row_sphere_begin + 1];
          const Pair *hit =
            std::lower_bound(row0,
                             row1,
                             j,
                             [](const Pair &e, const std::size_t k) {
                               return e.j < k;
                             });
          if (hit == row1 || hit->j != j)
            missing(i, j, false);
        });
      }


      template <typename Report>
      void
      ListCheck::check_mirror_pairs(const NeighbourLists &lists,
                                    const Report &missing)
      {
        // Sphere i with the image of j (or of itself) in x = 0 (axes 1),
        // z = 0 (2) or both (3); both spheres off the mirroring planes.
        const Decomposition &dec         = decomposition;
        const double d                   = chains.d;
        const double d2                  = d * d;
        const unsigned int nf            = chains.nf;
        const std::vector<double> &zmask = chains.zmask;
        const auto check                 = [&](const std::size_t p,
                               const std::size_t q,
                               const std::uint8_t axes) {
          const std::size_t i = std::min(p, q), j = std::max(p, q);
          if ((!dec.owned(i) && !dec.owned(j)) ||
              ((axes & 1) &&
               (dec.station_of(i) == 0 || dec.station_of(j) == 0)) ||
              ((axes & 2) && (zmask[i % nf] == 0. || zmask[j % nf] == 0.)))
            return;
          const double sx = (axes & 1) ? -1. : 1., sz = (axes & 2) ? -1. : 1.;
          double e[3];
          if (separation(pos[3 * i],
                         pos[3 * i + 1],
                         pos[3 * i + 2],
                         &pos[3 * j],
                         sx,
                         sz,
                         e) >= d2)
            return;
          checked_mirror_contacts += dec.own_factor(i, j);
          const MirrorPair key = {static_cast<std::uint32_t>(i),
                                  static_cast<std::uint32_t>(j),
                                  0.f,
                                  axes,
                                  false};
          bool listed          = false;
          for (const ListBlock &B : lists.blocks)
            listed = listed || std::binary_search(B.mpairs.begin(),
                                                  B.mpairs.end(),
                                                  key,
                                                  mirror_less);
          if (!listed)
            missing(i, j, true);
        };
        // In z = 0: spheres within d of that plane (an image distance
        // below d needs z_i + z_j < d), swept along x.
        if (chains.z_sym)
          {
            check_order.clear();
            for (std::size_t i = dec.act_b; i < dec.act_e; ++i)
              if (pos[3 * i + 2] < d)
                check_order.push_back(static_cast<std::uint32_t>(i));
            sweep_along_x(true, [&](const std::size_t p, const std::size_t q) {
              check(p, q, 2);
            });
          }
        // In x = 0, and in both planes: spheres within d of x = 0, every
        // pair (x_i + x_j < d).
        if (chains.x_sym)
          {
            check_order.clear();
            for (std::size_t i = dec.act_b; i < dec.act_e; ++i)
              if (pos[3 * i] < d)
                check_order.push_back(static_cast<std::uint32_t>(i));
            for (std::size_t a = 0; a < check_order.size(); ++a)
              for (std::size_t b = a; b < check_order.size(); ++b)
                {
                  check(check_order[a], check_order[b], 1);
                  if (chains.z_sym)
                    check(check_order[a], check_order[b], 3);
                }
          }
      }


      void
      ListCheck::check(const NeighbourLists &lists,
                       const std::uint64_t step_count)
      {
        const Decomposition &dec = decomposition;
        const unsigned int nf    = chains.nf;
        const auto where         = [&](const std::size_t i) {
          std::ostringstream s;
          s << "cross-section " << dec.station_of(i) << ", fibre " << i % nf;
          return s.str();
        };
        // The first missing pair of this rank; the error is collective.
        std::string first_missing;
        const auto missing =
          [&](const std::size_t i, const std::size_t j, const bool mirror) {
            if (!first_missing.empty())
              return;
            std::ostringstream s;
            s << "[dem] list check at force evaluation " << step_count
              << " on rank " << dec.rank << ": the sphere at " << where(i);
            if (!mirror)
              s << " and the sphere at " << where(j);
            else if (i != j)
              s << " and the mirror image of the sphere at " << where(j);
            else
              s << " and its own mirror image";
            s << " are closer than the fibre diameter but not in the "
              << (mirror ? "mirror-pair" : "neighbour") << " lists";
            first_missing = s.str();
          };
        check_pairs(lists, missing);
        check_mirror_pairs(lists, missing);
        if (dec.n_ranks > 1)
          {
            const unsigned int first =
              dealii::Utilities::MPI::min(first_missing.empty() ? dec.n_ranks
                                                                : dec.rank,
                                          dec.comm);
            if (first < dec.n_ranks)
              first_missing = dealii::Utilities::MPI::broadcast(dec.comm,
                                                                first_missing,
                                                                first);
          }
        if (!first_missing.empty())
          throw RunError(first_missing);
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
