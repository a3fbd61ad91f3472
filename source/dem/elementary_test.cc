// DEM elementary tests: a periodic segment of the yarn (the impact model's
// fibres, packing and contact laws) under a homogeneous deformation, with
// its homogenised stress. The theory, the boundary conditions and the
// checks are in doc/identification.md.
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/dem/contact_law.h>
#include <yarn_impact/dem/elementary_test.h>
#include <yarn_impact/dem/packing.h>
#include <yarn_impact/fe/constitutive_law.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>

namespace YarnImpact
{
  namespace DEM
  {
    using namespace dealii;

    std::string
    elementary_test_file(const ElementaryLoading loading)
    {
      switch (loading)
        {
          case ElementaryLoading::tension:
            return "elementary_tension.csv";
          case ElementaryLoading::compaction:
            return "elementary_compaction.csv";
          case ElementaryLoading::distortion:
            return "elementary_distortion.csv";
          default:
            return "";
        }
    }

    namespace
    {
      constexpr double PI = 3.14159265358979323846;

      /** The separation @p dx along the periodic axis of length @p L taken
       * to the nearest image; |dx| < 1.5 L here (the same result as
       * dx - L round(dx/L), without the call). */
      inline double
      nearest_image(const double dx, const double L)
      {
        return dx > 0.5 * L ? dx - L : (dx < -0.5 * L ? dx + L : dx);
      }

      /** A rigid wall normal to y or z: a plate (y) or a side wall (z). */
      struct Wall
      {
        /** Whether it exists. */
        bool active = false;
        /** Axis of its normal: 1 (y) or 2 (z). */
        unsigned int axis = 1;
        /** +1: the wall bounds the yarn from above (x_axis < pos), -1 from
         * below. */
        double side = 1.;
        /** Position along its axis [m] and velocity [m/s]. */
        double position = 0., velocity = 0.;
        /** Sum of the normal contact forces on it, positive when the yarn
         * pushes it outwards [N], and its number of contacts. */
        double load       = 0.;
        unsigned int n_in = 0;
        /** Integral part of the servo's velocity [m/s]. */
        double integral = 0.;
      };

      /** Values summed over all spheres for one CSV row. */
      struct Sums
      {
        /** Virial of the trusses and contacts, xx yy zz yz xy xz [N m]. */
        double virial[6] = {0., 0., 0., 0., 0., 0.};
        double kinetic = 0., truss = 0., contact = 0., dissipated = 0.;
      };


      /**
       * The periodic segment: `stations` cross-sections of the yarn's fibres
       * along x, the last joined to the first by a truss across the period.
       * Every rank holds the positions and velocities of all spheres and
       * integrates those of its own fibres (a contiguous range); the
       * walls' contacts are evaluated for all spheres by every rank, so
       * that their loads are the same on every rank.
       */
      class Segment
      {
      public:
        Segment(const YarnImpact::Parameters::Shared &shared,
                const Parameters &dem,
                const ElementaryTestParameters &test,
                const MPI_Comm comm);

        /** Back to the packed, unloaded, unbroken reference state. */
        void
        reset();

        /** One velocity-Verlet step of length dt. */
        void
        step();

        /** Sums over all spheres (collective). */
        Sums
        sums();

        /** Affine deformation gradient of the spheres (least-squares fit
         * of the current (y, z) to the reference ones), row-major 3x3. */
        void
        affine_gradient(FE::Matrix3 &F) const;

        /** Centred second moments <y^2>, <z^2> of the sphere centres
         * [m^2]. */
        std::pair<double, double>
        second_moments() const;

        /** Extreme coordinate of the sphere centres along @p axis. */
        double
        extreme(const unsigned int axis, const double side) const;

        /** The fibres' first break strains, in fibre order, -1 for an
         * unbroken fibre (collective). */
        std::vector<double>
        break_strains() const;

        // Set-up data.
        const YarnImpact::Parameters::Shared &shared;
        const Parameters &dem;
        const ElementaryTestParameters &test;
        const MPI_Comm comm;
        unsigned int rank = 0, n_ranks = 1;
        unsigned int nf = 0, ns = 0;
        std::size_t n = 0;
        double d = 0., radius = 0., L0 = 0., mass = 0., truss_k = 0.;
        double dt = 0., cutoff = 0., packing_scale = 1.;
        /** Reference volume: the FE yarn's ellipse times the segment length
         * [m^3]. */
        double V0 = 0.;
        /** Segment length at rest and now [m]. */
        double Lx0 = 0., Lx = 0.;
        ContactLaw fibre_law, wall_law;
        unsigned int f_begin = 0, f_end = 0;
        std::size_t i_begin = 0, i_end = 0;

        // State.
        double time = 0.;
        /** Imposed axial strain of the segment (tension) [-]. */
        double axial_strain = 0.;
        std::vector<double> X0, x, v, a;
        std::vector<std::uint8_t> broken; ///< truss (s, s+1) of each sphere
        std::vector<double> fibre_break;  ///< first break strain per fibre
        std::vector<double> dissipated;   ///< cumulative, per own sphere
        double wall_dissipated = 0.;
        std::vector<double> virial; ///< 6 per own sphere, last evaluation
        Wall walls[4];              ///< +y, -y, +z, -z
        /** External virial of the walls, yy and zz [N m]. */
        double wall_virial[2] = {0., 0.};
        unsigned long n_rebuilds = 0;

      private:
        void
        exchange();
        void
        build_lists();
        void
        compute_forces();

        std::vector<std::uint32_t> start;
        std::vector<std::uint32_t> neighbour;
        std::vector<std::uint8_t> touching;
        std::vector<double> history;
        std::vector<double> x_built;
        std::vector<int> counts, offsets;
        std::vector<double> buffer;
      };


      Segment::Segment(const YarnImpact::Parameters::Shared &shared,
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
        require(dem.sphere_spacing <= d * (1. + 1e-12),
                "DEM/Sphere spacing",
                "must not exceed Yarn/Fibre diameter: larger gaps would let "
                "fibres pass between the spheres of another fibre");
        const FibreCentres centres =
          (dem.layout == FibreLayout::file ?
             read_fibre_file(dem.fibre_file,
                             y.n_fibres,
                             d,
                             y.thickness_semi_axis,
                             y.width_semi_axis) :
             hexagonal_packing(y.n_fibres,
                               d,
                               y.thickness_semi_axis,
                               y.width_semi_axis,
                               dem.max_packing_scale));
        packing_scale = centres.scale;
        nf            = centres.size();
        ns            = test.stations;
        n             = static_cast<std::size_t>(nf) * ns;
        require(nf >= n_ranks,
                "Yarn/Number of fibres",
                "= " + std::to_string(nf) +
                  ": an elementary test needs at least one fibre per MPI "
                  "rank");

        L0  = dem.sphere_spacing;
        Lx0 = ns * L0;
        Lx  = Lx0;
        V0  = Lx0 * y.section_area();
        const double fibre_area = PI * d * d / 4.;
        mass                    = y.fibre_density * fibre_area * L0;
        truss_k                 = y.fibre_modulus * fibre_area / L0;
        cutoff                  = d + dem.skin;

        // The impact model's laws (doc/dem.md sections 2 and 3); the walls have
        // the projectile's normal law and no friction, so that they do not
        // hold the section back.
        fibre_law.k_n = dem.normal_stiffness_ratio * truss_k;
        fibre_law.c_n =
          2. * dem.damping_ratio * std::sqrt(0.5 * mass * fibre_law.k_n);
        fibre_law.k_t = dem.tangential_stiffness_ratio * fibre_law.k_n;
        fibre_law.mu  = dem.friction;
        wall_law.k_n  = dem.projectile_stiffness_ratio * truss_k;
        wall_law.c_n =
          2. * dem.projectile_damping_ratio * std::sqrt(mass * wall_law.k_n);

        // The impact model's stable step: two trusses, `coordination`
        // contacts and a wall per sphere.
        const double omega2 =
          2. * (2. * truss_k + dem.coordination * fibre_law.k_n + wall_law.k_n) /
          mass;
        const double zeta =
          std::max(dem.damping_ratio, dem.projectile_damping_ratio);
        dt = shared.time.safety_factor * 2. / std::sqrt(omega2) *
             (std::sqrt(1. + zeta * zeta) - zeta);

        // Fibres in contiguous ranges; sphere i = f * ns + s.
        f_begin = static_cast<unsigned int>(
          static_cast<unsigned long>(nf) * rank / n_ranks);
        f_end = static_cast<unsigned int>(static_cast<unsigned long>(nf) *
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
      Segment::reset()
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
      Segment::exchange()
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
      Segment::build_lists()
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
        std::vector<std::uint32_t> cell_of(n), cell_start(nc[0] * nc[1] + 1,
                                                          0);
        for (std::size_t i = 0; i < n; ++i)
          {
            const unsigned int cy = std::min<unsigned int>(
                                 nc[0] - 1, (x[3 * i + 1] - lo[0]) / cutoff),
                               cz = std::min<unsigned int>(
                                 nc[1] - 1, (x[3 * i + 2] - lo[1]) / cutoff);
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
                      double ex = x[3 * j] - x[3 * i];
                      ex = nearest_image(ex, Lx);
                      const double ey = x[3 * j + 1] - x[3 * i + 1],
                                   ez = x[3 * j + 2] - x[3 * i + 2];
                      if (ex * ex + ey * ey + ez * ez < c2)
                        found.push_back(j);
                    }
                }
            std::sort(found.begin(), found.end());
            const std::size_t li = i - i_begin;
            std::uint32_t p = (start.empty() ? 0 : start[li]);
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
      Segment::compute_forces()
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
              const double e[3] = {x[3 * j] - x[3 * i] + (s + 1 == ns ? Lx : 0.),
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
                ex = nearest_image(ex, Lx);
                const double ey = x[3 * i + 1] - x[3 * j + 1],
                             ez = x[3 * i + 2] - x[3 * j + 2];
                const double r2 = ex * ex + ey * ey + ez * ez;
                double *xi      = &history[3 * p];
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
      Segment::step()
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
            axial_strain = std::min(test.max_strain, test.strain_rate * time);
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
            moved = std::max(moved, dx * dx + dy * dy + dz * dz);
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
      Segment::sums()
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
                const double e[3] = {x[3 * j] - x[3 * i] + (s + 1 == ns ? Lx : 0.),
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
                  ex = nearest_image(ex, Lx);
                  const double ey = x[3 * i + 1] - x[3 * jj + 1],
                               ez = x[3 * i + 2] - x[3 * jj + 2];
                  const double dist = std::sqrt(ex * ex + ey * ey + ez * ez);
                  m[8] += 0.5 * fibre_law.energy(d - dist, &history[3 * p]);
                }
            m[9] = dissipated[li];
          }
        std::vector<double> all(K * n);
        if (n_ranks == 1)
          all = mine;
        else
          {
            std::vector<int> c(n_ranks), o(n_ranks);
            for (unsigned int q = 0; q < n_ranks; ++q)
              {
                c[q] = counts[q] / 6 * K;
                o[q] = offsets[q] / 6 * K;
              }
            MPI_Allgatherv(mine.data(),
                           static_cast<int>(mine.size()),
                           MPI_DOUBLE,
                           all.data(),
                           c.data(),
                           o.data(),
                           MPI_DOUBLE,
                           comm);
          }
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
      Segment::affine_gradient(FE::Matrix3 &F) const
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
        const double det = G[0][0] * G[1][1] - G[0][1] * G[1][0];
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
      Segment::second_moments() const
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
      Segment::extreme(const unsigned int axis, const double side) const
      {
        double e = -side * std::numeric_limits<double>::max();
        for (std::size_t i = 0; i < n; ++i)
          e = (side > 0. ? std::max(e, x[3 * i + axis]) :
                           std::min(e, x[3 * i + axis]));
        return e;
      }


      std::vector<double>
      Segment::break_strains() const
      {
        if (n_ranks == 1)
          return fibre_break;
        std::vector<double> mine(fibre_break.begin() + f_begin,
                                 fibre_break.begin() + f_end),
          all(nf);
        std::vector<int> c(n_ranks), o(n_ranks);
        for (unsigned int q = 0; q < n_ranks; ++q)
          {
            c[q] = counts[q] / 6 / ns;
            o[q] = offsets[q] / 6 / ns;
          }
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


      /** One row of the CSV and what the summary needs of it. */
      struct Row
      {
        std::string phase;
        double pressure = 0., time = 0., strain = 0.;
        FE::Matrix3 F;
        FE::Invariants inv;
        double height = 0., width = 0.;
        double tau[4]          = {0., 0., 0., 0.}; // xx yy zz yz [Pa]
        double tau_boundary[2] = {0., 0.};         // yy zz [Pa]
        double plate_load = 0., wall_load = 0.;    // per length [N/m]
        double plate_gap = 0., wall_gap = 0.;      // [m]
        Sums sums;
        unsigned int broken_fibres = 0;
      };

      const char *csv_header =
        "loading,confining_pressure,phase,time,imposed_strain,F_xx,F_yy,F_yz,"
        "F_zy,F_zz,I_e,I_tc,I_td,height,width,tau_xx,tau_yy,tau_zz,tau_yz,"
        "tau_yy_boundary,tau_zz_boundary,plate_gap,plate_load,wall_gap,"
        "wall_load,kinetic_energy,truss_energy,contact_energy,"
        "dissipated_energy,broken_fibres";


      /** Drives the segment through the phases of one test and records the
       * rows. */
      class Recorder
      {
      public:
        Recorder(Segment &segment, std::ostream *csv, const std::string &name)
          : seg(segment)
          , csv(csv)
          , name(name)
        {}

        Row
        record(const std::string &phase,
               const double pressure,
               const double strain)
        {
          Row r;
          r.phase    = phase;
          r.pressure = pressure;
          r.time     = seg.time;
          r.strain   = strain;
          seg.affine_gradient(r.F);
          r.inv            = FE::charmetant_invariants(r.F);
          const auto m     = seg.second_moments();
          r.height         = 4. * std::sqrt(m.first);
          r.width          = 4. * std::sqrt(m.second);
          r.sums           = seg.sums();
          const double *w  = r.sums.virial;
          r.tau[0]         = w[0] / seg.V0;
          r.tau[1]         = w[1] / seg.V0;
          r.tau[2]         = w[2] / seg.V0;
          r.tau[3]         = w[3] / seg.V0;
          r.tau_boundary[0] = seg.wall_virial[0] / seg.V0;
          r.tau_boundary[1] = seg.wall_virial[1] / seg.V0;
          const Wall *W     = seg.walls;
          if (W[0].active)
            {
              r.plate_gap  = W[0].position - W[1].position;
              r.plate_load = 0.5 * (W[0].load + W[1].load) / seg.Lx;
            }
          if (W[2].active)
            {
              r.wall_gap  = W[2].position - W[3].position;
              r.wall_load = 0.5 * (W[2].load + W[3].load) / seg.Lx;
            }
          for (const double b : seg.break_strains())
            r.broken_fibres += (b >= 0.);
          if (csv)
            {
              std::ostream &o = *csv;
              o << name << ',' << pressure << ',' << phase << ',' << r.time
                << ',' << strain << ',' << r.F[0] << ',' << r.F[4] << ','
                << r.F[5] << ',' << r.F[7] << ',' << r.F[8] << ','
                << r.inv.elongation << ',' << r.inv.compaction << ','
                << r.inv.distortion << ',' << r.height << ',' << r.width << ','
                << r.tau[0] << ',' << r.tau[1] << ',' << r.tau[2] << ','
                << r.tau[3] << ',' << r.tau_boundary[0] << ','
                << r.tau_boundary[1] << ',' << r.plate_gap << ','
                << r.plate_load << ',' << r.wall_gap << ',' << r.wall_load
                << ',' << r.sums.kinetic << ',' << r.sums.truss << ','
                << r.sums.contact << ',' << r.sums.dissipated << ','
                << r.broken_fibres << '\n';
              if (!o)
                throw RunError("cannot write the elementary-test CSV "
                               "(disk full?)");
            }
          rows.push_back(r);
          return r;
        }

        Segment &seg;
        std::ostream *csv;
        std::string name;
        std::vector<Row> rows;
      };


      /** Servo of a wall that holds the yarn at @p force [N]: a PI
       * controller on the force error, critically damped for the stiffness
       * of the wall's contacts, so that it follows a spreading section
       * without a lag error; at most @p v_max [m/s]. */
      void
      servo(Wall &w, const double force, const double k_n, const double dt,
            const double v_max)
      {
        constexpr double alpha = 0.05; // error closed per step, proportional
        const double k   = k_n * std::max(1u, w.n_in);
        const double err = w.load - force;
        w.integral = std::clamp(w.integral + 0.25 * alpha * alpha * err /
                                               (k * dt),
                                -v_max,
                                v_max);
        const double v =
          std::clamp(alpha * err / (k * dt) + w.integral, -v_max, v_max);
        w.velocity = w.side * v;
      }


      /** Tension along the fibres, to failure. */
      void
      run_tension(Segment &seg, Recorder &rec)
      {
        const auto &t = seg.test;
        double next   = 0.;
        while (true)
          {
            if (seg.axial_strain >= next - 1e-12 ||
                seg.axial_strain >= t.max_strain)
              {
                rec.record("load", 0., seg.axial_strain);
                next += t.output_strain_interval;
                if (seg.axial_strain >= t.max_strain)
                  break;
              }
            seg.step();
          }
      }


      /** Plates normal to y close at the strain rate, then reopen; with
       * @p pressure > 0, side walls normal to z hold the yarn at that
       * pressure, after a consolidation in which the plates do too. */
      void
      run_plates(Segment &seg, Recorder &rec, const double pressure)
      {
        const auto &t = seg.test;
        seg.reset();
        Wall *W = seg.walls;
        const bool side_walls =
          pressure > 0. || t.side_walls == SideWalls::fixed;
        for (unsigned int k = 0; k < (side_walls ? 4u : 2u); ++k)
          {
            W[k].active   = true;
            W[k].axis     = 1 + k / 2;
            W[k].side     = (k % 2 == 0 ? 1. : -1.);
            W[k].position = seg.extreme(W[k].axis, W[k].side) +
                            W[k].side * seg.radius;
          }
        const double k_n = seg.wall_law.k_n;
        const double gap_y0 = W[0].position - W[1].position;
        if (pressure > 0.)
          {
            const double gap_z0 = W[2].position - W[3].position;
            const double v_max =
              10. * t.strain_rate * std::max(gap_y0, gap_z0);
            const double t_end  = t.consolidation_time;
            double next         = 0.;
            while (true)
              {
                if (seg.time >= next - 1e-15)
                  {
                    rec.record("consolidation", pressure, 0.);
                    next += 0.1 * t_end;
                  }
                if (seg.time >= t_end)
                  break;
                const double gy = W[0].position - W[1].position,
                             gz = W[2].position - W[3].position;
                for (unsigned int k = 0; k < 4; ++k)
                  servo(W[k],
                        pressure * seg.Lx * (k < 2 ? gz : gy),
                        k_n,
                        seg.dt,
                        v_max);
                seg.step();
              }
          }

        // Plates under displacement control, about their mid-plane.
        const double gap_ref = W[0].position - W[1].position;
        const double mid     = 0.5 * (W[0].position + W[1].position);
        const double v_plate = 0.5 * t.strain_rate * gap_ref;
        // The section spreads in z faster than the plates close in y (it is
        // wider than thick): the walls may move at several times the
        // plates' speed over the larger gap.
        const double v_max =
          10. * t.strain_rate *
          std::max(gap_ref, W[2].active ? W[2].position - W[3].position : 0.);
        for (const bool loading : {true, false})
          {
            if (!loading && !t.unload)
              break;
            const double t0 = seg.time;
            double next     = (loading ? 0. : t.max_strain);
            while (true)
              {
                const double elapsed = seg.time - t0;
                const double strain =
                  loading ? std::min(t.max_strain, t.strain_rate * elapsed) :
                            std::max(0., t.max_strain - t.strain_rate * elapsed);
                const bool done = loading ? strain >= t.max_strain :
                                            strain <= 0.;
                if ((loading && strain >= next - 1e-12) ||
                    (!loading && strain <= next + 1e-12) || done)
                  {
                    if (!(loading == false && elapsed == 0.))
                      rec.record(loading ? "load" : "unload", pressure, strain);
                    next += (loading ? 1. : -1.) * t.output_strain_interval;
                  }
                if (done)
                  break;
                // Positions follow the imposed gap exactly; the velocity is
                // that of the next step.
                const double half = 0.5 * gap_ref * (1. - strain);
                W[0].position     = mid + half;
                W[1].position     = mid - half;
                W[0].velocity     = (loading ? -v_plate : v_plate);
                W[1].velocity     = -W[0].velocity;
                if (pressure > 0.)
                  {
                    const double gy = W[0].position - W[1].position;
                    for (unsigned int k = 2; k < 4; ++k)
                      servo(W[k], pressure * seg.Lx * gy, k_n, seg.dt, v_max);
                  }
                seg.step();
              }
          }
      }

      std::string
      fixed(const double value, const int digits)
      {
        std::ostringstream s;
        s << std::fixed << std::setprecision(digits) << value;
        return s.str();
      }
    } // namespace


    bool
    run_elementary_test(const YarnImpact::Parameters::Shared &shared,
                        const Parameters &dem,
                        const ElementaryTestParameters &test,
                        const MPI_Comm communicator,
                        std::ostream &out)
    {
      using YarnImpact::Parameters::Verbosity;
      const bool root = Utilities::MPI::this_mpi_process(communicator) == 0;
      const bool testing = shared.output.verbosity == Verbosity::test;
      Segment seg(shared, dem, test, communicator);
      const auto &y     = shared.yarn;
      const double phi  = y.fibre_area() / y.section_area();
      const double E_phi = y.fibre_modulus * phi;

      std::ostringstream report;
      if (root && !testing)
        out << "[elementary] " << seg.nf << " fibres x " << seg.ns
            << " cross-sections (" << seg.n << " spheres), periodic along x "
            << "over " << seg.Lx0 * 1e6 << " um; packing scale "
            << seg.packing_scale << "; fibre area fraction of the FE "
            << "ellipse " << phi << "; dt " << seg.dt * 1e9 << " ns\n";

      const std::string file =
        shared.output.directory + "/" + elementary_test_file(test.loading);
      const std::string partial = file + ".partial";
      std::ofstream csv;
      if (root)
        {
          csv.open(partial);
          if (!csv)
            throw RunError("cannot write '" + partial + "'");
          csv << std::setprecision(10) << csv_header << '\n';
        }
      const std::string name = elementary_test_file(test.loading)
                                 .substr(11, std::string::npos);
      Recorder rec(seg, root ? &csv : nullptr, name.substr(0, name.size() - 4));

      bool passed = true;
      auto check  = [&](const std::string &what, const bool ok) {
        report << "  check " << what << ": " << (ok ? "PASSED" : "FAILED")
               << '\n';
        passed = passed && ok;
      };

      report << "Elementary test (" << rec.name << ", " << seg.nf
             << " fibres, " << seg.ns << " cross-sections, periodic)\n";
      if (test.loading == ElementaryLoading::tension)
        {
          run_tension(seg, rec);
          // Before the first break the stress is E phi (lambda - 1) lambda
          // exactly: the trusses are linear in length and stretch affinely.
          double dev = 0., peak = 0., k_fit_num = 0., k_fit_den = 0.;
          for (const Row &r : rec.rows)
            {
              peak = std::max(peak, r.tau[0]);
              if (r.broken_fibres > 0)
                continue;
              const double lambda = r.F[0];
              const double exact  = E_phi * (lambda - 1.) * lambda;
              if (exact > 0.)
                dev = std::max(dev, std::abs(r.tau[0] / exact - 1.));
              k_fit_num += r.tau[0] * r.inv.elongation;
              k_fit_den += r.inv.elongation * r.inv.elongation;
            }
          const auto breaks = seg.break_strains();
          double bmin = 1e300, bmax = -1e300, bmean = 0.;
          unsigned int nb = 0;
          for (const double b : breaks)
            if (b >= 0.)
              {
                bmin = std::min(bmin, b);
                bmax = std::max(bmax, b);
                bmean += b;
                ++nb;
              }
          bmean = (nb > 0 ? bmean / nb : 0.);
          double bstd = 0.;
          for (const double b : breaks)
            if (b >= 0.)
              bstd += (b - bmean) * (b - bmean);
          bstd = (nb > 1 ? std::sqrt(bstd / (nb - 1)) : 0.);
          const Row &last = rec.rows.back();
          report << "  fibre area fraction of the FE ellipse   "
                 << fixed(phi, 5) << '\n'
                 << "  E phi (closed form)                     "
                 << fixed(E_phi * 1e-6, 1) << " MPa\n"
                 << "  k_e fitted to tau_xx = k_e I_e          "
                 << fixed(k_fit_num / k_fit_den * 1e-6, 1)
                 << " MPa (before the first break)\n"
                 << "  peak axial Kirchhoff stress             "
                 << fixed(peak * 1e-6, 1) << " MPa\n"
                 << "  broken fibres                           " << nb
                 << " of " << seg.nf << '\n';
          if (nb > 0)
            report << "  fibre break strains: min, mean, max     "
                   << fixed(bmin * 100., 4) << ", " << fixed(bmean * 100., 4)
                   << ", " << fixed(bmax * 100., 4) << " %, std "
                   << fixed(bstd * 100., 4) << " %\n";
          check("axial stress = E phi (lambda - 1) lambda before the first "
                "break within 1e-6",
                dev < 1e-6);
          if (y.failure && test.max_strain > y.failure_strain)
            {
              check("first break within 2e-5 of the failure strain",
                    nb > 0 && bmin >= y.failure_strain - 1e-12 &&
                      bmin < y.failure_strain + 2e-5);
              check("every fibre broken and the stress released (below "
                    "1e-3 of the peak)",
                    nb == seg.nf && std::abs(last.tau[0]) < 1e-3 * peak);
            }
        }
      else
        {
          const std::vector<double> pressures =
            (test.loading == ElementaryLoading::distortion ?
               test.confining_pressures :
               std::vector<double>{0.});
          for (const double pc : pressures)
            {
              const std::size_t first = rec.rows.size();
              run_plates(seg, rec, pc);
              // Peak of the loading branch, and the balance of the
              // internal virial with the walls' one.
              double peak_yy = 0., virial_gap = 0., ke_ratio = 0.;
              double ratio_peak = 0., servo_err = 0., servo_mean = 0.;
              unsigned int servo_rows = 0;
              const Row *at_peak = nullptr;
              for (std::size_t k = first; k < rec.rows.size(); ++k)
                {
                  const Row &r = rec.rows[k];
                  if (r.phase != "load")
                    continue;
                  if (-r.tau[1] >= peak_yy)
                    {
                      peak_yy = -r.tau[1];
                      at_peak = &r;
                    }
                }
              for (std::size_t k = first; k < rec.rows.size(); ++k)
                {
                  const Row &r = rec.rows[k];
                  if (r.phase != "load" || r.strain < 0.25 * test.max_strain)
                    continue;
                  virial_gap = std::max(virial_gap,
                                        std::abs(r.tau[1] - r.tau_boundary[0]) /
                                          std::max(peak_yy, 1e-300));
                  const double stored = r.sums.truss + r.sums.contact;
                  ke_ratio = std::max(ke_ratio, r.sums.kinetic / stored);
                  if (pc > 0.)
                    {
                      const double ratio = r.wall_load / r.plate_gap / pc;
                      servo_err = std::max(servo_err, std::abs(ratio - 1.));
                      servo_mean += ratio;
                      ++servo_rows;
                    }
                }
              servo_mean /= std::max(servo_rows, 1u);
              // Peak ratio of the Cauchy stresses of the box of walls, on
              // the rows where the side walls hold the pressure.
              for (std::size_t k = first; pc > 0. && k < rec.rows.size(); ++k)
                {
                  const Row &r = rec.rows[k];
                  const double s_yy = r.plate_load / r.wall_gap,
                               s_zz = r.wall_load / r.plate_gap;
                  if (r.phase == "load" && std::abs(s_zz / pc - 1.) < 0.05)
                    ratio_peak = std::max(ratio_peak, s_yy / s_zz);
                }
              const Row &end = rec.rows.back();
              report << "  confining pressure                      "
                     << fixed(pc * 1e-6, 2) << " MPa\n";
              if (at_peak)
                report << "  at the peak of -tau_yy (plate strain "
                       << fixed(at_peak->strain, 3)
                       << "): F_yy " << fixed(at_peak->F[4], 4) << ", F_zz "
                       << fixed(at_peak->F[8], 4) << ", I_tc "
                       << fixed(at_peak->inv.compaction, 4) << ", I_td "
                       << fixed(at_peak->inv.distortion, 4) << '\n'
                       << "    tau_yy " << fixed(at_peak->tau[1] * 1e-6, 3)
                       << " MPa, tau_zz " << fixed(at_peak->tau[2] * 1e-6, 3)
                       << " MPa, width/width_0 "
                       << fixed(at_peak->width / rec.rows[first].width, 4)
                       << '\n';
              report << "  after unloading: F_yy " << fixed(end.F[4], 4)
                     << ", F_zz " << fixed(end.F[8], 4) << ", tau_yy "
                     << fixed(end.tau[1] * 1e-6, 3) << " MPa\n";
              if (pc > 0.)
                {
                  const double phi_mu = std::atan(dem.friction);
                  const double closed =
                    std::sqrt(3.) / std::tan(PI / 6. - phi_mu);
                  report << "  peak stress ratio sigma_yy/sigma_zz     "
                         << fixed(ratio_peak, 3)
                         << " (rows of a hexagonal packing slide at "
                         << fixed(closed, 3) << ")\n";
                  report << "  side walls: sigma_zz / p_c on average "
                         << fixed(servo_mean, 4) << ", at worst off by "
                         << fixed(100. * servo_err, 1)
                         << " % (slip events)\n";
                  check("side walls hold the confining pressure within 2 % "
                        "on average over the loading",
                        std::abs(servo_mean - 1.) < 0.02);
                }
              if (peak_yy > 0.)
                check("virial of the contacts = virial of the plates within "
                      "5 % of the peak (quasi-static)",
                      virial_gap < 0.05);
              report << "  largest kinetic/stored energy (loading) "
                     << (testing ? fixed(ke_ratio, 3) : std::to_string(ke_ratio))
                     << '\n';
            }
        }
      if (!testing)
        report << "  neighbour-list rebuilds: " << seg.n_rebuilds
               << "\n  rows written to " << file << '\n';

      if (root)
        {
          csv.close();
          if (!csv)
            throw RunError("cannot write '" + partial + "' (disk full?)");
          std::error_code ec;
          std::filesystem::rename(partial, file, ec);
          if (ec)
            throw RunError("cannot rename '" + partial + "' to '" + file +
                           "': " + ec.message());
          out << report.str();
          std::ofstream summary(shared.output.directory + "/summary.txt");
          summary << report.str();
          if (!summary)
            throw RunError("cannot write the summary (disk full?)");
        }
      return passed;
    }
  } // namespace DEM
} // namespace YarnImpact
