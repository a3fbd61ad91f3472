// The loadings of the DEM elementary tests (tension, plates with or
// without confining side walls) and the rows they record
// (elementary_phases.h).
#include <yarn_impact/core/impact_simulation.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <iomanip>

#include "elementary_phases.h"

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      const char *const elementary_csv_header =
        "loading,confining_pressure,phase,time,imposed_strain,F_xx,F_yy,F_yz,"
        "F_zy,F_zz,I_e,I_tc,I_td,height,width,tau_xx,tau_yy,tau_zz,tau_yz,"
        "tau_yy_boundary,tau_zz_boundary,plate_gap,plate_load,wall_gap,"
        "wall_load,kinetic_energy,truss_energy,contact_energy,"
        "dissipated_energy,broken_fibres";


      Recorder::Recorder(PeriodicSegment &segment,
                         AppendFile *csv,
                         const std::string &name,
                         const std::string &partial)
        : seg(segment)
        , csv(csv)
        , name(name)
        , partial(partial)
        , signal_poll(segment.comm)
      {}


      void
      Recorder::step()
      {
        seg.step();
        if (const int signal = signal_poll.poll(); signal != 0)
          throw Interrupted(
            "the elementary test (" + name + ") was stopped by " +
            (signal == SIGINT ? "SIGINT" : "SIGTERM") +
            " at t = " + std::to_string(seg.time * 1e6) +
            " us; its rows so far are in " + partial +
            " (the elementary tests write no checkpoints: run it again "
            "to finish it)");
      }


      Row
      Recorder::record(const std::string &phase,
                       const double pressure,
                       const double strain)
      {
        Row r;
        r.phase    = phase;
        r.pressure = pressure;
        r.time     = seg.time;
        r.strain   = strain;
        seg.affine_gradient(r.F);
        r.inv             = Mechanics::invariants(r.F);
        const auto m      = seg.second_moments();
        r.height          = 4. * std::sqrt(m.first);
        r.width           = 4. * std::sqrt(m.second);
        r.sums            = seg.sums();
        const double *w   = r.sums.virial;
        r.tau[0]          = w[0] / seg.V0;
        r.tau[1]          = w[1] / seg.V0;
        r.tau[2]          = w[2] / seg.V0;
        r.tau[3]          = w[3] / seg.V0;
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
        // Every checked quantity finite, or the test stops (on every rank:
        // the sums are collective).
        bool finite =
          std::isfinite(r.sums.kinetic) && std::isfinite(r.sums.truss) &&
          std::isfinite(r.sums.contact) && std::isfinite(r.sums.dissipated) &&
          std::isfinite(r.plate_load) && std::isfinite(r.wall_load);
        for (const double t : r.tau)
          finite = finite && std::isfinite(t);
        if (!finite)
          throw RunError("the elementary test (" + name +
                         ") blew up at t = " + std::to_string(r.time * 1e6) +
                         " us (a non-finite energy, stress or wall load); "
                         "reduce Elementary test/Strain rate or "
                         "Time/Safety factor");
        // Every rank records (the sums are collective); rank 0 writes, and
        // a failed write stops all ranks alike.
        collective_output(seg.comm, [&] {
          if (csv == nullptr)
            return;
          std::ostringstream o;
          o << std::setprecision(10);
          o << name << ',' << pressure << ',' << phase << ',' << r.time << ','
            << strain << ',' << r.F[0] << ',' << r.F[4] << ',' << r.F[5] << ','
            << r.F[7] << ',' << r.F[8] << ',' << r.inv.elongation << ','
            << r.inv.compaction << ',' << r.inv.distortion << ',' << r.height
            << ',' << r.width << ',' << r.tau[0] << ',' << r.tau[1] << ','
            << r.tau[2] << ',' << r.tau[3] << ',' << r.tau_boundary[0] << ','
            << r.tau_boundary[1] << ',' << r.plate_gap << ',' << r.plate_load
            << ',' << r.wall_gap << ',' << r.wall_load << ',' << r.sums.kinetic
            << ',' << r.sums.truss << ',' << r.sums.contact << ','
            << r.sums.dissipated << ',' << r.broken_fibres << '\n';
          csv->append(o.str());
        });
        rows.push_back(r);
        return r;
      }


      namespace
      {
        /** Servo of a wall that holds the yarn at @p force [N]: a PI
         * controller on the force error, critically damped for the stiffness
         * of the wall's contacts, so that it follows a spreading section
         * without a lag error; at most @p v_max [m/s]. */
        void
        servo(Wall &w,
              const double force,
              const double k_n,
              const double dt,
              const double v_max)
        {
          constexpr double alpha = 0.05; // error closed per step, proportional
          const double k         = k_n * std::max(1u, w.n_in);
          const double err       = w.load - force;
          w.integral =
            std::clamp(w.integral + 0.25 * alpha * alpha * err / (k * dt),
                       -v_max,
                       v_max);
          const double v =
            std::clamp(alpha * err / (k * dt) + w.integral, -v_max, v_max);
          w.velocity = w.side * v;
        }
      } // namespace


      void
      run_tension(PeriodicSegment &seg, Recorder &rec)
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
            rec.step();
          }
      }


      void
      run_plates(PeriodicSegment &seg, Recorder &rec, const double pressure)
      {
        const auto &t = seg.test;
        seg.reset();
        Wall *W = seg.walls;
        const bool side_walls =
          pressure > 0. || t.side_walls == SideWalls::fixed;
        for (unsigned int k = 0; k < (side_walls ? 4u : 2u); ++k)
          {
            W[k].active = true;
            W[k].axis   = 1 + k / 2;
            W[k].side   = (k % 2 == 0 ? 1. : -1.);
            W[k].position =
              seg.extreme(W[k].axis, W[k].side) + W[k].side * seg.radius;
          }
        const double k_n    = seg.wall_law.k_n;
        const double gap_y0 = W[0].position - W[1].position;
        if (pressure > 0.)
          {
            const double gap_z0 = W[2].position - W[3].position;
            const double v_max = 10. * t.strain_rate * std::max(gap_y0, gap_z0);
            const double t_end = t.consolidation_time;
            double next        = 0.;
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
                rec.step();
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
                  loading
                    ? std::min(t.max_strain, t.strain_rate * elapsed)
                    : std::max(0., t.max_strain - t.strain_rate * elapsed);
                const bool done =
                  loading ? strain >= t.max_strain : strain <= 0.;
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
                rec.step();
              }
          }
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
