// The VTU snapshots of the fibre bars of the hybrid's far field: each rank
// writes its own fibres as one piece, rank 0 the record (the DEM's writer,
// dem/vtu_writer.h: points joined by line cells).

#include <yarn_impact/coupling/fibre_bars.h>
#include <yarn_impact/dem/vtu_writer.h>

#include <cstdint>
#include <iomanip>
#include <sstream>

namespace YarnImpact
{
  namespace Coupling
  {
    std::string
    FibreBars::write_snapshot(const std::string &directory,
                              const unsigned int snapshot) const
    {
      namespace VTU = DEM::VTU;
      std::vector<float> points;
      std::vector<std::int32_t> lines;
      std::vector<VTU::Array> pd(3), cd(3);
      pd[0]              = {"fibre_id", "Int32", 1, {}};
      pd[1]              = {"displacement", "Float32", 3, {}};
      pd[2]              = {"axial_velocity", "Float32", 1, {}};
      cd[0]              = {"strain", "Float32", 1, {}};
      cd[1]              = {"force", "Float32", 1, {}};
      cd[2]              = {"broken", "UInt8", 1, {}};
      std::int32_t first = 0;
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        {
          // The fibre's transverse displacement at a node layer.
          const auto transverse = [&](const unsigned int k,
                                      const unsigned int d) {
            return at_fibre(f, k, d);
          };
          for (unsigned int j = 0; j < n_nodes; ++j)
            {
              double xi;
              const unsigned int c = cell_of(j, xi);
              const double u[3]    = {displacement[index(f, j)],
                                      (1. - xi) * transverse(c, 0) +
                                        xi * transverse(c + 1, 0),
                                      (1. - xi) * transverse(c, 1) +
                                        xi * transverse(c + 1, 1)};
              const double X[3]    = {node_x(j), fibre_y[f], fibre_z[f]};
              // Mirrored bars are written where they stand, at -x.
              const double sign[3] = {mirrored ? -1. : 1., 1., 1.};
              for (unsigned int d = 0; d < 3; ++d)
                {
                  points.push_back(static_cast<float>(sign[d] * (X[d] + u[d])));
                  pd[1].push(sign[d] * u[d]);
                }
              pd[0].push(f);
              pd[2].push(sign[0] * velocity[index(f, j)]);
              if (j + 1 < n_nodes)
                {
                  lines.push_back(first + static_cast<std::int32_t>(j));
                  lines.push_back(first + static_cast<std::int32_t>(j + 1));
                  const bool gone = broken[index(f, j)];
                  const double e  = gone ? 0. : strain[index(f, j)];
                  const unsigned int c_bar =
                    std::min(j / bars_per_cell, n_layers - 2);
                  cd[0].push(e);
                  cd[1].push(cell_weight[c_bar] * stiffness * e * h);
                  cd[2].push(static_cast<unsigned int>(gone));
                }
            }
          first += static_cast<std::int32_t>(n_nodes);
        }
      std::ostringstream base;
      base << (mirrored ? "bars_left_" : "bars_") << std::setw(4)
           << std::setfill('0') << snapshot;
      return VTU::write_parallel(directory,
                                 base.str(),
                                 points,
                                 lines,
                                 pd,
                                 cd,
                                 communicator);
    }
  } // namespace Coupling
} // namespace YarnImpact
