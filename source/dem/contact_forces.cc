// The fibre-fibre contact forces of the DEM impact model: the listed pairs
// and the mirror pairs (contacts with images in the symmetry planes), both
// by the one pair kernel of contact_kernels.h.

#include <yarn_impact/dem/contact_kernels.h>
#include <yarn_impact/dem/forces.h>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      void
      fibre_contact_forces(std::vector<ListBlock> &blocks,
                           const FibreContactLaw &law,
                           const double d,
                           const Decomposition &decomposition,
                           const double *__restrict x,
                           const double *__restrict v,
                           double *__restrict F,
                           const double dt,
                           double *__restrict dissipated)
      {
        const double d2 = d * d;
        // The owned spheres' range, read once: the row loop credits each
        // row's dissipation to its sphere if this rank owns it.
        const std::size_t own_b = decomposition.own_b,
                          own_e = decomposition.own_e;
        for (ListBlock &B : blocks)
          {
            const std::uint32_t *__restrict pstart = B.pstart.data();
            Pair *__restrict pairs                 = B.pairs.data();
            double *__restrict pair_tangential_displacement =
              B.pair_tangential_displacement.data();
            for (std::size_t i = B.row_sphere_begin; i < B.row_sphere_end; ++i)
              {
                const std::uint32_t p0 = pstart[i - B.row_sphere_begin],
                                    p1 = pstart[i - B.row_sphere_begin + 1];
                if (p0 == p1)
                  continue;
                const double x_i = x[3 * i], y_i = x[3 * i + 1],
                             z_i = x[3 * i + 2];
                // The force on i is summed over its row first, then added;
                // so is the energy its row dissipates.
                double fx = 0., fy = 0., fz = 0., row_diss = 0.;
                for (std::uint32_t p = p0; p < p1; ++p)
                  {
                    const std::size_t j = pairs[p].j;
                    double e[3], f[3], diss = 0.;
                    separation(x_i, y_i, z_i, x + 3 * j, 1., 1., e);
                    if (!pair_contact_force(
                          law,
                          d,
                          d2,
                          e,
                          v + 3 * i,
                          v + 3 * j,
                          1.,
                          1.,
                          dt,
                          &pair_tangential_displacement[3 * p],
                          f,
                          diss))
                      {
                        // Separated: the contact ends with its history.
                        if (pairs[p].w < 0.f)
                          {
                            pairs[p].w                          = -pairs[p].w;
                            pair_tangential_displacement[3 * p] = 0.;
                            pair_tangential_displacement[3 * p + 1] = 0.;
                            pair_tangential_displacement[3 * p + 2] = 0.;
                          }
                        continue;
                      }
                    if (pairs[p].w > 0.f)
                      pairs[p].w = -pairs[p].w;
                    const double w = -pairs[p].w;
                    fx += w * f[0];
                    fy += w * f[1];
                    fz += w * f[2];
                    F[3 * j] -= w * f[0];
                    F[3 * j + 1] -= w * f[1];
                    F[3 * j + 2] -= w * f[2];
                    row_diss += w * diss;
                  }
                F[3 * i] += fx;
                F[3 * i + 1] += fy;
                F[3 * i + 2] += fz;
                if (i >= own_b && i < own_e)
                  dissipated[i] += row_diss;
              }
          }
      }


      void
      mirror_contact_forces(std::vector<ListBlock> &blocks,
                            const FibreContactLaw &law,
                            const double d,
                            const Decomposition &decomposition,
                            const double *__restrict x,
                            const double *__restrict v,
                            double *__restrict F,
                            const double dt,
                            double *__restrict dissipated)
      {
        const double d2 = d * d;
        for (ListBlock &B : blocks)
          {
            std::vector<MirrorPair> &mpairs = B.mpairs;
            std::vector<double> &mirror_tangential_displacement =
              B.mirror_tangential_displacement;
            for (std::size_t p = 0; p < mpairs.size(); ++p)
              {
                MirrorPair &mp      = mpairs[p];
                const std::size_t i = mp.i, j = mp.j;
                const double sx = (mp.axes & 1) ? -1. : 1.,
                             sz = (mp.axes & 2) ? -1. : 1.;
                double e[3], f[3], diss = 0.;
                separation(x[3 * i],
                           x[3 * i + 1],
                           x[3 * i + 2],
                           x + 3 * j,
                           sx,
                           sz,
                           e);
                if (!pair_contact_force(law,
                                        d,
                                        d2,
                                        e,
                                        v + 3 * i,
                                        v + 3 * j,
                                        sx,
                                        sz,
                                        dt,
                                        &mirror_tangential_displacement[3 * p],
                                        f,
                                        diss))
                  {
                    if (mp.active)
                      {
                        mp.active = false;
                        mirror_tangential_displacement[3 * p] =
                          mirror_tangential_displacement[3 * p + 1] =
                            mirror_tangential_displacement[3 * p + 2] = 0.;
                      }
                    continue;
                  }
                mp.active      = true;
                const double w = mp.w;
                F[3 * i] += w * f[0];
                F[3 * i + 1] += w * f[1];
                F[3 * i + 2] += w * f[2];
                // j feels the mirror image of the reaction; a self-image
                // pair counts half in the dissipation (it is one contact).
                if (j != i)
                  {
                    F[3 * j] -= w * sx * f[0];
                    F[3 * j + 1] -= w * f[1];
                    F[3 * j + 2] -= w * sz * f[2];
                  }
                if (decomposition.owned(i))
                  dissipated[i] += w * (i == j ? 0.5 : 1.) * diss;
              }
          }
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
