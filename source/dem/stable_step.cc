// The DEM's critical time step from the springs it has now: twice the
// largest eigenvalue of a sphere's own stiffness block over its mass
// (doc/theory.md section 3.2).
#pragma GCC optimize("O3")

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
        /** The largest eigenvalue of the symmetric 3x3 matrix with the
         * diagonal @p a, @p b, @p c and the off-diagonal @p d (xy), @p e
         * (xz), @p f (yz), in closed form (trigonometric solution of the
         * characteristic cubic). */
        double
        largest_eigenvalue(const double a,
                           const double b,
                           const double c,
                           const double d,
                           const double e,
                           const double f)
        {
          const double q  = (a + b + c) / 3.;
          const double p1 = d * d + e * e + f * f;
          const double p2 = (a - q) * (a - q) + (b - q) * (b - q) +
                            (c - q) * (c - q) + 2. * p1;
          if (!(p2 > 0.))
            return q;
          const double p = std::sqrt(p2 / 6.);
          // det((A - q I) / p) / 2
          const double A = (a - q) / p, B = (b - q) / p, C = (c - q) / p;
          const double D = d / p, E = e / p, F = f / p;
          const double r =
            0.5 * (A * (B * C - F * F) - D * (D * C - F * E) +
                   E * (D * F - B * E));
          const double phi = std::acos(std::clamp(r, -1., 1.)) / 3.;
          return q + 2. * p * std::cos(phi);
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


        /** Two unit vectors @p t1, @p t2 that complete the unit vector
         * @p n to an orthonormal basis, t1 along the projection of the
         * unit vector @p a off n (the fibre axis: the tangential springs
         * then split into one along the fibres and one across them). */
        void
        tangent_basis(const double *n, const float *a, double *t1, double *t2)
        {
          const double an = a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
          t1[0]           = a[0] - an * n[0];
          t1[1]           = a[1] - an * n[1];
          t1[2]           = a[2] - an * n[2];
          double l = std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
          if (l < 1e-6)
            {
              // The normal is along the fibre: any direction across it.
              const double h[3] = {0., 0., 1.};
              t1[0]             = h[1] * n[2] - h[2] * n[1];
              t1[1]             = h[2] * n[0] - h[0] * n[2];
              t1[2]             = h[0] * n[1] - h[1] * n[0];
              l = std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
              if (l < 1e-6)
                {
                  t1[0] = 1.;
                  t1[1] = t1[2] = 0.;
                  l             = 1.;
                }
            }
          t1[0] /= l;
          t1[1] /= l;
          t1[2] /= l;
          t2[0] = n[1] * t1[2] - n[2] * t1[1];
          t2[1] = n[2] * t1[0] - n[0] * t1[2];
          t2[2] = n[0] * t1[1] - n[1] * t1[0];
        }


        /**
         * Every spring of the model with an owned end, once: @p visit(i,
         * d_i, j, d_j, k) with the ends' local indices i, j (j = none for a
         * spring to the projectile), the directions d_i, d_j [-] in which
         * each end's displacement stretches it, and the stiffness k [N/m].
         * A spring with an end that is not owned is still visited: the
         * visitor ignores that end.
         */
        template <typename Visitor>
        void
        for_each_spring(const FibreChains &chains,
                        const Decomposition &D,
                        const std::vector<ListBlock> &blocks,
                        const Spheres &spheres,
                        const std::vector<float> &axis,
                        const double k_n,
                        const double k_t,
                        const double k_p,
                        const double k_pt,
                        const double projectile_y,
                        const double Rr,
                        const double projectile_margin,
                        const std::size_t none,
                        Visitor &&visit)
        {
          const double *x        = spheres.pos.data();
          const unsigned int nf  = chains.nf;
          const double L0        = chains.L0;
          const auto axis_of     = [&](const std::size_t i) {
            return &axis[3 * (i - D.act_b)];
          };
          const auto is_owned = [&](const std::size_t i) {
            return i >= D.own_b && i < D.own_e;
          };

          // Trusses with an owned end: along them, and the geometric
          // stiffness T/l across them.
          const unsigned int t_begin =
            std::max(D.g_lo, D.st_begin > 0 ? D.st_begin - 1 : 0u);
          const unsigned int t_end =
            std::min({D.st_end, chains.n_st - 1, D.g_hi - 1});
          for (unsigned int s = t_begin; s < t_end; ++s)
            for (unsigned int f = 0; f < nf; ++f)
              {
                const std::size_t i = D.local_index(s, f), j = i + nf;
                if (spheres.broken[i] || !(is_owned(i) || is_owned(j)))
                  continue;
                double d[3]    = {x[3 * j] - x[3 * i],
                                  x[3 * j + 1] - x[3 * i + 1],
                                  x[3 * j + 2] - x[3 * i + 2]};
                const double l = normalise(d);
                const double k = chains.truss_k * chains.fw[f];
                visit(i, d, j, d, k);
                const double kg = k * std::max(0., 1. - L0 / l);
                if (kg > 0.)
                  {
                    double u[3], w[3];
                    const float a[3] = {float(d[0]), float(d[1]), float(d[2])};
                    // Any pair across the truss will do.
                    tangent_basis(d, a, u, w);
                    visit(i, u, j, u, kg);
                    visit(i, w, j, w, kg);
                  }
              }

          // Fibre-fibre pairs in contact: a normal and two tangential
          // springs. Only these: every contact is listed, whatever the
          // partition or the list rebuilds, but pairs near contact are
          // listed or not depending on when the lists were built, and the
          // step must not depend on that.
          const double reach = chains.d;
          for (const ListBlock &B : blocks)
            for (std::size_t i = B.b; i < B.e; ++i)
              {
                const std::uint32_t p0 = B.pstart[i - B.b],
                                    p1 = B.pstart[i - B.b + 1];
                if (p0 == p1)
                  continue;
                const bool own_i = is_owned(i);
                for (std::uint32_t p = p0; p < p1; ++p)
                  {
                    const std::size_t j = B.pairs[p].j;
                    if (!own_i && !is_owned(j))
                      continue;
                    const double w = std::abs(B.pairs[p].w);
                    double n[3]    = {x[3 * i] - x[3 * j],
                                      x[3 * i + 1] - x[3 * j + 1],
                                      x[3 * i + 2] - x[3 * j + 2]};
                    if (normalise(n) >= reach)
                      continue;
                    double t1[3], t2[3];
                    tangent_basis(n, axis_of(i), t1, t2);
                    visit(i, n, j, n, w * k_n);
                    visit(i, t1, j, t1, w * k_t);
                    visit(i, t2, j, t2, w * k_t);
                  }
              }

          // Mirror pairs: the image of j moves as S u_j, so the spring
          // stretches with S d at j. A sphere against its own image has
          // both ends at i; its force is twice the pair's for one
          // displacement, which this counts with half the stiffness at each
          // of the two ends.
          for (const ListBlock &B : blocks)
            for (const MirrorPair &mp : B.mpairs)
              {
                const std::size_t i = mp.i, j = mp.j;
                if (!is_owned(i) && !is_owned(j))
                  continue;
                const double sx = (mp.axes & 1) ? -1. : 1.,
                             sz = (mp.axes & 2) ? -1. : 1.;
                double n[3]     = {x[3 * i] - sx * x[3 * j],
                                   x[3 * i + 1] - x[3 * j + 1],
                                   x[3 * i + 2] - sz * x[3 * j + 2]};
                if (normalise(n) >= reach)
                  continue;
                double t1[3], t2[3];
                tangent_basis(n, axis_of(i), t1, t2);
                const double w = (i == j ? 0.5 : 1.) * mp.w;
                const double *dirs[3] = {n, t1, t2};
                const double ks[3]    = {k_n, k_t, k_t};
                for (unsigned int c = 0; c < 3; ++c)
                  {
                    const double *d  = dirs[c];
                    const double s[3] = {sx * d[0], d[1], sz * d[2]};
                    visit(i, d, j, s, w * ks[c]);
                  }
              }

          // The projectile: every owned sphere within the margin of
          // touching it.
          if (Rr > 0.)
            {
              const double reach = Rr + projectile_margin;
              for (unsigned int s = D.st_begin; s < D.st_end; ++s)
                {
                  const double xlo = spheres.st_xlo[s],
                               xhi = spheres.st_xhi[s];
                  const double ax =
                    (xlo > 0. ? xlo : (xhi < 0. ? -xhi : 0.));
                  if (ax >= reach || spheres.st_ymax[s] <= projectile_y - reach)
                    continue;
                  for (unsigned int f = 0; f < nf; ++f)
                    {
                      const std::size_t i = D.local_index(s, f);
                      double n[3] = {x[3 * i], x[3 * i + 1] - projectile_y, 0.};
                      const double rho =
                        std::sqrt(n[0] * n[0] + n[1] * n[1]);
                      if (!(rho < reach) || rho == 0.)
                        continue;
                      n[0] /= rho;
                      n[1] /= rho;
                      const double w     = chains.fw[f] * chains.sw[s];
                      const double t1[3] = {0., 0., 1.};
                      const double t2[3] = {n[1], -n[0], 0.};
                      visit(i, n, none, n, w * k_p);
                      visit(i, t1, none, t1, w * k_pt);
                      visit(i, t2, none, t2, w * k_pt);
                    }
                }
            }
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
        const double *x        = spheres.pos.data();
        const unsigned int nf  = chains.nf;
        const std::size_t none = static_cast<std::size_t>(-1);

        // The fibre axis of every active sphere (it orients the tangential
        // springs; any orientation gives the same tensor), from its
        // neighbours along the fibre that are active and joined to it by an
        // unbroken truss.
        axis.resize(3 * (D.act_e - D.act_b));
        for (std::size_t i = D.act_b; i < D.act_e; ++i)
          {
            const unsigned int s = D.station_of(i);
            const bool prev      = s > D.g_lo && !spheres.broken[i - nf];
            const bool next =
              s + 1 < D.g_hi && s + 1 < chains.n_st && !spheres.broken[i];
            const std::size_t lo = prev ? i - nf : i, hi = next ? i + nf : i;
            double a[3] = {x[3 * hi] - x[3 * lo],
                           x[3 * hi + 1] - x[3 * lo + 1],
                           x[3 * hi + 2] - x[3 * lo + 2]};
            if (lo == hi)
              {
                a[0] = 1.;
                a[1] = a[2] = 0.;
              }
            normalise(a);
            float *out = &axis[3 * (i - D.act_b)];
            out[0]     = float(a[0]);
            out[1]     = float(a[1]);
            out[2]     = float(a[2]);
          }

        // The diagonal blocks K_ii = sum_f k_f d_f d_f^T of the owned
        // spheres (xx, yy, zz, xy, xz, yz).
        blocks_ii.assign(6 * (D.own_e - D.own_b), 0.f);
        const auto add = [&](const std::size_t i, const double *d,
                             const double k) {
          if (i == none || i < D.own_b || i >= D.own_e)
            return;
          float *K = &blocks_ii[6 * (i - D.own_b)];
          K[0] += float(k * d[0] * d[0]);
          K[1] += float(k * d[1] * d[1]);
          K[2] += float(k * d[2] * d[2]);
          K[3] += float(k * d[0] * d[1]);
          K[4] += float(k * d[0] * d[2]);
          K[5] += float(k * d[1] * d[2]);
        };
        for_each_spring(chains, D, blocks, spheres, axis, k_n, k_t, k_p, k_pt,
                        projectile_y, Rr, projectile_margin, none,
                        [&](const std::size_t i, const double *di,
                            const std::size_t j, const double *dj,
                            const double k) {
                          // A spring to the rigid projectile has one end:
                          // k (d . u_i)^2 needs no factor 2, and the sum
                          // below doubles every block.
                          add(i, di, j == none ? 0.5 * k : k);
                          add(j, dj, k);
                        });

        // u^T K u = sum_e k_e (d_e . (u_i - u_j))^2 <= 2 sum_i u_i^T K_ii u_i
        // <= 2 max_i lambda_max(K_ii / m_i) u^T M u.
        double lambda = 0.;
        for (std::size_t i = D.own_b; i < D.own_e; ++i)
          {
            const double inv_m =
              chains.finv[i % nf] * chains.sinv[D.station_of(i)];
            if (inv_m == 0.)
              continue;
            float *K = &blocks_ii[6 * (i - D.own_b)];
            // A sphere on a symmetry plane stands for itself and its image:
            // its block is the whole sphere's, K + S K S over two (it has
            // half the mass and half the springs in the plane), so that the
            // step is the full model's.
            if (chains.sw[D.station_of(i)] != 1.)
              K[3] = K[4] = 0.f; // x = 0: xy, xz
            if (chains.fw[i % nf] != 1.)
              K[4] = K[5] = 0.f; // z = 0: xz, yz
            lambda         = std::max(lambda,
                              inv_m * largest_eigenvalue(K[0],
                                                         K[1],
                                                         K[2],
                                                         K[3],
                                                         K[4],
                                                         K[5]));
          }
        // The float sums and the closed-form eigenvalue are good to a few
        // 1e-7: the margin keeps the result a bound.
        return 2. * (1. + 1e-5) * dealii::Utilities::MPI::max(lambda, D.comm);
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
