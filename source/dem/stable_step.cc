// The DEM's critical time step from the springs it has now: twice the
// largest eigenvalue of a sphere's own stiffness block over its mass
// (doc/theory.md section 3.2).

#include <yarn_impact/dem/stable_step.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      namespace
      {
        /** The largest eigenvalue of the symmetric 3x3 matrix @p K (xx,
         * yy, zz, xy, xz, yz) times @p scale, in closed form (the
         * trigonometric solution of the characteristic cubic), or @p floor
         * if that cannot exceed it: the closed form's q + 2 p bounds the
         * eigenvalue with one square root, and the cosines are only
         * evaluated where it could set a new maximum. */
        double
        largest_eigenvalue(const float *K,
                           const double scale,
                           const double floor)
        {
          const double a = K[0], b = K[1], c = K[2], d = K[3], e = K[4],
                       f  = K[5];
          const double q  = (a + b + c) / 3.;
          const double p1 = d * d + e * e + f * f;
          const double p2 =
            (a - q) * (a - q) + (b - q) * (b - q) + (c - q) * (c - q) + 2. * p1;
          if (!(p2 > 0.))
            return std::max(floor, scale * q);
          const double p = std::sqrt(p2 / 6.);
          if (scale * (q + 2. * p) <= floor)
            return floor;
          // det((A - q I) / p) / 2
          const double A = (a - q) / p, B = (b - q) / p, C = (c - q) / p;
          const double D = d / p, E = e / p, F = f / p;
          const double r   = 0.5 * (A * (B * C - F * F) - D * (D * C - F * E) +
                                  E * (D * F - B * E));
          const double phi = std::acos(std::clamp(r, -1., 1.)) / 3.;
          return std::max(floor, scale * (q + 2. * p * std::cos(phi)));
        }


        /** @p v normalised in place; its former length. */
        double
        normalise(double *v)
        {
          const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
          v[0] /= l;
          v[1] /= l;
          v[2] /= l;
          return l;
        }


        /** Add to the stiffness block @p K (xx, yy, zz, xy, xz, yz) [N/m]
         * a spring of stiffness @p along [N/m] in the unit direction @p d
         * and @p across [N/m] in every direction across it:
         * along d d^T + across (I - d d^T). The tangential spring of a
         * contact is the second part, whatever the frame its history is
         * kept in. */
        void
        add_spring(float *K,
                   const double *d,
                   const double along,
                   const double across)
        {
          const double c = along - across;
          K[0] += float(c * d[0] * d[0] + across);
          K[1] += float(c * d[1] * d[1] + across);
          K[2] += float(c * d[2] * d[2] + across);
          K[3] += float(c * d[0] * d[1]);
          K[4] += float(c * d[0] * d[2]);
          K[5] += float(c * d[1] * d[2]);
        }
      } // namespace


      ContactStableStep::ContactStableStep(
        const FibreChains &chains,
        const double fibre_k_n,
        const double fibre_k_t,
        const Contact::ContactConstants &projectile)
        : chains(chains)
        , k_n(fibre_k_n)
        , k_t(fibre_k_t)
        , k_p(projectile.stiffness)
        , k_pt(projectile.tangential_stiffness)
      {}


      double
      ContactStableStep::omega2_bound(const Decomposition &D,
                                      const std::vector<ListBlock> &blocks,
                                      const Spheres &spheres,
                                      const double projectile_y,
                                      const double Rr,
                                      const double projectile_margin) const
      {
        const double *x       = spheres.pos.data();
        const unsigned int nf = chains.nf;
        const double d        = chains.d;

        // The diagonal blocks K_ii = sum_f k_f d_f d_f^T of the owned
        // spheres (xx, yy, zz, xy, xz, yz); float is enough for a bound (the
        // margin at the end covers its rounding) and keeps the memory low.
        blocks_ii.assign(6 * (D.own_e - D.own_b), 0.f);
        const auto add = [&](const std::size_t i,
                             const double *dir,
                             const double along,
                             const double across) {
          if (i >= D.own_b && i < D.own_e)
            add_spring(&blocks_ii[6 * (i - D.own_b)], dir, along, across);
        };

        // Trusses with an owned end: along them, and across them the
        // geometric stiffness T/l = k (1 - L0/l) of a stretched truss.
        const unsigned int t_begin =
          std::max(D.g_lo, D.st_begin > 0 ? D.st_begin - 1 : 0u);
        const unsigned int t_end =
          std::min({D.st_end, chains.n_st - 1, D.g_hi - 1});
        for (unsigned int s = t_begin; s < t_end; ++s)
          for (unsigned int f = 0; f < nf; ++f)
            {
              const std::size_t i = D.local_index(s, f), j = i + nf;
              if (spheres.broken[i])
                continue;
              double e[3]    = {x[3 * j] - x[3 * i],
                                x[3 * j + 1] - x[3 * i + 1],
                                x[3 * j + 2] - x[3 * i + 2]};
              const double l = normalise(e);
              const double k =
                chains.truss_k * chains.fibre_symmetry_weight[f] * chains.tw[s];
              const double kg = k * std::max(0., 1. - chains.L0 / l);
              add(i, e, k, kg);
              add(j, e, k, kg);
            }

        // Fibre pairs in contact: the normal spring and the tangential one
        // across it. Only these: every contact is listed whatever the
        // partition or the list rebuilds, but a pair near contact is listed
        // or not depending on when the lists were built, and the step must
        // not depend on that.
        const double d2 = d * d;
        for (const ListBlock &B : blocks)
          for (std::size_t i = B.row_sphere_begin; i < B.row_sphere_end; ++i)
            for (std::uint32_t p = B.pstart[i - B.row_sphere_begin];
                 p < B.pstart[i - B.row_sphere_begin + 1];
                 ++p)
              {
                // The force evaluation at these positions marked the pairs
                // in contact (a negative weight).
                if (B.pairs[p].w >= 0.f)
                  continue;
                const std::size_t j = B.pairs[p].j;
                double n[3]         = {x[3 * i] - x[3 * j],
                                       x[3 * i + 1] - x[3 * j + 1],
                                       x[3 * i + 2] - x[3 * j + 2]};
                if (n[0] * n[0] + n[1] * n[1] + n[2] * n[2] >= d2)
                  continue;
                normalise(n);
                const double w = std::abs(B.pairs[p].w);
                add(i, n, w * k_n, w * k_t);
                add(j, n, w * k_n, w * k_t);
              }

        // Mirror pairs in contact: the image of j moves as S u_j, so the
        // spring stretches along S n at j. A sphere against its own image
        // has both ends at i, and its force is twice the pair's for one
        // displacement: half the stiffness at each of the two ends.
        for (const ListBlock &B : blocks)
          for (const MirrorPair &mp : B.mpairs)
            {
              if (!mp.active)
                continue;
              const std::size_t i = mp.i, j = mp.j;
              const double sx = (mp.axes & 1) ? -1. : 1.,
                           sz = (mp.axes & 2) ? -1. : 1.;
              double n[3]     = {x[3 * i] - sx * x[3 * j],
                                 x[3 * i + 1] - x[3 * j + 1],
                                 x[3 * i + 2] - sz * x[3 * j + 2]};
              if (n[0] * n[0] + n[1] * n[1] + n[2] * n[2] >= d2)
                continue;
              normalise(n);
              const double sn[3] = {sx * n[0], n[1], sz * n[2]};
              const double w     = (i == j ? 0.5 : 1.) * mp.w;
              add(i, n, w * k_n, w * k_t);
              add(j, sn, w * k_n, w * k_t);
            }

        // The projectile, for every owned sphere closer to it than the
        // margin: a spring with one end, k (n . u_i)^2, which needs no
        // factor 2 (the bound below doubles every block, hence the half).
        if (Rr > 0.)
          {
            const double reach = Rr + projectile_margin;
            for (unsigned int s = D.st_begin; s < D.st_end; ++s)
              {
                const double xlo = spheres.st_xlo[s], xhi = spheres.st_xhi[s];
                const double ax = (xlo > 0. ? xlo : (xhi < 0. ? -xhi : 0.));
                if (ax >= reach || spheres.st_ymax[s] <= projectile_y - reach)
                  continue;
                for (unsigned int f = 0; f < nf; ++f)
                  {
                    const std::size_t i = D.local_index(s, f);
                    double n[3] = {x[3 * i], x[3 * i + 1] - projectile_y, 0.};
                    const double rho = std::sqrt(n[0] * n[0] + n[1] * n[1]);
                    if (!(rho < reach) || rho == 0.)
                      continue;
                    n[0] /= rho;
                    n[1] /= rho;
                    const double w = 0.5 * chains.fibre_symmetry_weight[f] *
                                     chains.station_symmetry_weight[s] *
                                     chains.cw[s];
                    add(i, n, w * k_p, w * k_pt);
                  }
              }
          }

        // u^T K u = sum_e k_e (d_e . (u_i - u_j))^2 <= 2 sum_i u_i^T K_ii u_i
        // <= 2 max_i lambda_max(K_ii / m_i) u^T M u.
        double lambda = 0.;
        for (std::size_t i = D.own_b; i < D.own_e; ++i)
          {
            const double inv_m =
              chains.fibre_inverse_mass[i % nf] *
              chains.station_inverse_mass_factor[D.station_of(i)];
            if (inv_m == 0.)
              continue;
            float *K = &blocks_ii[6 * (i - D.own_b)];
            // A sphere on a symmetry plane stands for itself and its image:
            // its block is the whole sphere's, K + S K S over two (it has
            // half the mass and half the springs in the plane), so that the
            // step is the full model's.
            if (chains.station_symmetry_weight[D.station_of(i)] != 1.)
              K[3] = K[4] = 0.f; // x = 0: xy, xz
            if (chains.fibre_symmetry_weight[i % nf] != 1.)
              K[4] = K[5] = 0.f; // z = 0: xz, yz
            lambda = largest_eigenvalue(K, inv_m, lambda);
          }
        // The float sums and the closed-form eigenvalue are good to a few
        // 1e-7: the margin keeps the result a bound.
        return 2. * (1. + 1e-5) * dealii::Utilities::MPI::max(lambda, D.comm);
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
