// The slabs of the DEM impact model on the MPI ranks, their ghost layers
// and the locality checks that keep every contact within reach of a rank.

#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/dem/decomposition.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

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


      Decomposition::Decomposition(const Parameters &prm,
                                   const FibreChains &chains,
                                   const MPI_Comm communicator)
        : comm(communicator)
        , rank(dealii::Utilities::MPI::this_mpi_process(communicator))
        , n_ranks(dealii::Utilities::MPI::n_mpi_processes(communicator))
        , nf(chains.nf)
        , n_st(chains.n_st)
        , d(chains.d)
        , L0(chains.L0)
      {
        using YarnImpact::Parameters::require;
        const unsigned int G = prm.ghost_stations;
        slab_starts.assign(n_ranks + 1, n_st);
        slab_starts[0] = 0;
        if (n_ranks > 1)
          {
            const double share = (chains.x_sym ? prm.impact_slab_share : 1.);
            const unsigned int first =
              std::min<unsigned int>(n_st, std::lround(share * n_st / n_ranks));
            for (unsigned int q = 1; q < n_ranks; ++q)
              slab_starts[q] =
                first + static_cast<unsigned int>(
                          static_cast<unsigned long>(n_st - first) * (q - 1) /
                          (n_ranks - 1));
          }
        st_begin    = slab_begin(rank);
        st_end      = slab_begin(rank + 1);
        bool enough = true;
        for (unsigned int q = 0; n_ranks > 1 && q < n_ranks; ++q)
          enough = enough && slab_begin(q + 1) >= slab_begin(q) + G + 1;
        require(enough,
                "DEM/Ghost stations",
                "= " + std::to_string(G) + " is too large for " +
                  std::to_string(n_st) + " cross-sections on " +
                  std::to_string(n_ranks) +
                  " MPI ranks (each rank needs more cross-sections than "
                  "ghost layers; with x symmetry the first rank has "
                  "DEM/Impact slab share of an even slab): use fewer ranks, "
                  "fewer ghost stations or a larger impact slab share");
        lo      = (rank == 0 ? 0 : slab_begin(rank - 1));
        hi      = (rank + 1 == n_ranks ? n_st : slab_begin(rank + 2));
        n_local = static_cast<std::size_t>(hi - lo) * nf;
        own_b   = local_index(st_begin, 0);
        own_e   = local_index(st_end, 0);
        ghost_lo.resize(n_ranks);
        ghost_hi.resize(n_ranks);
        for (unsigned int q = 0; q < n_ranks; ++q)
          {
            ghost_lo[q] = (q == 0 ? 0 : slab_begin(q) - G);
            ghost_hi[q] = (q + 1 == n_ranks ? n_st : slab_begin(q + 1) + G);
          }
        set_active_range();
      }


      void
      Decomposition::set_active_range()
      {
        g_lo  = ghost_lo[rank];
        g_hi  = ghost_hi[rank];
        act_b = local_index(g_lo, 0);
        act_e = local_index(g_hi, 0);
      }


      void
      Decomposition::exchange_ghosts(std::vector<double> &v) const
      {
        if (n_ranks == 1)
          return;
        MPI_Request requests[4];
        unsigned int n = 0;
        const int tag  = 71;
        // Each message is one contiguous block of cross-sections: the
        // receiver's ghost layer is the sender's stations next to the
        // boundary.
        if (rank > 0)
          {
            MPI_Irecv(v.data() + 3 * act_b,
                      3ul * (st_begin - g_lo) * nf,
                      MPI_DOUBLE,
                      rank - 1,
                      tag,
                      comm,
                      &requests[n++]);
            MPI_Isend(v.data() + 3 * own_b,
                      3ul * (ghost_hi[rank - 1] - st_begin) * nf,
                      MPI_DOUBLE,
                      rank - 1,
                      tag,
                      comm,
                      &requests[n++]);
          }
        if (rank + 1 < n_ranks)
          {
            MPI_Irecv(v.data() + 3 * own_e,
                      3ul * (g_hi - st_end) * nf,
                      MPI_DOUBLE,
                      rank + 1,
                      tag,
                      comm,
                      &requests[n++]);
            MPI_Isend(v.data() + 3 * local_index(ghost_lo[rank + 1], 0),
                      3ul * (st_end - ghost_lo[rank + 1]) * nf,
                      MPI_DOUBLE,
                      rank + 1,
                      tag,
                      comm,
                      &requests[n++]);
          }
        MPI_Waitall(n, requests, MPI_STATUSES_IGNORE);
      }


      void
      Decomposition::global_extents(const std::vector<double> &st_xlo,
                                    const std::vector<double> &st_xhi,
                                    const std::vector<double> *&lo_x,
                                    const std::vector<double> *&hi_x)
      {
        lo_x = &st_xlo;
        hi_x = &st_xhi;
        if (n_ranks == 1)
          return;
        extent_buffer.assign(2 * n_st, infinity);
        for (unsigned int s = st_begin; s < st_end; ++s)
          {
            extent_buffer[s]        = st_xlo[s];
            extent_buffer[n_st + s] = -st_xhi[s];
          }
        MPI_Allreduce(MPI_IN_PLACE,
                      extent_buffer.data(),
                      2 * n_st,
                      MPI_DOUBLE,
                      MPI_MIN,
                      comm);
        glo.assign(extent_buffer.begin(), extent_buffer.begin() + n_st);
        ghi.resize(n_st);
        for (unsigned int s = 0; s < n_st; ++s)
          ghi[s] = -extent_buffer[n_st + s];
        lo_x = &glo;
        hi_x = &ghi;
      }


      bool
      Decomposition::grow_ghost_layers(const std::vector<double> &lo_x,
                                       const std::vector<double> &hi_x)
      {
        if (n_ranks == 1)
          return false;
        // Every cross-section that comes within d + L0 of the x-range of a
        // rank's slab must be in that rank's ghost layer. The layer grows
        // (by two more cross-sections) while the stations are still L0
        // farther than a contact, so no pair with history is ever missing
        // on one side, and L0 is more than any sphere moves relative to
        // another in a step. It can only take stations from the
        // neighbouring slab.
        const double reach = d + L0;
        bool grown         = false;
        for (unsigned int q = 0; q < n_ranks; ++q)
          {
            const unsigned int b = slab_begin(q), e = slab_begin(q + 1);
            double Xlo = infinity, Xhi = -infinity;
            for (unsigned int s = b; s < e; ++s)
              {
                Xlo = std::min(Xlo, lo_x[s]);
                Xhi = std::max(Xhi, hi_x[s]);
              }
            const auto near = [&](const unsigned int t, const double r) {
              return !(lo_x[t] > Xhi + r || hi_x[t] < Xlo - r);
            };
            const unsigned int l_min = (q == 0 ? 0 : slab_begin(q - 1));
            const unsigned int h_max =
              (q + 1 == n_ranks ? n_st : slab_begin(q + 2));
            for (unsigned int t = 0; t < n_st; ++t)
              {
                if (t >= ghost_lo[q] && t < ghost_hi[q])
                  continue;
                if (near(t, d) || ((t < l_min || t >= h_max) && near(t, reach)))
                  {
                    std::ostringstream s;
                    s << "[dem] fibres slid along each other across the "
                         "slabs of more than two MPI ranks (cross-section "
                      << t << " reached the slab of rank " << q
                      << "); use fewer ranks";
                    throw RunError(s.str());
                  }
                if (near(t, reach))
                  {
                    grown = true;
                    if (t < ghost_lo[q])
                      ghost_lo[q] = (t >= l_min + 2 ? t - 2 : l_min);
                    else
                      ghost_hi[q] = std::min(h_max, t + 3);
                  }
              }
          }
        if (grown)
          {
            ++n_ghost_growths;
            set_active_range();
          }
        return grown;
      }


      void
      check_symmetry_plane(const FibreChains &chains,
                           const std::vector<double> &lo_x)
      {
        if (!chains.x_sym || chains.n_st <= 1)
          return;
        double m           = infinity;
        unsigned int s_min = 1;
        for (unsigned int s = 1; s < chains.n_st; ++s)
          if (lo_x[s] < m)
            {
              m     = lo_x[s];
              s_min = s;
            }
        if (!(m > 0.))
          {
            // Which cross-section tells a fibre end freed at the plane
            // (a few spacings) from a blow-up far from it.
            std::ostringstream s;
            s << "[dem] a sphere off the symmetry plane crossed x = 0 (it "
                 "passed through its own mirror image; cross-section "
              << s_min << ", " << s_min * chains.L0 * 1e3
              << " mm from the plane at rest, reached x = " << m * 1e6
              << " um): the motion under the projectile blew up, which no "
                 "symmetry would survive; lower Time/Safety factor, or the "
                 "contact stiffness ratios of subsection DEM";
            throw RunError(s.str());
          }
      }


      std::string
      Decomposition::remarks() const
      {
        if (n_ranks == 1)
          return {};
        std::ostringstream s;
        s << "MPI ghost layers grew " << n_ghost_growths
          << " times; cross-sections below/above each slab at the end:";
        for (unsigned int q = 0; q < n_ranks; ++q)
          s << " rank " << q << " " << slab_begin(q) - ghost_lo[q] << "/"
            << ghost_hi[q] - slab_begin(q + 1);
        return s.str();
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
