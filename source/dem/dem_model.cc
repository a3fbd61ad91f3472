// The DEM yarn: fibres as chains of spheres joined by trusses, with
// penalty contacts (doc/dem.md). Everything that runs every step is a plain
// loop over contiguous arrays: no allocation, maps or virtual calls.
#pragma GCC optimize("O3")

#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/dem/candidate_search.h>
#include <yarn_impact/dem/contact_law.h>
#include <yarn_impact/dem/dem_model.h>
#include <yarn_impact/dem/packing.h>
#include <yarn_impact/dem/vtu_writer.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/numbers.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>

namespace YarnImpact
{
  namespace DEM
  {
    namespace
    {
      using dealii::numbers::PI;
      using Symmetry            = YarnImpact::Parameters::Symmetry;
      constexpr double infinity = std::numeric_limits<double>::infinity();

      /** A listed sphere pair; a negative weight marks an active contact
       * (one with tangential history). */
      struct Pair
      {
        std::uint32_t j;
        float w;
      };

      /** A pair of a sphere with the mirror image of another one, or of
       * itself: in x = 0 (half and quarter symmetry, axes bit 1), in z = 0
       * (quarter, bit 2) or in both (quarter, bits 1 | 2). The image of j is
       * (sx x_j, y_j, sz z_j) with sx = -1 for bit 1 and sz = -1 for bit 2. */
      struct MirrorPair
      {
        std::uint32_t i, j;
        float w;
        std::uint8_t axes;
        bool active;
      };

      inline bool
      mirror_less(const MirrorPair &a, const MirrorPair &b)
      {
        return a.i < b.i ||
               (a.i == b.i && (a.j < b.j || (a.j == b.j && a.axes < b.axes)));
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
        /** Spheres of the rows [b, e) and of the halo [e, h) at the last
         * build. */
        std::size_t b = 0, e = 0, h = 0;
        /** The cross-sections changed since the last build. */
        bool stale = true;
        /** The rows hold the plane x = 0 (mirror pairs in x). */
        bool holds_plane = false;
        /** Pairs in CSR by the row of the lower index, with the tangential
         * history of each pair [m]; mirror pairs likewise. */
        std::vector<std::uint32_t> pstart, pstart_old;
        std::vector<Pair> pairs, pairs_old;
        std::vector<double> pxi, pxi_old;
        std::vector<MirrorPair> mpairs, mpairs_old;
        std::vector<double> mxi, mxi_old;
        /** Build positions [m] and build bins of the spheres [b, h). */
        std::vector<float> pos_build;
        std::vector<std::uint32_t> bin_of;
        /** Bins along x of the build (width d + skin, from the lowest
         * sphere) and their reference displacements. */
        unsigned int n_bins = 0;
        std::vector<std::uint32_t> bin_count;
        std::vector<double> D_prev, D_sum;
        double r2_max = 0.;
        /** The criterion's bound of this step [m]. */
        double bound = 0.;

        bool
        active() const
        {
          return row_end > row_begin;
        }
      };


      class Model : public ImpactModel
      {
      public:
        Model(const YarnImpact::Parameters::Shared &shared,
              const Parameters &parameters,
              const MPI_Comm communicator);

        std::string
        name() const override
        {
          return "dem";
        }

        void
        setup(const Projectile &projectile, std::ostream &out) override;

        double
        stable_time_step() const override
        {
          return critical_step;
        }

        double
        yarn_top() const override
        {
          // The highest sphere surface of the packing: the projectile starts
          // touching it. Every rank holds the whole fibre layout.
          double top = -std::numeric_limits<double>::max();
          for (const double y : fy)
            top = std::max(top, y + radius);
          return top;
        }

        double
        compute_forces(const Projectile &projectile, const double dt) override;

        void
        kick(const double dt) override
        {
          // The kick is applied lazily, fused with the next drift (one pass
          // over memory instead of two); observables add it on the fly.
          pending_kick += dt;
        }

        void
        drift(const double dt) override;

        Observables
        observables() const override;

        bool
        yarn_cut_through() const override
        {
          return cut_through;
        }

        AxialProperties
        axial_properties() const override;

        double
        mass() const override
        {
          return total_mass;
        }

        std::string
        write_snapshot(const std::string &directory,
                       const unsigned int index,
                       const double time) const override;

        unsigned long
        n_elements() const override
        {
          return static_cast<unsigned long>(nf_whole) * n_whole_stations;
        }

        std::string
        remarks() const override
        {
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
            }
          if (prm.list_rebuilds == Parameters::ListRebuilds::missed_contact)
            {
              // Collective: the block rebuilds of all ranks.
              const unsigned long n =
                dealii::Utilities::MPI::sum(n_rebuilds, comm);
              s << separator
                << "neighbour-list blocks rebuilt only for missed contacts: "
                << n << " block rebuilds (all ranks) in " << step_count
                << " force evaluations";
              separator = "\n  ";
            }
          if (n_ranks == 1)
            return s.str();
          s << separator << "MPI ghost layers grew " << n_ghost_growths
            << " times; cross-sections below/above each slab at the end:";
          for (unsigned int q = 0; q < n_ranks; ++q)
            s << " rank " << q << " " << slab_begin(q) - ghost_lo[q] << "/"
              << ghost_hi[q] - slab_begin(q + 1);
          return s.str();
        }

        /** Counters for the benchmark (collective). */
        std::string
        statistics() const
        {
          // Collective: every rank's rebuilds and pairs. Rebuilds are
          // counted per block and in whole-rank equivalents (rebuilt rows
          // divided by the rows of the rank).
          std::vector<unsigned long> counts(3 * n_ranks, 0);
          const unsigned long n_pairs = n_listed_pairs();
          unsigned long n_rows        = 0;
          for (const ListBlock &B : blocks)
            n_rows += B.e - B.b;
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
                        comm);
          std::ostringstream s;
          s << step_count << " force evaluations; block rebuilds, in whole-"
            << "rank equivalents (listed pairs), per rank:";
          for (unsigned int q = 0; q < n_ranks; ++q)
            s << " " << counts[3 * q] << ", " << counts[3 * q + 1] << " ("
              << counts[3 * q + 2] << ")";
          s << "; rank " << rank << " last bound terms r " << last_r << " g "
            << last_g << " m, candidates per searched sphere "
            << static_cast<double>(n_candidates) / std::max(1ul, n_searched);
          return s.str();
        }

      private:
        double last_r = 0., last_g = 0.;
        // --- set-up data ---------------------------------------------------
        const YarnImpact::Parameters::Shared shared;
        const Parameters prm;
        const MPI_Comm comm;
        const unsigned int rank, n_ranks;
        const Symmetry symmetry;
        const bool x_sym, z_sym;
        const double factor;

        unsigned int nf               = 0; // modelled fibres
        unsigned int nf_whole         = 0;
        unsigned int n_st             = 0; // modelled stations (cross-sections)
        unsigned int n_whole_stations = 0;
        unsigned int s_impact         = 0; // station at x = 0
        unsigned int n_prof           = 0; // stations of the folded profile
        double d = 0., radius = 0., L0 = 0., sphere_mass = 0., truss_k = 0.,
               fibre_area = 0., cutoff = 0.;
        double packing_scale = 1.;

        std::vector<double> fy, fz, fw, finv, zmask; // per fibre
        std::vector<double> sx0, sw, sinv, xmask;    // per station

        ContactLaw fibre_law, projectile_law;
        double critical_step = 0.;
        double total_mass    = 0.;
        double failure_strain;
        bool failure;

        // --- decomposition ---------------------------------------------------
        // Storage holds the stations [lo, hi): the own slab and the whole
        // slabs of both neighbours, so that the ghost layers can grow
        // without moving data. The active stations [g_lo, g_hi) (spheres
        // [act_b, act_e)) are the own slab and the current ghost layers;
        // ghost_lo/ghost_hi hold them for every rank (identical on all).
        unsigned int st_begin = 0, st_end = 0, lo = 0, hi = 0, g_lo = 0,
                     g_hi   = 0;
        std::size_t n_local = 0, own_b = 0, own_e = 0, act_b = 0, act_e = 0;
        std::vector<unsigned int> ghost_lo, ghost_hi;
        std::vector<unsigned int> slab_starts; // of every rank, and n_st
        unsigned long n_ghost_growths = 0;

        // --- state (local spheres, cross-section-major)
        // ------------------------
        std::vector<double> pos, vel, frc;
        std::vector<std::uint8_t> broken; // truss (s, s+1) of each sphere
        std::vector<double> xi_p;         // projectile tangential history
        std::vector<std::uint64_t> proj_step;
        double pending_kick      = 0.;
        bool forces_consumed     = true;
        std::uint64_t step_count = 0;
        mutable bool cut_through = false;

        // Per-station extents of the owned stations (from the last drift).
        std::vector<double> st_xlo, st_xhi, st_ymax;
        std::vector<double> extent_buffer;

        // --- neighbour lists
        // ---------------------------------------------------
        // Blocks of `prm.list_block` storage cross-sections each.
        std::vector<ListBlock> blocks;
        std::vector<unsigned int> station_block; // of each storage station
        unsigned long n_rebuilds   = 0;          // block rebuilds
        unsigned long rebuilt_rows = 0; // sum of the rebuilt rows [spheres]
        unsigned long n_searched = 0, n_candidates = 0; // of the rebuilds
        // Contacts seen by the list check (pair-steps, weighted like the
        // energies) and its scratch (the spheres it sweeps).
        double checked_contacts = 0., checked_mirror_contacts = 0.;
        std::vector<std::uint32_t> check_order;
        std::vector<std::uint8_t> missed_in_block;

        // Scratch of the rebuild (kept to avoid reallocation).
        std::vector<std::uint32_t> bin_start, bin_sphere, cell_off, cell_start,
          cell_sphere, near_sphere, near_x;
        std::vector<double> bin_y0, bin_z0, bin_ic;
        std::vector<std::uint32_t> bin_ny, bin_nz;
        std::vector<std::pair<std::uint32_t, std::uint32_t>> found;
        std::vector<double> cell_x, cell_y, cell_z;
        std::vector<float> cell_xf, cell_yf, cell_zf;
        std::vector<std::uint32_t> candidate_k;
        std::vector<std::uint8_t> cell_partners;

        // --- energy accounting (local)
        // ----------------------------------------
        double dissipated_local = 0.;
        double last_yc = 0., last_Rr = 0.;

        // Initial width of each profile station.
        std::vector<double> initial_width;
        mutable std::vector<double> profile_buffer;

        // --- helpers
        // -----------------------------------------------------------
        std::size_t
        local_index(const unsigned int s, const unsigned int f) const
        {
          return static_cast<std::size_t>(s - lo) * nf + f;
        }
        bool
        owned(const std::size_t i) const
        {
          return i >= own_b && i < own_e;
        }
        double
        own_factor(const std::size_t i, const std::size_t j) const
        {
          return 0.5 * (owned(i) + owned(j));
        }
        unsigned int
        station_of(const std::size_t i) const
        {
          return lo + static_cast<unsigned int>(i / nf);
        }

        void
        exchange_ghosts(std::vector<double> &v);
        void
        compute_station_extents(const unsigned int s);
        /** Pairs in the neighbour lists of this rank. */
        unsigned long
        n_listed_pairs() const
        {
          unsigned long n = 0;
          for (const ListBlock &B : blocks)
            n += B.pairs.size();
          return n;
        }
        ListBlock &
        block_of(const std::size_t i)
        {
          return blocks[station_block[i / nf]];
        }
        void
        absorb(ListBlock &B, ListBlock &C);
        void
        accumulate_criterion(ListBlock &B, const std::size_t i);
        /** The bound on the relative motion of the pairs of block @p B
         * since its build [m]; the lists hold while it is below the skin.
         * Moves the block's reference displacements on. */
        double
        list_bound(ListBlock &B);
        /** First cross-section of the slab of rank @p q (of the modelled
         * ones; slab_begin(n_ranks) = n_st). */
        unsigned int
        slab_begin(const unsigned int q) const
        {
          return slab_starts[q];
        }
        void
        set_active_range();
        bool
        check_locality();
        void
        set_block_ranges();
        /** Rebuild the lists of the blocks that are stale or whose criterion
         * fails (when @p check_criterion). */
        void
        update_lists(const bool check_criterion);
        void
        rebuild(ListBlock &B);
        /** With `DEM/List rebuilds = missed contact`: rebuild the stale
         * blocks and those that miss a pair closer than d (found without
         * the lists, as check_lists() does), then verify. */
        void
        rebuild_on_missed_contacts();
        /** With `DEM/Check lists`: throw if a pair of spheres closer than d,
         * or a sphere and a mirror image closer than d, with an owned
         * sphere, is not in the lists (found without them). */
        void
        check_lists();
        /** Sort the spheres in check_order along x and call @p f(p, q) for
         * every pair of them (and every sphere with itself if @p with_self)
         * less than d apart in x. */
        template <typename PairFunction>
        void
        sweep_along_x(const bool with_self, const PairFunction &f);
        /** The sphere pairs of check_lists(); @p missing(i, j, false)
         * reports an unlisted one. */
        template <typename Report>
        void
        check_pairs(const Report &missing);
        /** The mirror-image pairs of check_lists(); @p missing(i, j, true)
         * reports an unlisted one. */
        template <typename Report>
        void
        check_mirror_pairs(const Report &missing);
        double
        truss_strain(const std::size_t i, double *length = nullptr) const;
        double
        velocity_component(const std::size_t i, const unsigned int d) const;
      };


      Model::Model(const YarnImpact::Parameters::Shared &shared,
                   const Parameters &parameters,
                   const MPI_Comm communicator)
        : shared(shared)
        , prm(parameters)
        , comm(communicator)
        , rank(dealii::Utilities::MPI::this_mpi_process(communicator))
        , n_ranks(dealii::Utilities::MPI::n_mpi_processes(communicator))
        , symmetry(shared.general.symmetry)
        , x_sym(symmetry != Symmetry::none)
        , z_sym(symmetry == Symmetry::quarter)
        , factor(YarnImpact::Parameters::symmetry_factor(symmetry))
        , failure_strain(shared.yarn.failure_strain)
        , failure(shared.yarn.failure)
      {
        using YarnImpact::Parameters::require;
        const auto &y = shared.yarn;
        d             = y.fibre_diameter;
        radius        = 0.5 * d;
        // Fibre centres, checked as by validate() (also run at parsing).
        const FibreCentres centres = fibre_centres(shared, prm, z_sym);
        packing_scale              = centres.scale;
        nf_whole                   = centres.size();
        for (unsigned int a = 0; a < nf_whole; ++a)
          if (!z_sym || centres.z[a] >= 0.)
            {
              const bool on_plane = z_sym && centres.z[a] == 0.;
              // Touching neighbours get a gap of 1e-9 d, so that they do not
              // start as contacts with round-off overlaps.
              fy.push_back(centres.y[a] * (1. + 1e-9));
              fz.push_back(centres.z[a] * (1. + 1e-9));
              fw.push_back(on_plane ? 0.5 : 1.);
              zmask.push_back(on_plane ? 0. : 1.);
            }
        nf = fy.size();

        // Stations: an even number of equal trusses over the length, so
        // that a cross-section lies on the plane x = 0.
        const unsigned int n_seg =
          2 * static_cast<unsigned int>(
                std::ceil(y.length / (2. * prm.sphere_spacing) - 1e-9));
        L0               = y.length / n_seg;
        n_whole_stations = n_seg + 1;
        n_prof           = n_seg / 2 + 1;
        n_st             = x_sym ? n_seg / 2 + 1 : n_seg + 1;
        s_impact         = x_sym ? 0 : n_seg / 2;
        for (unsigned int s = 0; s < n_st; ++s)
          {
            const double x     = x_sym ? s * L0 : -0.5 * y.length + s * L0;
            const bool plane   = x_sym && s == 0;
            const bool clamped = (s == n_st - 1) || (!x_sym && s == 0);
            sx0.push_back(x);
            sw.push_back(plane ? 0.5 : 1.);
            sinv.push_back(clamped ? 0. : (plane ? 2. : 1.));
            xmask.push_back(plane ? 0. : 1.);
          }

        fibre_area  = PI * d * d / 4.;
        sphere_mass = y.fibre_density * fibre_area * L0;
        truss_k     = y.fibre_modulus * fibre_area / L0;
        for (unsigned int f = 0; f < nf; ++f)
          finv.push_back(1. / (sphere_mass * fw[f]));
        cutoff = d + prm.skin;

        // Contact laws (doc/dem.md section 2).
        fibre_law      = fibre_contact_law(prm, truss_k, sphere_mass);
        projectile_law = projectile_contact_law(prm, truss_k, sphere_mass);

        // Stable step (doc/theory.md 3.2): Gershgorin bound of a sphere with
        // two trusses, `coordination` fibre contacts and the projectile,
        // reduced for the contact damping.
        critical_step = critical_time_step(prm, truss_k, sphere_mass);

        total_mass = 0.;
        for (unsigned int f = 0; f < nf; ++f)
          for (unsigned int s = 0; s < n_st; ++s)
            total_mass += sphere_mass * fw[f] * sw[s];
        total_mass *= factor;

        // Slabs of stations: even, but with x symmetry the first one (with
        // the impact point) is `Impact slab share` of an even one.
        const unsigned int G = prm.ghost_stations;
        slab_starts.assign(n_ranks + 1, n_st);
        slab_starts[0] = 0;
        if (n_ranks > 1)
          {
            const double share = (x_sym ? prm.impact_slab_share : 1.);
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
        // List blocks over the storage cross-sections.
        const unsigned int K = prm.list_block;
        for (unsigned int s = lo; s < hi; s += K)
          {
            ListBlock B;
            B.s_begin = s;
            B.s_end   = std::min(hi, s + K);
            for (unsigned int t = B.s_begin; t < B.s_end; ++t)
              station_block.push_back(blocks.size());
            blocks.push_back(std::move(B));
          }
        set_active_range();
      }


      void
      Model::set_active_range()
      {
        g_lo  = ghost_lo[rank];
        g_hi  = ghost_hi[rank];
        act_b = local_index(g_lo, 0);
        act_e = local_index(g_hi, 0);
        set_block_ranges();
      }


      void
      Model::set_block_ranges()
      {
        // Rows: the active part of each block. Halo: at least the next
        // `Ghost stations` cross-sections (more after a growth), within the
        // active range. Every block is rebuilt after this.
        for (ListBlock &B : blocks)
          {
            B.row_begin   = std::max(B.s_begin, g_lo);
            B.row_end     = std::min(B.s_end, g_hi);
            B.holds_plane = x_sym && B.row_begin == 0 && B.active();
            if (!B.active())
              {
                B.row_end  = B.row_begin;
                B.halo_end = B.row_begin;
                continue;
              }
            B.halo_end =
              std::min(g_hi,
                       std::max(B.halo_end, B.row_end + prm.ghost_stations));
            B.stale = true;
          }
      }


      AxialProperties
      Model::axial_properties() const
      {
        AxialProperties a;
        a.area           = nf_whole * fibre_area;
        a.density        = shared.yarn.fibre_density;
        a.modulus        = shared.yarn.fibre_modulus;
        const double E   = a.modulus;
        a.nominal_stress = [E](const double e) { return E * e; };
        return a;
      }


      void
      Model::setup(const Projectile &projectile, std::ostream &out)
      {
        pos.assign(3 * n_local, 0.);
        vel.assign(3 * n_local, 0.);
        frc.assign(3 * n_local, 0.);
        broken.assign(n_local, 0);
        xi_p.assign(3 * n_local, 0.);
        proj_step.assign(n_local, 0);
        st_xlo.assign(n_st, infinity);
        st_xhi.assign(n_st, -infinity);
        st_ymax.assign(n_st, -infinity);
        for (unsigned int s = lo; s < hi; ++s)
          for (unsigned int f = 0; f < nf; ++f)
            {
              const std::size_t i = local_index(s, f);
              pos[3 * i]          = sx0[s];
              pos[3 * i + 1]      = fy[f];
              pos[3 * i + 2]      = fz[f];
            }
        for (unsigned int s = st_begin; s < st_end; ++s)
          compute_station_extents(s);

        // Initial width of the folded profile.
        initial_width.assign(n_prof, 0.);
        for (unsigned int s = st_begin; s < st_end; ++s)
          {
            double zmin = infinity, zmax = -infinity;
            for (unsigned int f = 0; f < nf; ++f)
              {
                zmin = std::min(zmin, fz[f]);
                zmax = std::max(zmax, fz[f]);
              }
            const unsigned int k = (s > s_impact ? s - s_impact : s_impact - s);
            initial_width[k] =
              std::max(initial_width[k], z_sym ? 2. * zmax : zmax - zmin);
          }
        dealii::Utilities::MPI::max(initial_width, comm, initial_width);

        // The first lists, then those of the blocks whose cross-sections
        // changed with the first locality check (storage holds the initial
        // positions of every station).
        for (ListBlock &B : blocks)
          if (B.active())
            rebuild(B);
        check_locality();
        update_lists(false);
        forces_consumed = true;

        const double E0 = 0.5 * projectile.mass() * projectile.velocity() *
                          projectile.velocity();
        if (rank == 0)
          {
            const unsigned long n_pairs = n_listed_pairs();
            out << std::setprecision(5) << "[dem] " << nf_whole
                << " fibres (hexagonal packing scale " << packing_scale << "), "
                << n_whole_stations << " spheres per fibre, spacing "
                << L0 * 1e6 << " um; modelled: " << nf << " fibres x " << n_st
                << " cross-sections = " << static_cast<unsigned long>(nf) * n_st
                << " spheres on " << n_ranks << " rank(s)\n"
                << "[dem] sphere mass " << sphere_mass << " kg, truss "
                << "stiffness " << truss_k << " N/m, contact stiffness "
                << fibre_law.k_n << " N/m (projectile " << projectile_law.k_n
                << " N/m), rank 0 pairs listed " << n_pairs
                << ", initial projectile energy " << E0 * 1e3 << " mJ\n";
          }
      }


      void
      Model::compute_station_extents(const unsigned int s)
      {
        double xlo = infinity, xhi = -infinity, ymax = -infinity;
        for (unsigned int f = 0; f < nf; ++f)
          {
            const std::size_t i = local_index(s, f);
            xlo                 = std::min(xlo, pos[3 * i]);
            xhi                 = std::max(xhi, pos[3 * i]);
            ymax                = std::max(ymax, pos[3 * i + 1]);
          }
        st_xlo[s]  = xlo;
        st_xhi[s]  = xhi;
        st_ymax[s] = ymax;
      }


      inline void
      Model::accumulate_criterion(ListBlock &B, const std::size_t i)
      {
        const std::size_t k   = i - B.b;
        const std::uint32_t b = B.bin_of[k];
        const double dx       = pos[3 * i] - B.pos_build[3 * k];
        const double dy       = pos[3 * i + 1] - B.pos_build[3 * k + 1];
        const double dz       = pos[3 * i + 2] - B.pos_build[3 * k + 2];
        const double rx       = dx - B.D_prev[3 * b];
        const double ry       = dy - B.D_prev[3 * b + 1];
        const double rz       = dz - B.D_prev[3 * b + 2];
        B.r2_max              = std::max(B.r2_max, rx * rx + ry * ry + rz * rz);
        B.D_sum[3 * b] += dx;
        B.D_sum[3 * b + 1] += dy;
        B.D_sum[3 * b + 2] += dz;
      }


      void
      Model::drift(const double dt)
      {
        const double kick    = pending_kick;
        pending_kick         = 0.;
        double *__restrict x = pos.data();
        double *__restrict v = vel.data();
        double *__restrict F = frc.data();
        for (unsigned int s = st_begin; s < st_end; ++s)
          {
            const double as      = kick * sinv[s];
            const double xm      = xmask[s];
            const std::size_t b0 = local_index(s, 0);
            ListBlock &B         = block_of(b0);
            double xlo = infinity, xhi = -infinity, ymax = -infinity;
            for (unsigned int f = 0; f < nf; ++f)
              {
                const std::size_t i = b0 + f;
                const double a      = as * finv[f];
                v[3 * i] += a * xm * F[3 * i];
                v[3 * i + 1] += a * F[3 * i + 1];
                v[3 * i + 2] += a * zmask[f] * F[3 * i + 2];
                F[3 * i] = F[3 * i + 1] = F[3 * i + 2] = 0.;
                x[3 * i] += dt * v[3 * i];
                x[3 * i + 1] += dt * v[3 * i + 1];
                x[3 * i + 2] += dt * v[3 * i + 2];
                xlo  = std::min(xlo, x[3 * i]);
                xhi  = std::max(xhi, x[3 * i]);
                ymax = std::max(ymax, x[3 * i + 1]);
                accumulate_criterion(B, i);
              }
            st_xlo[s]  = xlo;
            st_xhi[s]  = xhi;
            st_ymax[s] = ymax;
          }
        forces_consumed = true;
      }


      void
      Model::exchange_ghosts(std::vector<double> &v)
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


      bool
      Model::check_locality()
      {
        // Global x-extent of every cross-section. Everything below is
        // evaluated identically on all ranks, so a failure or a growth of
        // the ghost layers is collective. Returns whether the layers grew.
        const std::vector<double> *lo_x = &st_xlo, *hi_x = &st_xhi;
        std::vector<double> glo, ghi;
        if (n_ranks > 1)
          {
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
        // Half/quarter: a sphere off the plane x = 0 meets the mirror images
        // of the others (and its own) through the mirror pairs; only a
        // sphere that crosses the plane cannot be represented: it has
        // passed through its own mirror image (an overlap of a whole
        // diameter), and the mirror search assumes x >= 0.
        if (x_sym && n_st > 1)
          {
            double m = infinity;
            for (unsigned int s = 1; s < n_st; ++s)
              m = std::min(m, (*lo_x)[s]);
            if (!(m > 0.))
              throw RunError("[dem] a sphere off the symmetry plane crossed "
                             "x = 0 (it passed through its own mirror "
                             "image); run the case with Symmetry = none");
          }
        // List blocks: every cross-section above the rows of a block that
        // comes within d + L0 of their x-range joins the block's halo (with
        // two more), and the block is rebuilt; the same argument as for the
        // ghost layers below. Cross-sections below the rows list their pairs
        // with the rows in their own block.
        const double reach = d + L0;
        for (ListBlock &B : blocks)
          {
            if (!B.active())
              continue;
            double Xlo = infinity, Xhi = -infinity;
            for (unsigned int s = B.row_begin; s < B.row_end; ++s)
              {
                Xlo = std::min(Xlo, (*lo_x)[s]);
                Xhi = std::max(Xhi, (*hi_x)[s]);
              }
            for (unsigned int t = B.halo_end; t < g_hi; ++t)
              if (!((*lo_x)[t] > Xhi + reach || (*hi_x)[t] < Xlo - reach))
                {
                  B.halo_end = std::min(g_hi, t + 3);
                  B.stale    = true;
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
        if (n_ranks == 1)
          return false;
        // Ghost layers: every cross-section that comes within d + L0 of the
        // x-range of a rank's slab must be in that rank's ghost layer. The
        // layer grows (by two more cross-sections) while the stations are
        // still L0 farther than a contact, so no pair with history is ever
        // missing on one side, and L0 is more than any sphere moves
        // relative to another in a step. It can only take stations from the
        // neighbouring slab.
        bool grown = false;
        for (unsigned int q = 0; q < n_ranks; ++q)
          {
            const unsigned int b = slab_begin(q), e = slab_begin(q + 1);
            double Xlo = infinity, Xhi = -infinity;
            for (unsigned int s = b; s < e; ++s)
              {
                Xlo = std::min(Xlo, (*lo_x)[s]);
                Xhi = std::max(Xhi, (*hi_x)[s]);
              }
            const auto near = [&](const unsigned int t, const double r) {
              return !((*lo_x)[t] > Xhi + r || (*hi_x)[t] < Xlo - r);
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


      double
      Model::list_bound(ListBlock &B)
      {
        // Criterion (doc/dem.md, "Neighbour lists"): with D_b the reference
        // displacement of build bin b, r = max |Delta_i - D_b(i)| and
        // g = max |D_{b+1} - D_b| over consecutive non-empty bins, no
        // unlisted pair can touch while 2 r + 2 g (+ 2 max|D_b,z| for mirror
        // pairs in z = 0, + 2 |D_0,x| for mirror pairs in x = 0) < skin.
        double g = 0., dz = 0.;
        int prev = -1;
        for (unsigned int b = 0; b < B.n_bins; ++b)
          {
            if (B.bin_count[b] == 0)
              continue;
            if (prev >= 0)
              {
                const double ex = B.D_prev[3 * b] - B.D_prev[3 * prev];
                const double ey = B.D_prev[3 * b + 1] - B.D_prev[3 * prev + 1];
                const double ez = B.D_prev[3 * b + 2] - B.D_prev[3 * prev + 2];
                g = std::max(g, std::sqrt(ex * ex + ey * ey + ez * ez));
              }
            dz   = std::max(dz, std::abs(B.D_prev[3 * b + 2]));
            prev = b;
          }
        // Rounding of the single-precision build positions.
        const double margin = 8. * 6e-8 * shared.yarn.length;
        last_r              = std::max(last_r, std::sqrt(B.r2_max));
        last_g              = std::max(last_g, g);
        // Mirror pairs in x = 0: 2 |D_0,x| of bin 0 (which starts at x = 0).
        const double dx0 =
          (B.holds_plane && B.n_bins > 0 ? std::abs(B.D_prev[0]) : 0.);
        const double bound = 2. * std::sqrt(B.r2_max) + 2. * g +
                             (z_sym ? 2. * dz : 0.) + 2. * dx0 + margin;
        // New reference: the mean displacement of each bin.
        for (unsigned int b = 0; b < B.n_bins; ++b)
          if (B.bin_count[b] > 0)
            for (unsigned int c = 0; c < 3; ++c)
              B.D_prev[3 * b + c] = B.D_sum[3 * b + c] / B.bin_count[b];
        std::fill(B.D_sum.begin(), B.D_sum.end(), 0.);
        B.r2_max = 0.;
        return bound;
      }


      void
      Model::absorb(ListBlock &B, ListBlock &C)
      {
        // C's rows follow B's: its lists append to B's, with their
        // tangential history, and B is rebuilt from them.
        AssertThrow(B.e == C.b, dealii::ExcInternalError());
        const auto offset = static_cast<std::uint32_t>(B.pairs.size());
        for (std::size_t r = 1; r < C.pstart.size(); ++r)
          B.pstart.push_back(C.pstart[r] + offset);
        B.pairs.insert(B.pairs.end(), C.pairs.begin(), C.pairs.end());
        B.pxi.insert(B.pxi.end(), C.pxi.begin(), C.pxi.end());
        if (!C.mpairs.empty())
          {
            std::vector<std::size_t> order(B.mpairs.size() + C.mpairs.size());
            std::vector<MirrorPair> mp(B.mpairs);
            mp.insert(mp.end(), C.mpairs.begin(), C.mpairs.end());
            std::vector<double> xi(B.mxi);
            xi.insert(xi.end(), C.mxi.begin(), C.mxi.end());
            for (std::size_t k = 0; k < order.size(); ++k)
              order[k] = k;
            std::sort(order.begin(),
                      order.end(),
                      [&](const std::size_t a, const std::size_t b) {
                        return mirror_less(mp[a], mp[b]);
                      });
            B.mpairs.resize(order.size());
            B.mxi.resize(3 * order.size());
            for (std::size_t k = 0; k < order.size(); ++k)
              {
                B.mpairs[k] = mp[order[k]];
                for (unsigned int c = 0; c < 3; ++c)
                  B.mxi[3 * k + c] = xi[3 * order[k] + c];
              }
          }
        B.e        = C.e;
        B.s_end    = C.s_end;
        B.row_end  = C.row_end;
        B.halo_end = std::max(B.halo_end, C.halo_end);
        B.stale    = true;
        for (unsigned int t = C.s_begin; t < C.s_end; ++t)
          station_block[t - lo] = station_block[B.s_begin - lo];
        C         = ListBlock();
        C.s_begin = C.s_end = B.s_end;
      }


      void
      Model::update_lists(const bool check_criterion)
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
        if (check_criterion &&
            prm.list_rebuilds == Parameters::ListRebuilds::missed_contact)
          {
            rebuild_on_missed_contacts();
            return;
          }
        // A rank's rebuild stalls the others (every step ends in a
        // collective): when any rank must rebuild, the others rebuild their
        // blocks that would fail soon in the same step.
        double joint_bound = infinity;
        if (n_ranks > 1 && check_criterion && prm.joint_rebuild_fraction < 1.)
          {
            MPI_Allreduce(MPI_IN_PLACE,
                          &must_rebuild,
                          1,
                          MPI_INT,
                          MPI_LOR,
                          comm);
            if (must_rebuild)
              joint_bound = prm.joint_rebuild_fraction * prm.skin;
          }
        for (ListBlock &B : blocks)
          if (B.active() &&
              (B.stale || !(B.bound < prm.skin) || B.bound >= joint_bound))
            rebuild(B);
      }


      void
      Model::rebuild_on_missed_contacts()
      {
        // The blocks that must list a missed pair: that of the lower index
        // (its rows), and for a mirror image also the block holding the
        // plane x = 0 (which lists all mirror pairs in that plane).
        std::vector<std::uint8_t> &missed = missed_in_block;
        missed.assign(blocks.size(), 0);
        const auto mark =
          [&](const std::size_t i, const std::size_t, const bool mirror) {
            missed[&block_of(i) - blocks.data()] = 1;
            if (mirror)
              for (std::size_t k = 0; k < blocks.size(); ++k)
                missed[k] |= (blocks[k].holds_plane ? 1 : 0);
          };
        // Not counted as checked contacts of `Check lists`.
        const double counted[2] = {checked_contacts, checked_mirror_contacts};
        check_pairs(mark);
        check_mirror_pairs(mark);
        bool rebuilt = false;
        for (std::size_t k = 0; k < blocks.size(); ++k)
          if (blocks[k].active() && (blocks[k].stale || missed[k]))
            {
              rebuilt = true;
              rebuild(blocks[k]);
            }
        // A rebuilt block lists every pair of its rows and halo closer than
        // d + skin; a pair still missing would be one that the halos or the
        // ghost layers failed to bring in, which the locality check
        // forbids. Verified (collectively) after every rebuild, unless
        // `Check lists` verifies every step anyway (compute_forces()).
        if (!prm.check_lists)
          {
            if (n_ranks > 1)
              rebuilt =
                (dealii::Utilities::MPI::max(rebuilt ? 1 : 0, comm) > 0);
            if (rebuilt)
              check_lists();
          }
        checked_contacts        = counted[0];
        checked_mirror_contacts = counted[1];
      }


      void
      Model::rebuild(ListBlock &B)
      {
        ++n_rebuilds;
        B.stale = false;
        // The spheres of the build: rows and halo; the rows of the list
        // being replaced.
        const std::size_t old_b = B.b, old_e = B.e;
        B.b = local_index(B.row_begin, 0);
        B.e = local_index(B.row_end, 0);
        B.h = local_index(B.halo_end, 0);
        rebuilt_rows += B.e - B.b;
        const std::size_t sb = B.b, se = B.h, n_build = se - sb;
        const double cut2 = cutoff * cutoff;
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
        B.D_prev.assign(3 * n_bins, 0.);
        B.D_sum.assign(3 * n_bins, 0.);
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
        const std::size_t row_e = B.e;
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
                    const double xi = cell_x[k_i], yi = cell_y[k_i],
                                 zi = cell_z[k_i];
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
                          std::floor((yi - bin_y0[bb]) * bin_ic[bb]));
                        const long cz_ = static_cast<long>(
                          std::floor((zi - bin_z0[bb]) * bin_ic[bb]));
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
                        const double ex = xi - cell_x[k], ey = yi - cell_y[k],
                                     ez = zi - cell_z[k];
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
        std::vector<double> &pxi = B.pxi, &pxi_old = B.pxi_old;
        std::swap(pstart, pstart_old);
        std::swap(pairs, pairs_old);
        std::swap(pxi, pxi_old);
        const std::size_t n_rows = B.e - B.b;
        pstart.assign(n_rows + 1, 0);
        for (const auto &p : found)
          ++pstart[p.first - sb + 1];
        for (std::size_t r = 0; r < n_rows; ++r)
          pstart[r + 1] += pstart[r];
        pairs.resize(found.size());
        pxi.assign(3 * found.size(), 0.);
        {
          std::vector<std::uint32_t> &fill = cell_of; // scratch again
          fill.assign(pstart.begin(), pstart.end() - 1);
          for (const auto &p : found)
            pairs[fill[p.first - sb]++] = {p.second, 1.f};
        }
        const bool have_old = pstart_old.size() == old_e - old_b + 1;
        for (std::size_t i = B.b; i < B.e; ++i)
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
                      pxi[3 * p + c] = pxi_old[3 * q + c];
                  }
              }
          }

        // Mirror pairs: spheres with the image of another one, or of
        // themselves, in the symmetry planes (doc/dem.md section 4: the
        // candidates below are every pair whose image distance can drop
        // below d while the criterion holds).
        std::vector<MirrorPair> &mpairs = B.mpairs, &mpairs_old = B.mpairs_old;
        std::vector<double> &mxi = B.mxi, &mxi_old = B.mxi_old;
        std::swap(mpairs, mpairs_old);
        std::swap(mxi, mxi_old);
        mpairs.clear();
        const auto add_mirror = [&](const std::size_t i,
                                    const std::size_t j,
                                    const std::uint8_t axes,
                                    const double w) {
          // Pairs in z = 0 belong to the block of the lower index; pairs in
          // x = 0 all to the block holding the plane, whose build holds
          // every sphere that can come near the plane.
          if ((!owned(i) && !owned(j)) ||
              (!(axes & 1) && std::min(i, j) >= row_e))
            return;
          const double sx = (axes & 1) ? -1. : 1., sz = (axes & 2) ? -1. : 1.;
          const double ex = pos[3 * i] - sx * pos[3 * j],
                       ey = pos[3 * i + 1] - pos[3 * j + 1],
                       ez = pos[3 * i + 2] - sz * pos[3 * j + 2];
          if (ex * ex + ey * ey + ez * ez < cut2)
            mpairs.push_back({static_cast<std::uint32_t>(std::min(i, j)),
                              static_cast<std::uint32_t>(std::max(i, j)),
                              static_cast<float>(w),
                              axes,
                              false});
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
        mxi.assign(3 * mpairs.size(), 0.);
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
                  mxi[3 * p + c] = mxi_old[3 * q + c];
              }
          }
      }


      template <typename PairFunction>
      void
      Model::sweep_along_x(const bool with_self, const PairFunction &f)
      {
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
      Model::check_pairs(const Report &missing)
      {
        // Every pair closer than d is within d along x.
        const double d2 = d * d;
        check_order.clear();
        for (std::size_t i = act_b; i < act_e; ++i)
          check_order.push_back(static_cast<std::uint32_t>(i));
        sweep_along_x(false, [&](const std::size_t p, const std::size_t q) {
          const std::size_t i = std::min(p, q), j = std::max(p, q);
          if ((!owned(i) && !owned(j)) || j == i + nf)
            return;
          const double ex = pos[3 * j] - pos[3 * i],
                       ey = pos[3 * j + 1] - pos[3 * i + 1],
                       ez = pos[3 * j + 2] - pos[3 * i + 2];
          if (ex * ex + ey * ey + ez * ez >= d2)
            return;
          checked_contacts += own_factor(i, j);
          // Row i of the block whose rows hold i, sorted by j.
          const ListBlock &B = block_of(i);
          if (i < B.b || i >= B.e)
            {
              missing(i, j, false);
              return;
            }
          const Pair *row0 = B.pairs.data() + B.pstart[i - B.b],
                     *row1 = B.pairs.data() + B.pstart[i - B.b + 1];
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
      Model::check_mirror_pairs(const Report &missing)
      {
        // Sphere i with the image of j (or of itself) in x = 0 (axes 1),
        // z = 0 (2) or both (3); both spheres off the mirroring planes.
        const double d2  = d * d;
        const auto check = [&](const std::size_t p,
                               const std::size_t q,
                               const std::uint8_t axes) {
          const std::size_t i = std::min(p, q), j = std::max(p, q);
          if ((!owned(i) && !owned(j)) ||
              ((axes & 1) && (station_of(i) == 0 || station_of(j) == 0)) ||
              ((axes & 2) && (zmask[i % nf] == 0. || zmask[j % nf] == 0.)))
            return;
          const double sx = (axes & 1) ? -1. : 1., sz = (axes & 2) ? -1. : 1.;
          const double ex = pos[3 * i] - sx * pos[3 * j],
                       ey = pos[3 * i + 1] - pos[3 * j + 1],
                       ez = pos[3 * i + 2] - sz * pos[3 * j + 2];
          if (ex * ex + ey * ey + ez * ez >= d2)
            return;
          checked_mirror_contacts += own_factor(i, j);
          const MirrorPair key = {static_cast<std::uint32_t>(i),
                                  static_cast<std::uint32_t>(j),
                                  0.f,
                                  axes,
                                  false};
          bool listed          = false;
          for (const ListBlock &B : blocks)
            listed = listed || std::binary_search(B.mpairs.begin(),
                                                  B.mpairs.end(),
                                                  key,
                                                  mirror_less);
          if (!listed)
            missing(i, j, true);
        };
        // In z = 0: spheres within d of that plane (an image distance
        // below d needs z_i + z_j < d), swept along x.
        if (z_sym)
          {
            check_order.clear();
            for (std::size_t i = act_b; i < act_e; ++i)
              if (pos[3 * i + 2] < d)
                check_order.push_back(static_cast<std::uint32_t>(i));
            sweep_along_x(true, [&](const std::size_t p, const std::size_t q) {
              check(p, q, 2);
            });
          }
        // In x = 0, and in both planes: spheres within d of x = 0, every
        // pair (x_i + x_j < d).
        if (x_sym)
          {
            check_order.clear();
            for (std::size_t i = act_b; i < act_e; ++i)
              if (pos[3 * i] < d)
                check_order.push_back(static_cast<std::uint32_t>(i));
            for (std::size_t a = 0; a < check_order.size(); ++a)
              for (std::size_t b = a; b < check_order.size(); ++b)
                {
                  check(check_order[a], check_order[b], 1);
                  if (z_sym)
                    check(check_order[a], check_order[b], 3);
                }
          }
      }


      void
      Model::check_lists()
      {
        const auto where = [&](const std::size_t i) {
          std::ostringstream s;
          s << "cross-section " << station_of(i) << ", fibre " << i % nf;
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
              << " on rank " << rank << ": the sphere at " << where(i);
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
        check_pairs(missing);
        check_mirror_pairs(missing);
        if (n_ranks > 1)
          {
            const unsigned int first =
              dealii::Utilities::MPI::min(first_missing.empty() ? n_ranks
                                                                : rank,
                                          comm);
            if (first < n_ranks)
              first_missing =
                dealii::Utilities::MPI::broadcast(comm, first_missing, first);
          }
        if (!first_missing.empty())
          throw RunError(first_missing);
      }


      double
      Model::compute_forces(const Projectile &projectile, const double dt)
      {
        ++step_count;
        exchange_ghosts(pos);
        exchange_ghosts(vel);
        // Criterion contributions of the ghosts (the owned ones were added
        // during the drift).
        for (std::size_t i = act_b; i < own_b; ++i)
          accumulate_criterion(block_of(i), i);
        for (std::size_t i = own_e; i < act_e; ++i)
          accumulate_criterion(block_of(i), i);
        for (ListBlock &B : blocks)
          for (std::size_t i = B.e; i < B.h; ++i)
            accumulate_criterion(B, i);
        if (check_locality())
          {
            // New ghost cross-sections: fetch them; every block is stale.
            exchange_ghosts(pos);
            exchange_ghosts(vel);
          }
        update_lists(true);
        if (prm.check_lists)
          check_lists();

        double *__restrict x = pos.data();
        double *__restrict v = vel.data();
        double *__restrict F = frc.data();
        std::fill(F + 3 * act_b, F + 3 * own_b, 0.);
        std::fill(F + 3 * own_e, F + 3 * act_e, 0.);
        if (!forces_consumed)
          std::fill(F + 3 * own_b, F + 3 * own_e, 0.);
        forces_consumed = false;

        double dissipated = 0.;

        // Trusses (s, s+1) with at least one owned end.
        const unsigned int t_begin = (st_begin > 0 ? st_begin - 1 : 0);
        const unsigned int t_end   = std::min(st_end, n_st - 1);
        for (unsigned int s = t_begin; s < t_end; ++s)
          {
            const std::size_t b0 = local_index(s, 0);
            for (unsigned int f = 0; f < nf; ++f)
              {
                const std::size_t i = b0 + f, j = i + nf;
                if (broken[i])
                  continue;
                const double e[3] = {x[3 * j] - x[3 * i],
                                     x[3 * j + 1] - x[3 * i + 1],
                                     x[3 * j + 2] - x[3 * i + 2]};
                const double k    = truss_k * fw[f];
                double t[3];
                const double strain = truss_force(e, k, L0, t);
                if (failure && strain > failure_strain)
                  {
                    broken[i] = 1;
                    dissipated +=
                      own_factor(i, j) * 0.5 * k * strain * strain * L0 * L0;
                    continue;
                  }
                F[3 * i] += t[0];
                F[3 * i + 1] += t[1];
                F[3 * i + 2] += t[2];
                F[3 * j] -= t[0];
                F[3 * j + 1] -= t[1];
                F[3 * j + 2] -= t[2];
              }
          }

        // Fibre-fibre contacts.
        const double d2 = d * d;
        for (ListBlock &B : blocks)
          {
            const std::uint32_t *__restrict pstart = B.pstart.data();
            Pair *__restrict pairs                 = B.pairs.data();
            double *__restrict pxi                 = B.pxi.data();
            for (std::size_t i = B.b; i < B.e; ++i)
              {
                const std::uint32_t p0 = pstart[i - B.b],
                                    p1 = pstart[i - B.b + 1];
                if (p0 == p1)
                  continue;
                const double xi = x[3 * i], yi = x[3 * i + 1],
                             zi = x[3 * i + 2];
                double fx = 0., fy_ = 0., fz_ = 0.;
                for (std::uint32_t p = p0; p < p1; ++p)
                  {
                    const std::size_t j = pairs[p].j;
                    const double ex = xi - x[3 * j], ey = yi - x[3 * j + 1],
                                 ez = zi - x[3 * j + 2];
                    const double r2 = ex * ex + ey * ey + ez * ez;
                    if (r2 >= d2)
                      {
                        if (pairs[p].w < 0.f)
                          {
                            pairs[p].w     = -pairs[p].w;
                            pxi[3 * p]     = 0.;
                            pxi[3 * p + 1] = 0.;
                            pxi[3 * p + 2] = 0.;
                          }
                        continue;
                      }
                    if (pairs[p].w > 0.f)
                      pairs[p].w = -pairs[p].w;
                    const double w     = -pairs[p].w;
                    const double dist  = std::sqrt(r2);
                    const double n[3]  = {ex / dist, ey / dist, ez / dist};
                    const double vr[3] = {v[3 * i] - v[3 * j],
                                          v[3 * i + 1] - v[3 * j + 1],
                                          v[3 * i + 2] - v[3 * j + 2]};
                    double f[3], diss = 0.;
                    fibre_law.force(d - dist, n, vr, dt, &pxi[3 * p], f, diss);
                    fx += w * f[0];
                    fy_ += w * f[1];
                    fz_ += w * f[2];
                    F[3 * j] -= w * f[0];
                    F[3 * j + 1] -= w * f[1];
                    F[3 * j + 2] -= w * f[2];
                    dissipated += w * own_factor(i, j) * diss;
                  }
                F[3 * i] += fx;
                F[3 * i + 1] += fy_;
                F[3 * i + 2] += fz_;
              }
          }

        // Mirror pairs: i with the image of j; j feels the mirror image of
        // the reaction (nothing more for a self-image pair).
        for (ListBlock &B : blocks)
          {
            std::vector<MirrorPair> &mpairs = B.mpairs;
            std::vector<double> &mxi        = B.mxi;
            for (std::size_t p = 0; p < mpairs.size(); ++p)
              {
                MirrorPair &mp      = mpairs[p];
                const std::size_t i = mp.i, j = mp.j;
                const double sx = (mp.axes & 1) ? -1. : 1.,
                             sz = (mp.axes & 2) ? -1. : 1.;
                const double ex = x[3 * i] - sx * x[3 * j],
                             ey = x[3 * i + 1] - x[3 * j + 1],
                             ez = x[3 * i + 2] - sz * x[3 * j + 2];
                const double r2 = ex * ex + ey * ey + ez * ez;
                if (r2 >= d2)
                  {
                    if (mp.active)
                      {
                        mp.active  = false;
                        mxi[3 * p] = mxi[3 * p + 1] = mxi[3 * p + 2] = 0.;
                      }
                    continue;
                  }
                mp.active          = true;
                const double dist  = std::sqrt(r2);
                const double n[3]  = {ex / dist, ey / dist, ez / dist};
                const double vr[3] = {v[3 * i] - sx * v[3 * j],
                                      v[3 * i + 1] - v[3 * j + 1],
                                      v[3 * i + 2] - sz * v[3 * j + 2]};
                double f[3], diss = 0.;
                fibre_law.force(d - dist, n, vr, dt, &mxi[3 * p], f, diss);
                const double w = mp.w;
                F[3 * i] += w * f[0];
                F[3 * i + 1] += w * f[1];
                F[3 * i + 2] += w * f[2];
                if (j != i)
                  {
                    F[3 * j] -= w * sx * f[0];
                    F[3 * j + 1] -= w * f[1];
                    F[3 * j + 2] -= w * sz * f[2];
                  }
                dissipated += w * (i == j ? 0.5 : 1.) * own_factor(i, j) * diss;
              }
          }

        // Projectile: only cross-sections that can reach it.
        const double yc = projectile.axis_position();
        const double vp = projectile.velocity();
        const double Rr = projectile.radius() + radius;
        double reaction = 0.;
        last_yc         = yc;
        last_Rr         = Rr;
        for (unsigned int s = st_begin; s < st_end; ++s)
          {
            const double ax =
              (st_xlo[s] > 0. ? st_xlo[s] : (st_xhi[s] < 0. ? -st_xhi[s] : 0.));
            if (ax >= Rr || st_ymax[s] <= yc - Rr)
              continue;
            const std::size_t b0 = local_index(s, 0);
            for (unsigned int f = 0; f < nf; ++f)
              {
                const std::size_t i = b0 + f;
                const double ex = x[3 * i], ey = x[3 * i + 1] - yc;
                const double r2 = ex * ex + ey * ey;
                if (r2 >= Rr * Rr)
                  continue;
                if (proj_step[i] + 1 != step_count)
                  xi_p[3 * i] = xi_p[3 * i + 1] = xi_p[3 * i + 2] = 0.;
                proj_step[i]       = step_count;
                const double rho   = std::sqrt(r2);
                const double n[3]  = {ex / rho, ey / rho, 0.};
                const double vr[3] = {v[3 * i],
                                      v[3 * i + 1] - vp,
                                      v[3 * i + 2]};
                double fc[3], diss = 0.;
                projectile_law
                  .force(Rr - rho, n, vr, dt, &xi_p[3 * i], fc, diss);
                const double w = fw[f] * sw[s];
                F[3 * i] += w * fc[0];
                F[3 * i + 1] += w * fc[1];
                F[3 * i + 2] += w * fc[2];
                reaction -= w * fc[1];
                dissipated += w * diss;
              }
          }
        dissipated_local += dissipated;
        if (n_ranks > 1)
          reaction = dealii::Utilities::MPI::sum(reaction, comm);
        return factor * reaction;
      }


      double
      Model::truss_strain(const std::size_t i, double *length) const
      {
        const std::size_t j = i + nf;
        const double e[3]   = {pos[3 * j] - pos[3 * i],
                               pos[3 * j + 1] - pos[3 * i + 1],
                               pos[3 * j + 2] - pos[3 * i + 2]};
        const double l = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
        if (length)
          *length = l;
        return l / L0 - 1.;
      }


      double
      Model::velocity_component(const std::size_t i, const unsigned int c) const
      {
        const unsigned int s = station_of(i), f = i % nf;
        const double mask = (c == 0 ? xmask[s] : (c == 2 ? zmask[f] : 1.));
        return vel[3 * i + c] +
               pending_kick * sinv[s] * finv[f] * mask * frc[3 * i + c];
      }


      Observables
      Model::observables() const
      {
        Observables o;
        // Sums: kinetic, elastic, contact, dissipated, failed.
        double kinetic = 0., elastic = 0., contact = 0., failed = 0.;
        // Maxima: max strain, then the profile (strain, deflection, width,
        // position) of n_prof stations.
        auto &buf = profile_buffer;
        buf.assign(1 + 4 * n_prof + nf, -infinity);
        double *fibre_cut = buf.data() + 1 + 4 * n_prof;
        double *pstrain = buf.data() + 1, *pdefl = pstrain + n_prof,
               *pwidth = pdefl + n_prof, *ppos = pwidth + n_prof;

        // Second moment of the fibre centres about z = 0 and their weight,
        // per profile station (summed over the ranks).
        std::vector<double> pz2(2 * n_prof, 0.);
        for (unsigned int s = st_begin; s < st_end; ++s)
          {
            const unsigned int k = (s > s_impact ? s - s_impact : s_impact - s);
            double smax = -infinity, defl = -infinity, zmin = infinity,
                   zmax = -infinity, xsum = 0.;
            for (unsigned int f = 0; f < nf; ++f)
              {
                const std::size_t i = local_index(s, f);
                const double m      = sphere_mass * fw[f] * sw[s];
                double v2           = 0.;
                for (unsigned int c = 0; c < 3; ++c)
                  {
                    const double vc = velocity_component(i, c);
                    v2 += vc * vc;
                  }
                kinetic += 0.5 * m * v2;
                defl = std::max(defl, fy[f] - pos[3 * i + 1]);
                pz2[k] += fw[f] * pos[3 * i + 2] * pos[3 * i + 2];
                pz2[n_prof + k] += fw[f];
                zmin = std::min(zmin, pos[3 * i + 2]);
                zmax = std::max(zmax, pos[3 * i + 2]);
                xsum += std::abs(pos[3 * i]);
                // Truss to the next station (the last station uses the one
                // before it for the profile).
                if (s + 1 < n_st)
                  {
                    if (broken[i])
                      {
                        failed += factor * fw[f];
                        fibre_cut[f] = 1.;
                      }
                    else
                      {
                        double l;
                        const double e = truss_strain(i, &l);
                        elastic += 0.5 * truss_k * fw[f] * (l - L0) * (l - L0);
                        smax = std::max(smax, e);
                      }
                  }
                else if (!broken[i - nf])
                  smax = std::max(smax, truss_strain(i - nf));
              }
            pstrain[k] = std::max(pstrain[k], smax);
            pdefl[k]   = std::max(pdefl[k], defl);
            pwidth[k]  = std::max(pwidth[k], z_sym ? 2. * zmax : zmax - zmin);
            ppos[k]    = std::max(ppos[k], xsum / nf);
            buf[0]     = std::max(buf[0], smax);
          }
        // Truss (st_begin - 1, st_begin) belongs to the rank on the left.

        // Contacts.
        for (const ListBlock &B : blocks)
          {
            const std::uint32_t *pstart           = B.pstart.data();
            const std::vector<Pair> &pairs        = B.pairs;
            const std::vector<double> &pxi        = B.pxi;
            const std::vector<MirrorPair> &mpairs = B.mpairs;
            const std::vector<double> &mxi        = B.mxi;
            for (std::size_t i = B.b; i < B.e; ++i)
              for (std::uint32_t p = pstart[i - B.b]; p < pstart[i - B.b + 1];
                   ++p)
                if (pairs[p].w < 0.f)
                  {
                    const std::size_t j = pairs[p].j;
                    double r2           = 0.;
                    for (unsigned int c = 0; c < 3; ++c)
                      r2 += std::pow(pos[3 * i + c] - pos[3 * j + c], 2);
                    const double delta = std::max(0., d - std::sqrt(r2));
                    contact += -pairs[p].w * own_factor(i, j) *
                               fibre_law.energy(delta, &pxi[3 * p]);
                  }
            for (std::size_t p = 0; p < mpairs.size(); ++p)
              if (mpairs[p].active)
                {
                  const std::size_t i = mpairs[p].i, j = mpairs[p].j;
                  const double sx = (mpairs[p].axes & 1) ? -1. : 1.,
                               sz = (mpairs[p].axes & 2) ? -1. : 1.;
                  const double r2 =
                    std::pow(pos[3 * i] - sx * pos[3 * j], 2) +
                    std::pow(pos[3 * i + 1] - pos[3 * j + 1], 2) +
                    std::pow(pos[3 * i + 2] - sz * pos[3 * j + 2], 2);
                  const double delta = std::max(0., d - std::sqrt(r2));
                  contact += mpairs[p].w * (i == j ? 0.5 : 1.) *
                             own_factor(i, j) *
                             fibre_law.energy(delta, &mxi[3 * p]);
                }
          }
        // Projectile contacts of the last force evaluation (the positions
        // have not moved since).
        for (std::size_t i = own_b; i < own_e; ++i)
          if (proj_step[i] == step_count && step_count > 0)
            {
              const unsigned int s = station_of(i), f = i % nf;
              const double ex = pos[3 * i], ey = pos[3 * i + 1] - last_yc;
              const double delta =
                std::max(0., last_Rr - std::sqrt(ex * ex + ey * ey));
              contact +=
                fw[f] * sw[s] * projectile_law.energy(delta, &xi_p[3 * i]);
            }

        double sums[5] = {kinetic, elastic, contact, dissipated_local, failed};
        if (n_ranks > 1)
          {
            MPI_Allreduce(MPI_IN_PLACE, sums, 5, MPI_DOUBLE, MPI_SUM, comm);
            MPI_Allreduce(MPI_IN_PLACE,
                          buf.data(),
                          buf.size(),
                          MPI_DOUBLE,
                          MPI_MAX,
                          comm);
            MPI_Allreduce(MPI_IN_PLACE,
                          pz2.data(),
                          pz2.size(),
                          MPI_DOUBLE,
                          MPI_SUM,
                          comm);
          }
        o.kinetic_energy    = factor * sums[0];
        o.elastic_energy    = factor * sums[1];
        o.contact_energy    = factor * sums[2];
        o.dissipated_energy = factor * sums[3];
        o.n_failed          = static_cast<unsigned long>(sums[4] + 0.5);
        o.max_strain        = std::max(0., buf[0]);

        Analysis::StationProfile profile;
        profile.resize(n_prof);
        for (unsigned int k = 0; k < n_prof; ++k)
          {
            profile.position[k]      = ppos[k];
            profile.axial_strain[k]  = pstrain[k];
            profile.deflection[k]    = pdefl[k];
            profile.width[k]         = pwidth[k];
            profile.initial_width[k] = initial_width[k];
            profile.rms_width[k] =
              4. * std::sqrt(pz2[k] / std::max(pz2[n_prof + k], 1e-300));
          }
        o.fronts = Analysis::measure_wave_fronts(profile, shared.wave_fronts);
        bool all_cut = nf > 0;
        for (unsigned int f = 0; f < nf; ++f)
          all_cut = all_cut && fibre_cut[f] > 0.;
        cut_through = all_cut;
        return o;
      }
      std::string
      Model::write_snapshot(const std::string &directory,
                            const unsigned int index,
                            const double) const
      {
        // Owned cross-sections plus the first ghost one on the right, so the
        // trusses across the rank boundary are drawn.
        const unsigned int p_end = std::min(st_end + 1, g_hi);
        std::vector<float> points;
        std::vector<std::int32_t> lines;
        std::vector<VTU::Array> pd(4), cd(3);
        pd[0] = {"fibre_id", "Int32", 1, {}};
        pd[1] = {"displacement", "Float32", 3, {}};
        pd[2] = {"velocity", "Float32", 3, {}};
        pd[3] = {"axial_strain", "Float32", 1, {}};
        cd[0] = {"strain", "Float32", 1, {}};
        cd[1] = {"force", "Float32", 1, {}};
        cd[2] = {"broken", "UInt8", 1, {}};
        for (unsigned int s = st_begin; s < p_end; ++s)
          for (unsigned int f = 0; f < nf; ++f)
            {
              const std::size_t i = local_index(s, f);
              const double X0[3]  = {sx0[s], fy[f], fz[f]};
              for (unsigned int c = 0; c < 3; ++c)
                {
                  points.push_back(static_cast<float>(pos[3 * i + c]));
                  pd[1].push(pos[3 * i + c] - X0[c]);
                  pd[2].push(s < st_end ? velocity_component(i, c)
                                        : vel[3 * i + c]);
                }
              pd[0].push(f);
              double e = 0.;
              if (s + 1 < n_st && !broken[i])
                e = std::max(e, truss_strain(i));
              if (s > lo && !broken[i - nf])
                e = std::max(e, truss_strain(i - nf));
              pd[3].push(e);
              if (s + 1 < p_end)
                {
                  const std::int32_t a =
                    static_cast<std::int32_t>((s - st_begin) * nf + f);
                  lines.push_back(a);
                  lines.push_back(a + static_cast<std::int32_t>(nf));
                  const double strain = truss_strain(i);
                  cd[0].push(strain);
                  cd[1].push(broken[i] ? 0. : truss_k * fw[f] * strain * L0);
                  cd[2].push(static_cast<unsigned int>(broken[i]));
                }
            }
        std::ostringstream base;
        base << "dem_" << std::setw(4) << std::setfill('0') << index;
        const std::string piece =
          base.str() + "_r" + std::to_string(rank) + ".vtu";
        VTU::write_piece(directory + "/" + piece, points, lines, pd, cd);
        if (rank == 0)
          {
            std::vector<std::string> pieces;
            for (unsigned int q = 0; q < n_ranks; ++q)
              pieces.push_back(base.str() + "_r" + std::to_string(q) + ".vtu");
            VTU::write_record(directory + "/" + base.str() + ".pvtu",
                              pieces,
                              pd,
                              cd);
          }
        MPI_Barrier(comm);
        return base.str() + ".pvtu";
      }
    } // namespace


    std::string
    statistics(const ImpactModel &model)
    {
      const auto *m = dynamic_cast<const Model *>(&model);
      return m ? m->statistics() : std::string();
    }


    std::unique_ptr<ImpactModel>
    create_model(const YarnImpact::Parameters::Shared &shared,
                 const Parameters &parameters,
                 const MPI_Comm communicator)
    {
      return std::make_unique<Model>(shared, parameters, communicator);
    }
  } // namespace DEM
} // namespace YarnImpact
