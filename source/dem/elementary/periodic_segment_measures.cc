// What the elementary tests measure on the periodic segment: the sums of
// one CSV row (virial, energies), the affine deformation gradient of the
// section, its second moments and extent, and the fibres' break strains.
#include <yarn_impact/dem/elementary/periodic_segment.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      Sums
      PeriodicSegment::sums()
      {
        // Own spheres' shares, gathered in sphere order so that the sums
        // do not depend on the ranks.
        constexpr unsigned int K = 10;
        std::vector<double> mine(K * (i_end - i_begin), 0.);
        for (std::size_t i = i_begin; i < i_end; ++i)
          {
            const std::size_t li = i - i_begin;
            double *m            = &mine[K * li];
            for (unsigned int c = 0; c < 6; ++c)
              m[c] = virial[6 * li + c];
            m[6] = 0.5 * mass *
                   (v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] +
                    v[3 * i + 2] * v[3 * i + 2]);
            const unsigned int s = i % ns;
            const std::size_t j  = (s + 1 == ns ? i + 1 - ns : i + 1);
            if (!broken[i])
              {
                const double e[3] = {x[3 * j] - x[3 * i] +
                                       (s + 1 == ns ? Lx : 0.),
                                     x[3 * j + 1] - x[3 * i + 1],
                                     x[3 * j + 2] - x[3 * i + 2]};
                const double l =
                  std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
                m[7] = 0.5 * truss_k * (l - L0) * (l - L0);
              }
            for (std::uint32_t p = start[li]; p < start[li + 1]; ++p)
              if (touching[p])
                {
                  const std::size_t jj = neighbour[p];
                  double ex            = x[3 * i] - x[3 * jj];
                  ex                   = nearest_image(ex, Lx);
                  const double ey      = x[3 * i + 1] - x[3 * jj + 1],
                               ez      = x[3 * i + 2] - x[3 * jj + 2];
                  const double dist    = std::sqrt(ex * ex + ey * ey + ez * ez);
                  m[8] += 0.5 * fibre_law.energy(d - dist, &history[3 * p]);
                }
            m[9] = dissipated[li];
          }
        const std::vector<double> all = gather(mine, K, false);
        Sums S;
        for (std::size_t i = 0; i < n; ++i)
          {
            const double *m = &all[K * i];
            for (unsigned int c = 0; c < 6; ++c)
              S.virial[c] += m[c];
            S.kinetic += m[6];
            S.truss += m[7];
            S.contact += m[8];
            S.dissipated += m[9];
          }
        S.dissipated += wall_dissipated;
        return S;
      }


      void
      PeriodicSegment::affine_gradient(Mechanics::Matrix3 &F) const
      {
        double mx[2] = {0., 0.}, mX[2] = {0., 0.};
        for (std::size_t i = 0; i < n; ++i)
          for (unsigned int c = 0; c < 2; ++c)
            {
              mx[c] += x[3 * i + 1 + c];
              mX[c] += X0[3 * i + 1 + c];
            }
        for (unsigned int c = 0; c < 2; ++c)
          {
            mx[c] /= n;
            mX[c] /= n;
          }
        // F = (sum x X^T) (sum X X^T)^-1 on the section plane.
        double M[2][2] = {{0., 0.}, {0., 0.}}, G[2][2] = {{0., 0.}, {0., 0.}};
        for (std::size_t i = 0; i < n; ++i)
          {
            const double xc[2] = {x[3 * i + 1] - mx[0], x[3 * i + 2] - mx[1]};
            const double Xc[2] = {X0[3 * i + 1] - mX[0], X0[3 * i + 2] - mX[1]};
            for (unsigned int r = 0; r < 2; ++r)
              for (unsigned int c = 0; c < 2; ++c)
                {
                  M[r][c] += xc[r] * Xc[c];
                  G[r][c] += Xc[r] * Xc[c];
                }
          }
        const double det      = G[0][0] * G[1][1] - G[0][1] * G[1][0];
        const double Gi[2][2] = {{G[1][1] / det, -G[0][1] / det},
                                 {-G[1][0] / det, G[0][0] / det}};
        for (unsigned int k = 0; k < 9; ++k)
          F[k] = 0.;
        F[0] = Lx / Lx0;
        for (unsigned int r = 0; r < 2; ++r)
          for (unsigned int c = 0; c < 2; ++c)
            F[3 * (r + 1) + c + 1] = M[r][0] * Gi[0][c] + M[r][1] * Gi[1][c];
      }


      std::pair<double, double>
      PeriodicSegment::second_moments() const
      {
        double m[2] = {0., 0.}, q[2] = {0., 0.};
        for (std::size_t i = 0; i < n; ++i)
          for (unsigned int c = 0; c < 2; ++c)
            m[c] += x[3 * i + 1 + c];
        for (unsigned int c = 0; c < 2; ++c)
          m[c] /= n;
        for (std::size_t i = 0; i < n; ++i)
          for (unsigned int c = 0; c < 2; ++c)
            q[c] += (x[3 * i + 1 + c] - m[c]) * (x[3 * i + 1 + c] - m[c]);
        return {q[0] / n, q[1] / n};
      }


      double
      PeriodicSegment::extreme(const unsigned int axis, const double side) const
      {
        double e = -side * std::numeric_limits<double>::max();
        for (std::size_t i = 0; i < n; ++i)
          e = (side > 0. ? std::max(e, x[3 * i + axis])
                         : std::min(e, x[3 * i + axis]));
        return e;
      }


      std::vector<double>
      PeriodicSegment::break_strains() const
      {
        if (n_ranks == 1)
          return fibre_break;
        return gather(std::vector<double>(fibre_break.begin() + f_begin,
                                          fibre_break.begin() + f_end),
                      1,
                      true);
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
