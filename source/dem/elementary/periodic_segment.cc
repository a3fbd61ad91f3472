// The periodic yarn segment of the DEM elementary tests: the impact
// model's fibres, trusses and contact laws on a segment periodic along x,
// with rigid walls (doc/identification.md section 2). This file sets it up
// and steps it; the neighbour lists, the forces and what is measured on it
// are in periodic_segment_lists.cc, periodic_segment_forces.cc and
// periodic_segment_measures.cc.
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/dem/elementary/periodic_segment.h>
#include <yarn_impact/dem/packing.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
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
        fibre_law = fibre_contact_law(dem, truss_k, mass);
        wall_law  = Contact::CundallStrackLaw(
          projectile_contact_constants(dem, truss_k, mass));
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
