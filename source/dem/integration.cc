// Velocity Verlet of the DEM impact model: the kick is applied lazily, fused
// with the next drift (one pass over memory instead of two).

#include <yarn_impact/dem/integration.h>

#include <algorithm>
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


      namespace
      {
        /** The drift of the owned spheres of cross-section @p s (the kick
         * @p as times each fibre's inverse mass, then x += dt v) and their
         * share of the list criterion of its block @p B, searched by a
         * partial search or not (a compile-time choice: the loop tests
         * nothing per sphere); its extents along x and its highest y
         * [m]. */
        template <bool searched>
        void
        drift_cross_section(const FibreChains &chains,
                            const std::size_t b0,
                            const double as,
                            const double xm,
                            const double dt,
                            ListBlock &B,
                            double *__restrict x,
                            double *__restrict v,
                            double *__restrict F,
                            double &xlo,
                            double &xhi,
                            double &ymax)
        {
          const unsigned int nf = chains.nf;
          for (unsigned int f = 0; f < nf; ++f)
            {
              const std::size_t i = b0 + f;
              const double a      = as * chains.fibre_inverse_mass[f];
              v[3 * i] += a * xm * F[3 * i];
              v[3 * i + 1] += a * F[3 * i + 1];
              v[3 * i + 2] += a * chains.zmask[f] * F[3 * i + 2];
              F[3 * i] = F[3 * i + 1] = F[3 * i + 2] = 0.;
              x[3 * i] += dt * v[3 * i];
              x[3 * i + 1] += dt * v[3 * i + 1];
              x[3 * i + 2] += dt * v[3 * i + 2];
              xlo  = std::min(xlo, x[3 * i]);
              xhi  = std::max(xhi, x[3 * i]);
              ymax = std::max(ymax, x[3 * i + 1]);
              accumulate_criterion_of<searched>(B, x, i);
            }
        }
      } // namespace


      void
      drift(const FibreChains &chains,
            const Decomposition &decomposition,
            NeighbourLists &lists,
            Spheres &spheres,
            const double dt)
      {
        const double kick    = spheres.pending_kick;
        spheres.pending_kick = 0.;
        double *__restrict x = spheres.pos.data();
        double *__restrict v = spheres.vel.data();
        double *__restrict F = spheres.force.data();
        for (unsigned int s = decomposition.st_begin; s < decomposition.st_end;
             ++s)
          {
            const double as      = kick * chains.station_inverse_mass_factor[s];
            const double xm      = chains.xmask[s];
            const std::size_t b0 = decomposition.local_index(s, 0);
            ListBlock &B         = lists.block_of(b0);
            double xlo = infinity, xhi = -infinity, ymax = -infinity;
            if (B.searched)
              drift_cross_section<
                true>(chains, b0, as, xm, dt, B, x, v, F, xlo, xhi, ymax);
            else
              drift_cross_section<
                false>(chains, b0, as, xm, dt, B, x, v, F, xlo, xhi, ymax);
            spheres.st_xlo[s]  = xlo;
            spheres.st_xhi[s]  = xhi;
            spheres.st_ymax[s] = ymax;
          }
        spheres.forces_consumed = true;
      }


      void
      clear_forces(const Decomposition &decomposition, Spheres &spheres)
      {
        double *F = spheres.force.data();
        std::fill(F + 3 * decomposition.act_b, F + 3 * decomposition.own_b, 0.);
        std::fill(F + 3 * decomposition.own_e, F + 3 * decomposition.act_e, 0.);
        if (!spheres.forces_consumed)
          std::fill(F + 3 * decomposition.own_b,
                    F + 3 * decomposition.own_e,
                    0.);
        spheres.forces_consumed = false;
      }


      void
      compute_station_extents(const FibreChains &chains,
                              const Decomposition &decomposition,
                              Spheres &spheres,
                              const unsigned int s)
      {
        const std::vector<double> &pos = spheres.pos;
        double xlo = infinity, xhi = -infinity, ymax = -infinity;
        for (unsigned int f = 0; f < chains.nf; ++f)
          {
            const std::size_t i = decomposition.local_index(s, f);
            xlo                 = std::min(xlo, pos[3 * i]);
            xhi                 = std::max(xhi, pos[3 * i]);
            ymax                = std::max(ymax, pos[3 * i + 1]);
          }
        spheres.st_xlo[s]  = xlo;
        spheres.st_xhi[s]  = xhi;
        spheres.st_ymax[s] = ymax;
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
