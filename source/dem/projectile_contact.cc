// The contact of the rigid cylindrical projectile with the spheres of the
// DEM impact model.
#pragma GCC optimize("O3")

#include <yarn_impact/core/projectile.h>
#include <yarn_impact/dem/forces.h>

#include <cmath>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      double
      projectile_contact_forces(const Projectile &projectile,
                                const ContactLaw &law,
                                const FibreChains &chains,
                                const Decomposition &decomposition,
                                Spheres &spheres,
                                const double dt,
                                ProjectileContactState &contact,
                                double &dissipated)
      {
        const double *__restrict x          = spheres.pos.data();
        const double *__restrict v          = spheres.vel.data();
        double *__restrict F                = spheres.frc.data();
        double *__restrict xi_p             = spheres.xi_p.data();
        std::uint64_t *__restrict proj_step = spheres.proj_step.data();
        const std::uint64_t step_count      = spheres.step_count;
        const unsigned int nf               = chains.nf;
        double diss_sum                     = dissipated;

        // Only cross-sections that can reach the projectile.
        const double yc = projectile.axis_position();
        const double vp = projectile.velocity();
        const double Rr = projectile.radius() + chains.radius;
        double reaction = 0.;
        contact.yc      = yc;
        contact.Rr      = Rr;
        for (unsigned int s = decomposition.st_begin; s < decomposition.st_end;
             ++s)
          {
            const double xlo = spheres.st_xlo[s], xhi = spheres.st_xhi[s];
            const double ax = (xlo > 0. ? xlo : (xhi < 0. ? -xhi : 0.));
            if (ax >= Rr || spheres.st_ymax[s] <= yc - Rr)
              continue;
            const std::size_t b0 = decomposition.local_index(s, 0);
            for (unsigned int f = 0; f < nf; ++f)
              {
                const std::size_t i = b0 + f;
                const double ex = x[3 * i], ey = x[3 * i + 1] - yc;
                const double r2 = ex * ex + ey * ey;
                if (r2 >= Rr * Rr)
                  continue;
                // A new contact starts without tangential history.
                if (proj_step[i] + 1 != step_count)
                  xi_p[3 * i] = xi_p[3 * i + 1] = xi_p[3 * i + 2] = 0.;
                proj_step[i]       = step_count;
                const double rho   = std::sqrt(r2);
                const double n[3]  = {ex / rho, ey / rho, 0.};
                const double vr[3] = {v[3 * i],
                                      v[3 * i + 1] - vp,
                                      v[3 * i + 2]};
                double fc[3], diss = 0.;
                law.force(Rr - rho, n, vr, dt, &xi_p[3 * i], fc, diss);
                const double w = chains.fw[f] * chains.sw[s];
                F[3 * i] += w * fc[0];
                F[3 * i + 1] += w * fc[1];
                F[3 * i + 2] += w * fc[2];
                reaction -= w * fc[1];
                diss_sum += w * diss;
              }
          }
        dissipated = diss_sum;
        return reaction;
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
