// The forces on the periodic segment of the DEM elementary tests: trusses
// (with failure), fibre contacts (by the impact model's pair kernel), the
// rigid walls and the local damping.
#include <yarn_impact/dem/contact_kernels.h>
#include <yarn_impact/dem/elementary/periodic_segment.h>

#include <algorithm>
#include <cmath>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      void
      PeriodicSegment::compute_forces()
      {
        const bool failure = shared.yarn.failure;
        const double eps_b = shared.yarn.failure_strain;
        std::fill(a.begin() + 3 * i_begin, a.begin() + 3 * i_end, 0.);
        std::fill(virial.begin(), virial.end(), 0.);
        double *F = a.data();

        // Trusses (s, s+1) of the own fibres; the last closes the period.
        for (unsigned int f = f_begin; f < f_end; ++f)
          for (unsigned int s = 0; s < ns; ++s)
            {
              const std::size_t i = static_cast<std::size_t>(f) * ns + s,
                                j = static_cast<std::size_t>(f) * ns +
                                    (s + 1 == ns ? 0 : s + 1);
              if (broken[i])
                continue;
              const double e[3] = {x[3 * j] - x[3 * i] +
                                     (s + 1 == ns ? Lx : 0.),
                                   x[3 * j + 1] - x[3 * i + 1],
                                   x[3 * j + 2] - x[3 * i + 2]};
              double t[3];
              const double strain = truss_force(e, truss_k, L0, t);
              if (failure && strain > eps_b)
                {
                  broken[i] = 1;
                  dissipated[i - i_begin] +=
                    0.5 * truss_k * strain * strain * L0 * L0;
                  if (fibre_break[f] < 0.)
                    fibre_break[f] = axial_strain;
                  continue;
                }
              for (unsigned int c = 0; c < 3; ++c)
                {
                  F[3 * i + c] += t[c];
                  F[3 * j + c] -= t[c];
                }
              double *w = &virial[6 * (i - i_begin)];
              w[0] += t[0] * e[0];
              w[1] += t[1] * e[1];
              w[2] += t[2] * e[2];
              w[3] += 0.5 * (t[1] * e[2] + t[2] * e[1]);
              w[4] += 0.5 * (t[0] * e[1] + t[1] * e[0]);
              w[5] += 0.5 * (t[0] * e[2] + t[2] * e[0]);
            }

        // Fibre contacts, from both sides (each rank evaluates the pairs of
        // its own spheres): the law is odd in (n, v, xi_t), so both sides
        // give the same force bit for bit and the sum does not depend on
        // the ranks. The pair kernel is the impact model's
        // (contact_kernels.h), on the nearest periodic image.
        const double d2 = d * d;
        for (std::size_t i = i_begin; i < i_end; ++i)
          {
            const std::size_t li = i - i_begin;
            double *w            = &virial[6 * li];
            for (std::uint32_t p = start[li]; p < start[li + 1]; ++p)
              {
                const std::size_t j = neighbour[p];
                const double e[3]   = {nearest_image(x[3 * i] - x[3 * j], Lx),
                                       x[3 * i + 1] - x[3 * j + 1],
                                       x[3 * i + 2] - x[3 * j + 2]};
                double *xi_t        = &history[3 * p];
                double f[3], diss = 0.;
                if (!pair_contact_force(fibre_law,
                                        d,
                                        d2,
                                        e,
                                        &v[3 * i],
                                        &v[3 * j],
                                        1.,
                                        1.,
                                        dt,
                                        xi_t,
                                        f,
                                        diss))
                  {
                    // Separated: the contact ends with its history.
                    if (touching[p])
                      {
                        touching[p] = 0;
                        xi_t[0] = xi_t[1] = xi_t[2] = 0.;
                      }
                    continue;
                  }
                touching[p] = 1;
                F[3 * i] += f[0];
                F[3 * i + 1] += f[1];
                F[3 * i + 2] += f[2];
                dissipated[li] += 0.5 * diss;
                // Half of f (x) (x_j - x_i) from each side.
                w[0] -= 0.5 * f[0] * e[0];
                w[1] -= 0.5 * f[1] * e[1];
                w[2] -= 0.5 * f[2] * e[2];
                w[3] -= 0.25 * (f[1] * e[2] + f[2] * e[1]);
                w[4] -= 0.25 * (f[0] * e[1] + f[1] * e[0]);
                w[5] -= 0.25 * (f[0] * e[2] + f[2] * e[0]);
              }
          }

        // Walls, for every sphere on every rank (their loads drive the
        // servo walls and must agree on all ranks).
        wall_virial[0] = wall_virial[1] = 0.;
        for (Wall &wall : walls)
          {
            wall.load = 0.;
            wall.n_in = 0;
            if (!wall.active)
              continue;
            const unsigned int c = wall.axis;
            double nv[3]         = {0., 0., 0.};
            nv[c]                = -wall.side; // from the wall to the sphere
            for (std::size_t i = 0; i < n; ++i)
              {
                const double delta =
                  wall.side * (x[3 * i + c] - wall.position) + radius;
                if (delta <= 0.)
                  continue;
                double vr[3] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
                vr[c] -= wall.velocity;
                double xi_t[3] = {0., 0., 0.}, f[3], diss = 0.;
                Contact::contact_force(wall_law,
                                       delta,
                                       nv,
                                       vr,
                                       dt,
                                       xi_t,
                                       f,
                                       diss);
                wall.load -= wall.side * f[c];
                ++wall.n_in;
                wall_virial[c - 1] += x[3 * i + c] * f[c];
                wall_dissipated += diss;
                if (i >= i_begin && i < i_end)
                  F[3 * i + c] += f[c];
              }
          }

        // Local (non-viscous) damping, as in quasi-static DEM tests: each
        // force component is reduced by alpha |F| against the velocity, so
        // that a sphere at rest or moving steadily is not dragged, while
        // the energy a collapsing packing releases is drained
        // (doc/identification.md section 2.3); its work is dissipated.
        const double alpha = test.local_damping;
        const double inv_m = 1. / mass;
        for (std::size_t k = 3 * i_begin; k < 3 * i_end; ++k)
          {
            if (alpha > 0. && v[k] != 0.)
              {
                const double damp = alpha * std::abs(F[k]);
                F[k] -= (v[k] > 0. ? damp : -damp);
                dissipated[k / 3 - i_begin] += damp * std::abs(v[k]) * dt;
              }
            F[k] *= inv_m;
          }
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
