// The neighbour lists of the periodic segment of the DEM elementary tests:
// a cell search on the section plane with the nearest periodic image along
// x, keeping the tangential history of the pairs listed before.
#include <yarn_impact/dem/elementary/periodic_segment.h>

#include <algorithm>
#include <limits>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      void
      PeriodicSegment::build_lists()
      {
        // Cells of side >= cutoff on the (y, z) plane; the segment is short
        // along x, so every station of a cell is searched with the nearest
        // periodic image.
        double lo[2] = {std::numeric_limits<double>::max(),
                        std::numeric_limits<double>::max()},
               hi[2] = {-lo[0], -lo[1]};
        for (std::size_t i = 0; i < n; ++i)
          for (unsigned int c = 0; c < 2; ++c)
            {
              lo[c] = std::min(lo[c], x[3 * i + 1 + c]);
              hi[c] = std::max(hi[c], x[3 * i + 1 + c]);
            }
        unsigned int nc[2];
        for (unsigned int c = 0; c < 2; ++c)
          nc[c] = 1 + static_cast<unsigned int>((hi[c] - lo[c]) / cutoff);
        std::vector<std::uint32_t> cell_of(n), cell_start(nc[0] * nc[1] + 1, 0);
        for (std::size_t i = 0; i < n; ++i)
          {
            const unsigned int cy =
                                 std::min<unsigned int>(nc[0] - 1,
                                                        (x[3 * i + 1] - lo[0]) /
                                                          cutoff),
                               cz =
                                 std::min<unsigned int>(nc[1] - 1,
                                                        (x[3 * i + 2] - lo[1]) /
                                                          cutoff);
            cell_of[i] = cy * nc[1] + cz;
            ++cell_start[cell_of[i] + 1];
          }
        for (unsigned int c = 0; c < nc[0] * nc[1]; ++c)
          cell_start[c + 1] += cell_start[c];
        std::vector<std::uint32_t> sorted(n), fill(cell_start);
        for (std::size_t i = 0; i < n; ++i)
          sorted[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);

        // New lists, each sorted by neighbour, keeping the tangential
        // history of the pairs that were listed before.
        std::vector<std::uint32_t> new_start(1, 0), new_neighbour;
        std::vector<std::uint8_t> new_touching;
        std::vector<double> new_history;
        const double c2 = cutoff * cutoff;
        std::vector<std::uint32_t> found;
        for (std::size_t i = i_begin; i < i_end; ++i)
          {
            found.clear();
            const int cy = static_cast<int>(cell_of[i] / nc[1]),
                      cz = static_cast<int>(cell_of[i] % nc[1]);
            for (int dy = -1; dy <= 1; ++dy)
              for (int dz = -1; dz <= 1; ++dz)
                {
                  const int y = cy + dy, z = cz + dz;
                  if (y < 0 || z < 0 || y >= static_cast<int>(nc[0]) ||
                      z >= static_cast<int>(nc[1]))
                    continue;
                  const unsigned int c = y * nc[1] + z;
                  for (std::uint32_t k = cell_start[c]; k < cell_start[c + 1];
                       ++k)
                    {
                      const std::uint32_t j = sorted[k];
                      if (j == i)
                        continue;
                      double ex       = x[3 * j] - x[3 * i];
                      ex              = nearest_image(ex, Lx);
                      const double ey = x[3 * j + 1] - x[3 * i + 1],
                                   ez = x[3 * j + 2] - x[3 * i + 2];
                      if (ex * ex + ey * ey + ez * ez < c2)
                        found.push_back(j);
                    }
                }
            std::sort(found.begin(), found.end());
            const std::size_t li      = i - i_begin;
            std::uint32_t p           = (start.empty() ? 0 : start[li]);
            const std::uint32_t p_end = (start.empty() ? 0 : start[li + 1]);
            for (const std::uint32_t j : found)
              {
                while (p < p_end && neighbour[p] < j)
                  ++p;
                const bool kept = (p < p_end && neighbour[p] == j);
                new_neighbour.push_back(j);
                new_touching.push_back(kept ? touching[p] : 0);
                for (unsigned int c = 0; c < 3; ++c)
                  new_history.push_back(kept ? history[3 * p + c] : 0.);
              }
            new_start.push_back(
              static_cast<std::uint32_t>(new_neighbour.size()));
          }
        start.swap(new_start);
        neighbour.swap(new_neighbour);
        touching.swap(new_touching);
        history.swap(new_history);
        x_built = x;
        ++n_rebuilds;
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
