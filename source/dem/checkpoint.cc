// The DEM's state in a checkpoint (core/checkpoint.h): every array that a
// step reads and that the set-up does not rebuild identically. The
// neighbour lists are written whole, not rebuilt at the restart: a rebuild
// would list the pairs in another order, and the forces would be summed in
// another order (a restarted run must make bitwise the same steps).
#include <yarn_impact/dem/decomposition.h>
#include <yarn_impact/dem/neighbour_lists.h>
#include <yarn_impact/dem/spheres.h>

#include <string>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      void
      Spheres::save(Checkpoint::Writer &out) const
      {
        out.tag("dem spheres");
        out.put(pos);
        out.put(vel);
        out.put(force);
        out.put(broken);
        out.put(projectile_tangential_displacement);
        out.put(proj_step);
        out.put(dissipated);
        out.put(break_time);
        out.put(time);
        out.put(st_xlo);
        out.put(st_xhi);
        out.put(st_ymax);
        out.put(pending_kick);
        out.put(forces_consumed);
        out.put(step_count);
      }

      void
      Spheres::load(Checkpoint::Reader &in)
      {
        in.tag("dem spheres");
        in.get_same_size(pos, "sphere positions");
        in.get_same_size(vel, "sphere velocities");
        in.get_same_size(force, "sphere forces");
        in.get_same_size(broken, "truss states");
        in.get_same_size(projectile_tangential_displacement,
                         "projectile contact histories");
        in.get_same_size(proj_step, "projectile contact steps");
        in.get_same_size(dissipated, "dissipated energies");
        in.get_same_size(break_time, "truss break times");
        in.get(time);
        in.get_same_size(st_xlo, "cross-section extents");
        in.get_same_size(st_xhi, "cross-section extents");
        in.get_same_size(st_ymax, "cross-section heights");
        in.get(pending_kick);
        in.get(forces_consumed);
        in.get(step_count);
      }


      void
      Decomposition::save(Checkpoint::Writer &out) const
      {
        out.tag("dem decomposition");
        out.put(slab_starts);
        out.put(n_local);
        out.put(g_lo);
        out.put(g_hi);
        out.put(act_b);
        out.put(act_e);
        out.put(ghost_lo);
        out.put(ghost_hi);
        out.put(n_ghost_growths);
      }

      void
      Decomposition::load(Checkpoint::Reader &in)
      {
        in.tag("dem decomposition");
        std::vector<unsigned int> starts;
        in.get(starts);
        if (starts != slab_starts)
          throw InputError("the DEM checkpoint was written with another "
                           "slab layout of the cross-sections over the "
                           "ranks.");
        std::size_t n = 0;
        in.get(n);
        if (n != n_local)
          throw InputError("the DEM checkpoint holds " + std::to_string(n) +
                           " spheres on this rank, this set-up " +
                           std::to_string(n_local) + ".");
        in.get(g_lo);
        in.get(g_hi);
        in.get(act_b);
        in.get(act_e);
        in.get_same_size(ghost_lo, "ghost layers");
        in.get_same_size(ghost_hi, "ghost layers");
        in.get(n_ghost_growths);
      }


      void
      NeighbourLists::save(Checkpoint::Writer &out) const
      {
        out.tag("dem neighbour lists");
        out.put(static_cast<std::uint64_t>(blocks.size()));
        for (const ListBlock &B : blocks)
          {
            out.put(B.s_begin);
            out.put(B.s_end);
            out.put(B.row_begin);
            out.put(B.row_end);
            out.put(B.halo_end);
            out.put(B.row_sphere_begin);
            out.put(B.row_sphere_end);
            out.put(B.halo_sphere_end);
            out.put(B.stale);
            out.put(B.holds_plane);
            out.put(B.pstart);
            out.put(B.pstart_old);
            out.put(B.pairs);
            out.put(B.pairs_old);
            out.put(B.pair_tangential_displacement);
            out.put(B.pair_tangential_displacement_old);
            out.put(B.mpairs);
            out.put(B.mpairs_old);
            out.put(B.mirror_tangential_displacement);
            out.put(B.mirror_tangential_displacement_old);
            out.put(B.pos_build);
            out.put(B.bin_of);
            out.put(B.n_bins);
            out.put(B.bin_count);
            out.put(B.bin_mean_displacement);
            out.put(B.bin_displacement_sum);
            out.put(B.r2_max);
            out.put(B.bound);
            out.put(B.searched);
            out.put(B.fast);
            out.put(B.pos_search);
            out.put(B.bin_of_search);
            out.put(B.n_bins_search);
            out.put(B.bin_count_search);
            out.put(B.search_mean_displacement);
            out.put(B.search_displacement_sum);
            out.put(B.r2_search);
            out.put(B.r2_search_fast);
          }
        out.put(station_block);
        out.put(n_rebuilds);
        out.put(rebuilt_rows);
        out.put(n_searched);
        out.put(n_candidates);
        out.put(n_partial);
        out.put(partial_spheres);
        out.put(last_r);
        out.put(last_g);
      }

      void
      NeighbourLists::load(Checkpoint::Reader &in)
      {
        in.tag("dem neighbour lists");
        std::uint64_t n = 0;
        in.get(n);
        if (n != blocks.size())
          throw InputError("the DEM checkpoint holds " + std::to_string(n) +
                           " neighbour-list blocks on this rank, this set-up " +
                           std::to_string(blocks.size()) + ".");
        for (ListBlock &B : blocks)
          {
            in.get(B.s_begin);
            in.get(B.s_end);
            in.get(B.row_begin);
            in.get(B.row_end);
            in.get(B.halo_end);
            in.get(B.row_sphere_begin);
            in.get(B.row_sphere_end);
            in.get(B.halo_sphere_end);
            in.get(B.stale);
            in.get(B.holds_plane);
            in.get(B.pstart);
            in.get(B.pstart_old);
            in.get(B.pairs);
            in.get(B.pairs_old);
            in.get(B.pair_tangential_displacement);
            in.get(B.pair_tangential_displacement_old);
            in.get(B.mpairs);
            in.get(B.mpairs_old);
            in.get(B.mirror_tangential_displacement);
            in.get(B.mirror_tangential_displacement_old);
            in.get(B.pos_build);
            in.get(B.bin_of);
            in.get(B.n_bins);
            in.get(B.bin_count);
            in.get(B.bin_mean_displacement);
            in.get(B.bin_displacement_sum);
            in.get(B.r2_max);
            in.get(B.bound);
            in.get(B.searched);
            in.get(B.fast);
            in.get(B.pos_search);
            in.get(B.bin_of_search);
            in.get(B.n_bins_search);
            in.get(B.bin_count_search);
            in.get(B.search_mean_displacement);
            in.get(B.search_displacement_sum);
            in.get(B.r2_search);
            in.get(B.r2_search_fast);
            // The cell grid of the build is not stored (derived data): the
            // one the set-up made is of other positions, and the next
            // partial search makes it again from the build positions.
            B.has_grid = false;
          }
        in.get_same_size(station_block, "block of each cross-section");
        in.get(n_rebuilds);
        in.get(rebuilt_rows);
        in.get(n_searched);
        in.get(n_candidates);
        in.get(n_partial);
        in.get(partial_spheres);
        in.get(last_r);
        in.get(last_g);
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
