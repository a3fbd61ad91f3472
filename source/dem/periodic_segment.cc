// The periodic yarn segment of the DEM elementary tests: the impact
// model's fibres, trusses and contact laws on a segment periodic along x,
// with rigid walls (doc/identification.md section 2).
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/dem/packing.h>
#include <yarn_impact/dem/periodic_segment.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      using namespace dealii;

      namespace
      {
        constexpr double PI = 3.14159265358979323846;

        /** The separation @p dx along the periodic axis of length @p L
         * taken to the nearest image; |dx| < 1.5 L here (the same result
         * as dx - L round(dx/L), without the call). */
        inline double
        nearest_image(const double dx, const double L)
        {
          return dx > 0.5 * L ? dx - L : (dx < -0.5 * L ? dx + L : dx);
        }
      } // namespace


      PeriodicSegment::PeriodicSegment(
        const YarnImpact::Parameters::Shared &shared,
        const Parameters &dem,
        const ElementaryTestParameters &test,
        const MPI_Comm comm)
        : shared(shared)
        , dem(dem)
        , test(test)
        , comm(comm)
        , rank(Utilities::MPI::this_mpi_process(comm))
        , n_ranks(Utilities::MPI::n_mpi_processes(comm))
      {
        using YarnImpact::Parameters::require;
        const auto &y = shared.yarn;
        d             = y.fibre_diameter;
        radius        = 0.5 * d;
        // Checked as by validate() (also run at parsing); the segment
        // ignores Symmetry.
        const FibreCentres centres = fibre_centres(shared, dem, false);
        packing_scale              = centres.scale;
        nf                         = centres.size();
        ns                         = test.stations;
        n                          = static_cast<std::size_t>(nf) * ns;
        require(nf >= n_ranks,
                "Yarn/Number of fibres",
                "= " + std::to_string(nf) +
                  ": an elementary test needs at least one fibre per MPI "
                  "rank");

        L0                      = dem.sphere_spacing;
        Lx0                     = ns * L0;
        Lx                      = Lx0;
        V0                      = Lx0 * y.section_area();
        const double fibre_area = PI * d * d / 4.;
        mass                    = y.fibre_density * fibre_area * L0;
        truss_k                 = y.fibre_modulus * fibre_area / L0;
        cutoff                  = d + dem.skin;

        // The impact model's laws (doc/dem.md sections 2 and 3); the walls have
        // the projectile's normal law and no friction, so that they do not
        // hold the section back.
        fibre_law    = fibre_contact_law(dem, truss_k, mass);
        wall_law     = projectile_contact_law(dem, truss_k, mass);
        wall_law.k_t = 0.;
        wall_law.mu  = 0.;

        // The impact model's stable step (a wall in place of the
        // projectile).
        dt = shared.time.safety_factor * critical_time_step(dem, truss_k, mass);

        // Fibres in contiguous ranges; sphere i = f * ns + s.
        f_begin = static_cast<unsigned int>(static_cast<unsigned long>(nf) *
                                            rank / n_ranks);
        f_end   = static_cast<unsigned int>(static_cast<unsigned long>(nf) *
                                          (rank + 1) / n_ranks);
        i_begin = static_cast<std::size_t>(f_begin) * ns;
        i_end   = static_cast<std::size_t>(f_end) * ns;
        for (unsigned int q = 0; q < n_ranks; ++q)
          {
            const unsigned long b = static_cast<unsigned long>(nf) * q /
                                    n_ranks * ns,
                                e = static_cast<unsigned long>(nf) * (q + 1) /
                                    n_ranks * ns;
            counts.push_back(static_cast<int>(6 * (e - b)));
            offsets.push_back(static_cast<int>(6 * b));
          }

        X0.resize(3 * n);
        for (unsigned int f = 0; f < nf; ++f)
          for (unsigned int s = 0; s < ns; ++s)
            {
              const std::size_t i = static_cast<std::size_t>(f) * ns + s;
              X0[3 * i]           = s * L0;
              // Touching neighbours start 1e-9 d apart, as in the impact
              // model, so that they do not start with round-off overlaps.
              X0[3 * i + 1] = centres.y[f] * (1. + 1e-9);
              X0[3 * i + 2] = centres.z[f] * (1. + 1e-9);
            }
        reset();
      }


      void
      PeriodicSegment::reset()
      {
        time         = 0.;
        axial_strain = 0.;
        Lx           = Lx0;
        x            = X0;
        v.assign(3 * n, 0.);
        a.assign(3 * n, 0.);
        broken.assign(n, 0);
        fibre_break.assign(nf, -1.);
        dissipated.assign(i_end - i_begin, 0.);
        virial.assign(6 * (i_end - i_begin), 0.);
        wall_dissipated = 0.;
        for (Wall &w : walls)
          w = Wall();
        start.clear();
        neighbour.clear();
        touching.clear();
        history.clear();
        build_lists();
        compute_forces();
      }


      void
      PeriodicSegment::exchange()
      {
        if (n_ranks == 1)
          return;
        std::vector<double> mine(6 * (i_end - i_begin));
        for (std::size_t i = i_begin; i < i_end; ++i)
          for (unsigned int c = 0; c < 3; ++c)
            {
              mine[6 * (i - i_begin) + c]     = x[3 * i + c];
              mine[6 * (i - i_begin) + 3 + c] = v[3 * i + c];
            }
        buffer.resize(6 * n);
        MPI_Allgatherv(mine.data(),
                       static_cast<int>(mine.size()),
                       MPI_DOUBLE,
                       buffer.data(),
                       counts.data(),
                       offsets.data(),
                       MPI_DOUBLE,
                       comm);
        for (std::size_t i = 0; i < n; ++i)
          for (unsigned int c = 0; c < 3; ++c)
            {
              x[3 * i + c] = buffer[6 * i + c];
              v[3 * i + c] = buffer[6 * i + 3 + c];
            }
      }


      void
      PeriodicSegment::build_lists()
      {
        // Cells of side >= cutoff on the (y, z) plane; the segment is short
        // along x, so every station of a cell is searched with the nearest
        // periodic image.
        double lo[2] = {std::numeric_limits<double>::max(),
                        std::numeric_limits<double>::max()},
               hi[2] = {-lo[0], -lo[1]};
        for (std::size_t i = 0; i < n; ++i)
          for (unsigned int c = 0; c < 2; ++c)
            {
              lo[c] = std::min(lo[c], x[3 * i + 1 + c]);
              hi[c] = std::max(hi[c], x[3 * i + 1 + c]);
            }
        unsigned int nc[2];
        for (unsigned int c = 0; c < 2; ++c)
          nc[c] = 1 + static_cast<unsigned int>((hi[c] - lo[c]) / cutoff);
        std::vector<std::uint32_t> cell_of(n), cell_start(nc[0] * nc[1] + 1, 0);
        for (std::size_t i = 0; i < n; ++i)
          {
            const unsigned int cy =
                                 std::min<unsigned int>(nc[0] - 1,
                                                        (x[3 * i + 1] - lo[0]) /
                                                          cutoff),
                               cz =
                                 std::min<unsigned int>(nc[1] - 1,
                                                        (x[3 * i + 2] - lo[1]) /
                                                          cutoff);
            cell_of[i] = cy * nc[1] + cz;
            ++cell_start[cell_of[i] + 1];
          }
        for (unsigned int c = 0; c < nc[0] * nc[1]; ++c)
          cell_start[c + 1] += cell_start[c];
        std::vector<std::uint32_t> sorted(n), fill(cell_start);
        for (std::size_t i = 0; i < n; ++i)
          sorted[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);

        // New lists, each sorted by neighbour, keeping the tangential
        // history of the pairs that were listed before.
        std::vector<std::uint32_t> new_start(1, 0), new_neighbour;
        std::vector<std::uint8_t> new_touching;
        std::vector<double> new_history;
        const double c2 = cutoff * cutoff;
        std::vector<std::uint32_t> found;
        for (std::size_t i = i_begin; i < i_end; ++i)
          {
            found.clear();
            const int cy = static_cast<int>(cell_of[i] / nc[1]),
                      cz = static_cast<int>(cell_of[i] % nc[1]);
            for (int dy = -1; dy <= 1; ++dy)
              for (int dz = -1; dz <= 1; ++dz)
                {
                  const int y = cy + dy, z = cz + dz;
                  if (y < 0 || z < 0 || y >= static_cast<int>(nc[0]) ||
                      z >= static_cast<int>(nc[1]))
                    continue;
                  const unsigned int c = y * nc[1] + z;
                  for (std::uint32_t k = cell_start[c]; k < cell_start[c + 1];
                       ++k)
                    {
                      const std::uint32_t j = sorted[k];
                      if (j == i)
                        continue;
                      double ex       = x[3 * j] - x[3 * i];
                      ex              = nearest_image(ex, Lx);
                      const double ey = x[3 * j + 1] - x[3 * i + 1],
                                   ez = x[3 * j + 2] - x[3 * i + 2];
                      if (ex * ex + ey * ey + ez * ez < c2)
                        found.push_back(j);
                    }
                }
            std::sort(found.begin(), found.end());
            const std::size_t li      = i - i_begin;
            std::uint32_t p           = (start.empty() ? 0 : start[li]);
            const std::uint32_t p_end = (start.empty() ? 0 : start[li + 1]);
            for (const std::uint32_t j : found)
              {
                while (p < p_end && neighbour[p] < j)
                  ++p;
                const bool kept = (p < p_end && neighbour[p] == j);
                new_neighbour.push_back(j);
                new_touching.push_back(kept ? touching[p] : 0);
                for (unsigned int c = 0; c < 3; ++c)
                  new_history.push_back(kept ? history[3 * p + c] : 0.);
              }
            new_start.push_back(
              static_cast<std::uint32_t>(new_neighbour.size()));
          }
        start.swap(new_start);
        neighbour.swap(new_neighbour);
        touching.swap(new_touching);
        history.swap(new_history);
        x_built = x;
        ++n_rebuilds;
      }


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
        // its own spheres): the law is odd in (n, v, xi), so both sides
        // give the same force bit for bit and the sum does not depend on
        // the ranks.
        const double d2 = d * d;
        for (std::size_t i = i_begin; i < i_end; ++i)
          {
            const std::size_t li = i - i_begin;
            double *w            = &virial[6 * li];
            for (std::uint32_t p = start[li]; p < start[li + 1]; ++p)
              {
                const std::size_t j = neighbour[p];
                double ex           = x[3 * i] - x[3 * j];
                ex                  = nearest_image(ex, Lx);
                const double ey     = x[3 * i + 1] - x[3 * j + 1],
                             ez     = x[3 * i + 2] - x[3 * j + 2];
                const double r2     = ex * ex + ey * ey + ez * ez;
                double *xi          = &history[3 * p];
                if (r2 >= d2)
                  {
                    if (touching[p])
                      {
                        touching[p] = 0;
                        xi[0] = xi[1] = xi[2] = 0.;
                      }
                    continue;
                  }
                touching[p]        = 1;
                const double dist  = std::sqrt(r2);
                const double nv[3] = {ex / dist, ey / dist, ez / dist};
                const double vr[3] = {v[3 * i] - v[3 * j],
                                      v[3 * i + 1] - v[3 * j + 1],
                                      v[3 * i + 2] - v[3 * j + 2]};
                double f[3], diss = 0.;
                fibre_law.force(d - dist, nv, vr, dt, xi, f, diss);
                F[3 * i] += f[0];
                F[3 * i + 1] += f[1];
                F[3 * i + 2] += f[2];
                dissipated[li] += 0.5 * diss;
                // Half of f (x) (x_j - x_i) from each side.
                w[0] -= 0.5 * f[0] * ex;
                w[1] -= 0.5 * f[1] * ey;
                w[2] -= 0.5 * f[2] * ez;
                w[3] -= 0.25 * (f[1] * ez + f[2] * ey);
                w[4] -= 0.25 * (f[0] * ey + f[1] * ex);
                w[5] -= 0.25 * (f[0] * ez + f[2] * ex);
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
                double xi[3] = {0., 0., 0.}, f[3], diss = 0.;
                wall_law.force(delta, nv, vr, dt, xi, f, diss);
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


      void
      PeriodicSegment::step()
      {
        for (std::size_t k = 3 * i_begin; k < 3 * i_end; ++k)
          {
            v[k] += 0.5 * dt * a[k];
            x[k] += dt * v[k];
          }
        time += dt;
        // Tension: the period stretches and the spheres follow affinely
        // (the homogeneous part of the motion is imposed, not carried by a
        // wave).
        if (test.loading == ElementaryLoading::tension)
          {
            axial_strain   = std::min(test.max_strain, test.strain_rate * time);
            const double L = Lx0 * (1. + axial_strain);
            const double r = L / Lx;
            for (std::size_t i = i_begin; i < i_end; ++i)
              x[3 * i] *= r;
            Lx = L;
          }
        for (Wall &w : walls)
          if (w.active)
            w.position += dt * w.velocity;
        exchange();

        double moved = 0.;
        for (std::size_t k = 0; k < 3 * n; k += 3)
          {
            const double dx = x[k] - x_built[k], dy = x[k + 1] - x_built[k + 1],
                         dz = x[k + 2] - x_built[k + 2];
            moved           = std::max(moved, dx * dx + dy * dy + dz * dz);
          }
        if (4. * moved > dem.skin * dem.skin)
          build_lists();

        compute_forces();
        for (std::size_t k = 3 * i_begin; k < 3 * i_end; ++k)
          v[k] += 0.5 * dt * a[k];
        // Background viscous damping: stops the spheres that a collapsing
        // packing throws off, which no force (and so no local damping)
        // would stop (doc/identification.md section 2.3); dissipated.
        if (test.damping_time > 0.)
          {
            const double keep = std::exp(-dt / test.damping_time);
            for (std::size_t i = i_begin; i < i_end; ++i)
              {
                double v2 = 0.;
                for (unsigned int c = 0; c < 3; ++c)
                  {
                    v2 += v[3 * i + c] * v[3 * i + c];
                    v[3 * i + c] *= keep;
                  }
                dissipated[i - i_begin] += 0.5 * mass * v2 * (1. - keep * keep);
              }
          }
        for (std::size_t k = 3 * i_begin; k < 3 * i_end; ++k)
          if (!std::isfinite(v[k]))
            throw RunError("the elementary test blew up at t = " +
                           std::to_string(time * 1e6) +
                           " us (non-finite velocity); reduce "
                           "Elementary test/Strain rate or Time/Safety "
                           "factor");
      }


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
      PeriodicSegment::affine_gradient(FE::Matrix3 &F) const
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


      std::vector<double>
      PeriodicSegment::gather(const std::vector<double> &mine,
                              const unsigned int per,
                              const bool per_fibre) const
      {
        if (n_ranks == 1)
          return mine;
        // counts and offsets are in doubles of 6 per sphere.
        const unsigned int items = 6 * (per_fibre ? ns : 1);
        std::vector<int> c(n_ranks), o(n_ranks);
        for (unsigned int q = 0; q < n_ranks; ++q)
          {
            c[q] = counts[q] / items * per;
            o[q] = offsets[q] / items * per;
          }
        std::vector<double> all((per_fibre ? nf : n) * per);
        MPI_Allgatherv(mine.data(),
                       static_cast<int>(mine.size()),
                       MPI_DOUBLE,
                       all.data(),
                       c.data(),
                       o.data(),
                       MPI_DOUBLE,
                       comm);
        return all;
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
