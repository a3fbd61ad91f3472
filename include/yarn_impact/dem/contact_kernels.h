#ifndef yarn_impact_dem_contact_kernels_h
#define yarn_impact_dem_contact_kernels_h

#include <yarn_impact/contact/contact_law.h>
#include <yarn_impact/dem/parameters.h>

#include <algorithm>
#include <cmath>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      /**
       * The geometry of a sphere pair, written once for the listed pairs
       * and the mirror pairs, for their forces, energies and list checks:
       * the vector @p e [m] from the image (sx x_j, y_j, sz z_j) of sphere j
       * at @p pos_j to sphere i at (@p x_i, @p y_i, @p z_i), and its squared
       * length [m^2] (returned). A listed pair has @p sx = @p sz = 1 (the
       * products are then exact, so the results are those of the plain
       * difference); a mirror image in x = 0 has @p sx = -1, in z = 0
       * @p sz = -1.
       */
      inline double
      separation(const double x_i,
                 const double y_i,
                 const double z_i,
                 const double *pos_j,
                 const double sx,
                 const double sz,
                 double *e)
      {
        e[0] = x_i - sx * pos_j[0];
        e[1] = y_i - pos_j[1];
        e[2] = z_i - sz * pos_j[2];
        return e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
      }


      /**
       * The one sphere-pair contact of the DEM's fibres: the impact model's
       * listed and mirror pairs (their separation by separation()) and the
       * periodic segment of the elementary tests (its separation taken to
       * the nearest periodic image) all call it, so that the contact
       * identified on the segment is the one of the impact runs. With the
       * vector @p e [m] from the image of sphere j to sphere i and the fibre
       * diameter @p d [m] (@p d2 = d^2 [m^2]): if they overlap, the force
       * @p f [N] on i by @p law from the relative velocity of i (@p vi) and
       * the image (@p sx, @p sz as in separation()) of j (@p vj) [m/s], the
       * tangential history @p xi_t [m] (updated) over the step @p dt [s],
       * the energy dissipated in the step added to @p dissipated [J], and
       * true; false (nothing touched) if they do not.
       */
      inline bool
      pair_contact_force(const FibreContactLaw &law,
                         const double d,
                         const double d2,
                         const double *e,
                         const double *vi,
                         const double *vj,
                         const double sx,
                         const double sz,
                         const double dt,
                         double *xi_t,
                         double *f,
                         double &dissipated)
      {
        const double r2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
        if (r2 >= d2)
          return false;
        const double dist  = std::sqrt(r2);
        const double n[3]  = {e[0] / dist, e[1] / dist, e[2] / dist};
        const double vr[3] = {vi[0] - sx * vj[0],
                              vi[1] - vj[1],
                              vi[2] - sz * vj[2]};
        Contact::contact_force(law, d - dist, n, vr, dt, xi_t, f, dissipated);
        return true;
      }


      /**
       * The elastic energy [J] of the contact of sphere i at @p pos_i with
       * (the image of) sphere j at @p pos_j, as separation(), with its
       * tangential history @p xi_t [m]: the energy twin of
       * pair_contact_force(), on the same geometry.
       */
      inline double
      pair_contact_energy(const FibreContactLaw &law,
                          const double d,
                          const double *pos_i,
                          const double *pos_j,
                          const double sx,
                          const double sz,
                          const double *xi_t)
      {
        double e[3];
        const double r2 =
          separation(pos_i[0], pos_i[1], pos_i[2], pos_j, sx, sz, e);
        const double delta = std::max(0., d - std::sqrt(r2));
        return law.energy(delta, xi_t);
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
