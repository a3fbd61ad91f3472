// The truss forces of the DEM impact model (the fibres' axial stiffness)
// and truss failure.

#include <yarn_impact/dem/forces.h>
#include <yarn_impact/dem/truss.h>

#include <algorithm>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      void
      truss_forces(const FibreChains &chains,
                   const Decomposition &decomposition,
                   const bool failure,
                   const double failure_strain,
                   const double *__restrict x,
                   double *__restrict F,
                   std::uint8_t *__restrict broken,
                   const double time,
                   double *__restrict break_time,
                   double *__restrict dissipated)
      {
        const unsigned int nf    = chains.nf;
        const double L0          = chains.L0;
        const unsigned int first = decomposition.st_begin;
        // Trusses (s, s+1) with at least one owned end.
        const unsigned int t_begin = (first > 0 ? first - 1 : 0);
        const unsigned int t_end =
          std::min(decomposition.st_end, chains.n_st - 1);
        for (unsigned int s = t_begin; s < t_end; ++s)
          {
            const std::size_t b0 = decomposition.local_index(s, 0);
            const double tw      = chains.tw[s];
            for (unsigned int f = 0; f < nf; ++f)
              {
                const std::size_t i = b0 + f, j = i + nf;
                if (broken[i])
                  continue;
                const double e[3] = {x[3 * j] - x[3 * i],
                                     x[3 * j + 1] - x[3 * i + 1],
                                     x[3 * j + 2] - x[3 * i + 2]};
                const double k =
                  chains.truss_k * chains.fibre_symmetry_weight[f] * tw;
                double t[3];
                const double strain = truss_force(e, k, L0, t);
                if (failure && strain > failure_strain)
                  {
                    broken[i]     = 1;
                    break_time[i] = time;
                    if (decomposition.owned(i))
                      dissipated[i] += 0.5 * k * strain * strain * L0 * L0;
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
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
