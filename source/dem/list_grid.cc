// The cell grid of a neighbour-list block's build, made again from the
// build positions where the block does not hold it (after a restart: it is
// derived data, not stored), for the partial searches of the DEM impact
// model (doc/dem.md section 4, "Partial searches"; list_partial.cc).

#include <yarn_impact/dem/neighbour_lists.h>

#include <algorithm>
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
      NeighbourLists::make_build_grid(ListBlock &B)
      {
        // The grid of the build (list_build.cc) from the single-precision
        // build positions, over the spheres that are not fast (the fast
        // ones are looked up in their own grid). The x-bins are the build's;
        // their origin, not stored, is placed from the spheres: x - b h is
        // between it and one bin width above it, hence the slack.
        const std::size_t sb = B.row_sphere_begin, n = B.fast.size();
        const unsigned int n_bins = B.n_bins;
        B.grid_x0                 = infinity;
        B.grid_y0.assign(n_bins, infinity);
        B.grid_z0.assign(n_bins, infinity);
        std::vector<double> &y1 = cell_y, &z1 = cell_z; // scratch
        y1.assign(n_bins, -infinity);
        z1.assign(n_bins, -infinity);
        std::vector<std::uint32_t> &count = bin_start; // scratch
        count.assign(n_bins, 0);
        for (std::size_t k = 0; k < n; ++k)
          if (!B.fast[k])
            {
              const std::uint32_t b = B.bin_of[k];
              const double y        = B.pos_build[3 * k + 1],
                           z        = B.pos_build[3 * k + 2];
              B.grid_x0 = std::min(B.grid_x0, B.pos_build[3 * k] - b * cutoff);
              B.grid_y0[b] = std::min(B.grid_y0[b], y);
              y1[b]        = std::max(y1[b], y);
              B.grid_z0[b] = std::min(B.grid_z0[b], z);
              z1[b]        = std::max(z1[b], z);
              ++count[b];
            }
        B.grid_ic.resize(n_bins);
        B.grid_ny.resize(n_bins);
        B.grid_nz.resize(n_bins);
        B.grid_cell_off.assign(n_bins + 1, 0);
        for (unsigned int b = 0; b < n_bins; ++b)
          {
            if (count[b] == 0)
              B.grid_y0[b] = y1[b] = B.grid_z0[b] = z1[b] = 0.;
            double c = cutoff;
            while ((y1[b] - B.grid_y0[b]) / c * (z1[b] - B.grid_z0[b]) / c >
                   16. * count[b] + 64.)
              c *= 2.;
            B.grid_ic[b] = 1. / c;
            B.grid_ny[b] =
              static_cast<std::uint32_t>((y1[b] - B.grid_y0[b]) / c) + 1;
            B.grid_nz[b] =
              static_cast<std::uint32_t>((z1[b] - B.grid_z0[b]) / c) + 1;
            B.grid_cell_off[b + 1] =
              B.grid_cell_off[b] + B.grid_ny[b] * B.grid_nz[b];
          }
        std::vector<std::uint32_t> &cell_of = near_sphere; // scratch
        cell_of.assign(n, 0);
        B.grid_cell_start.assign(B.grid_cell_off[n_bins] + 1, 0);
        for (std::size_t k = 0; k < n; ++k)
          if (!B.fast[k])
            {
              const std::uint32_t b = B.bin_of[k];
              const auto cy         = static_cast<std::uint32_t>(
                (B.pos_build[3 * k + 1] - B.grid_y0[b]) * B.grid_ic[b]);
              const auto cz = static_cast<std::uint32_t>(
                (B.pos_build[3 * k + 2] - B.grid_z0[b]) * B.grid_ic[b]);
              cell_of[k] = B.grid_cell_off[b] +
                           std::min(cy, B.grid_ny[b] - 1) * B.grid_nz[b] +
                           std::min(cz, B.grid_nz[b] - 1);
              ++B.grid_cell_start[cell_of[k] + 1];
            }
        for (std::uint32_t c = 0; c < B.grid_cell_off[n_bins]; ++c)
          B.grid_cell_start[c + 1] += B.grid_cell_start[c];
        B.grid_cell_sphere.resize(B.grid_cell_start.back());
        std::vector<std::uint32_t> fill(B.grid_cell_start.begin(),
                                        B.grid_cell_start.end() - 1);
        for (std::size_t k = 0; k < n; ++k)
          if (!B.fast[k])
            B.grid_cell_sphere[fill[cell_of[k]]++] = sb + k;
        B.grid_x_slack = cutoff;
        B.has_grid     = true;
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
