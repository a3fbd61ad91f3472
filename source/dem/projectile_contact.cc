// The contact of the rigid cylindrical projectile with the spheres of the
// DEM impact model, by the law of DEM/Projectile contact law
// (contact/contact_law.h).

#include <yarn_impact/contact/projectile_contact.h>
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
                                const Contact::LawType law_type,
                                const Contact::ContactConstants &constants,
                                const FibreChains &chains,
                                const Decomposition &decomposition,
                                Spheres &spheres,
                                const double dt,
                                ProjectileContactState &contact)
      {
        const double *__restrict x = spheres.pos.data();
        const double *__restrict v = spheres.vel.data();
        double *__restrict F       = spheres.force.data();
        double *__restrict projectile_tangential_displacement =
          spheres.projectile_tangential_displacement.data();
        std::uint64_t *__restrict proj_step = spheres.proj_step.data();
        const std::uint64_t step_count      = spheres.step_count;
        const unsigned int nf               = chains.nf;
        double *__restrict dissipated       = spheres.dissipated.data();

        // Only cross-sections that can reach the projectile; a sphere
        // centre touches it within the projectile's radius plus its own.
        const double yc = projectile.axis_position();
        const double vp = projectile.velocity();
        const double Rr = projectile.radius() + chains.radius;
        double reaction = 0.;
        contact.yc      = yc;
        contact.Rr      = Rr;
        // The law is chosen once per call; the loop over the spheres is
        // instantiated for each law.
        Contact::with_contact_law(law_type, [&](auto tag) {
          using Law = typename decltype(tag)::type;
          static_assert(Law::history_size <= 3,
                        "a sphere keeps 3 doubles of projectile history");
          const Law law(constants);
          for (unsigned int s = decomposition.st_begin;
               s < decomposition.st_end;
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
                  double delta, n[3];
                  if (!Contact::projectile_overlap(x[3 * i],
                                                   x[3 * i + 1],
                                                   yc,
                                                   Rr,
                                                   delta,
                                                   n))
                    continue;
                  // A new contact starts without tangential history.
                  if (proj_step[i] + 1 != step_count)
                    for (unsigned int c = 0; c < Law::history_size; ++c)
                      projectile_tangential_displacement[3 * i + c] = 0.;
                  proj_step[i] = step_count;
                  double vr[3];
                  Contact::relative_to_projectile(&v[3 * i], vp, vr);
                  double fc[3], diss = 0.;
                  Contact::contact_force(
                    law,
                    delta,
                    n,
                    vr,
                    dt,
                    &projectile_tangential_displacement[3 * i],
                    fc,
                    diss);
                  const double w = chains.fibre_symmetry_weight[f] *
                                   chains.station_symmetry_weight[s] *
                                   chains.cw[s];
                  F[3 * i] += w * fc[0];
                  F[3 * i + 1] += w * fc[1];
                  F[3 * i + 2] += w * fc[2];
                  reaction -= w * fc[1];
                  dissipated[i] += w * diss;
                }
            }
        });
        return reaction;
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
