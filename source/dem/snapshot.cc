// The VTU snapshots of the DEM impact model: one piece per rank, a record
// on rank 0.

#include <yarn_impact/dem/integration.h>
#include <yarn_impact/dem/observables.h>
#include <yarn_impact/dem/vtu_writer.h>

#include <algorithm>
#include <cstdint>
#include <iomanip>
#include <sstream>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      std::string
      write_snapshot(const FibreChains &chains,
                     const Decomposition &decomposition,
                     const Spheres &spheres,
                     const std::string &directory,
                     const unsigned int index)
      {
        const unsigned int nf = chains.nf, n_st = chains.n_st;
        const double L0 = chains.L0, truss_k = chains.truss_k;
        const unsigned int st_begin = decomposition.st_begin,
                           st_end   = decomposition.st_end,
                           g_hi = decomposition.g_hi, lo = decomposition.lo;
        const std::vector<double> &station_x0 = chains.station_x0,
                                  &fibre_y0   = chains.fibre_y0,
                                  &fibre_z0   = chains.fibre_z0,
                                  &fibre_symmetry_weight =
                                    chains.fibre_symmetry_weight;
        const std::vector<double> &pos = spheres.pos, &vel = spheres.vel;
        const double *x                         = pos.data();
        const std::vector<std::uint8_t> &broken = spheres.broken;

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
              const std::size_t i = decomposition.local_index(s, f);
              const double X0[3]  = {station_x0[s], fibre_y0[f], fibre_z0[f]};
              for (unsigned int c = 0; c < 3; ++c)
                {
                  points.push_back(static_cast<float>(pos[3 * i + c]));
                  pd[1].push(pos[3 * i + c] - X0[c]);
                  pd[2].push(
                    s < st_end
                      ? kicked_velocity(chains, decomposition, spheres, i, c)
                      : vel[3 * i + c]);
                }
              pd[0].push(f);
              double e = 0.;
              if (s + 1 < n_st && !broken[i])
                e = std::max(e, truss_strain(x, i, nf, L0));
              if (s > lo && !broken[i - nf])
                e = std::max(e, truss_strain(x, i - nf, nf, L0));
              pd[3].push(e);
              if (s + 1 < p_end)
                {
                  const std::int32_t a =
                    static_cast<std::int32_t>((s - st_begin) * nf + f);
                  lines.push_back(a);
                  lines.push_back(a + static_cast<std::int32_t>(nf));
                  const double strain = truss_strain(x, i, nf, L0);
                  cd[0].push(strain);
                  cd[1].push(broken[i] ? 0.
                                       : truss_k * fibre_symmetry_weight[f] *
                                           strain * L0);
                  cd[2].push(static_cast<unsigned int>(broken[i]));
                }
            }
        std::ostringstream base;
        base << (chains.clamp_part ? "dem_clamp_" : "dem_") << std::setw(4)
             << std::setfill('0') << index;
        return VTU::write_parallel(directory,
                                   base.str(),
                                   points,
                                   lines,
                                   pd,
                                   cd,
                                   decomposition.comm);
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
