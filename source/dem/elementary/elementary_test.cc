// DEM elementary tests: a periodic segment of the yarn (the impact model's
// fibres, packing and contact laws) under a homogeneous deformation, with
// its homogenised stress. The theory, the boundary conditions and the
// checks are in doc/identification.md.
#include <yarn_impact/contact/contact_law.h>
#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/output_file.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/dem/elementary/elementary_test.h>
#include <yarn_impact/dem/elementary/periodic_segment.h>
#include <yarn_impact/mechanics/kinematics.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <csignal>
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
      using internal::PeriodicSegment;
      using internal::Sums;
      using internal::Wall;
      constexpr double PI = 3.14159265358979323846;


      /** One row of the CSV and what the summary needs of it. */
      struct Row
      {
        std::string phase;
        double pressure = 0., time = 0., strain = 0.;
        Mechanics::Matrix3 F;
        Mechanics::Invariants inv;
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
        Recorder(PeriodicSegment &segment,
                 AppendFile *csv,
                 const std::string &name,
                 const std::string &partial)
          : seg(segment)
          , csv(csv)
          , name(name)
          , partial(partial)
          , signal_poll(segment.comm)
        {}

        /** One step of the segment; a SIGTERM or SIGINT (agreed by the
         * ranks within a few steps) stops the test between two steps, its
         * rows so far kept in the .partial file. */
        void
        step()
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
              << strain << ',' << r.F[0] << ',' << r.F[4] << ',' << r.F[5]
              << ',' << r.F[7] << ',' << r.F[8] << ',' << r.inv.elongation
              << ',' << r.inv.compaction << ',' << r.inv.distortion << ','
              << r.height << ',' << r.width << ',' << r.tau[0] << ','
              << r.tau[1] << ',' << r.tau[2] << ',' << r.tau[3] << ','
              << r.tau_boundary[0] << ',' << r.tau_boundary[1] << ','
              << r.plate_gap << ',' << r.plate_load << ',' << r.wall_gap << ','
              << r.wall_load << ',' << r.sums.kinetic << ',' << r.sums.truss
              << ',' << r.sums.contact << ',' << r.sums.dissipated << ','
              << r.broken_fibres << '\n';
            csv->append(o.str());
          });
          rows.push_back(r);
          return r;
        }

        PeriodicSegment &seg;
        AppendFile *csv;
        std::string name;
        std::string partial;
        Checkpoint::SignalPoll signal_poll;
        std::vector<Row> rows;
      };


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


      /** Tension along the fibres, to failure. */
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


      /** Plates normal to y close at the strain rate, then reopen; with
       * @p pressure > 0, side walls normal to z hold the yarn at that
       * pressure, after a consolidation in which the plates do too. */
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
      const bool root    = Utilities::MPI::this_mpi_process(communicator) == 0;
      const bool testing = shared.output.verbosity == Verbosity::test;
      PeriodicSegment seg(shared, dem, test, communicator);
      const auto &y      = shared.yarn;
      const double phi   = y.fibre_area() / y.section_area();
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
      AppendFile csv;
      collective_output(communicator, [&] {
        if (root)
          {
            csv.open(partial);
            csv.append(std::string(csv_header) + '\n');
          }
      });
      const std::string name =
        elementary_test_file(test.loading).substr(11, std::string::npos);
      Recorder rec(seg,
                   root ? &csv : nullptr,
                   name.substr(0, name.size() - 4),
                   partial);

      bool passed = true;
      auto check  = [&](const std::string &what, const bool ok) {
        report << "  check " << what << ": " << (ok ? "PASSED" : "FAILED")
               << '\n';
        passed = passed && ok;
      };

      report << "Elementary test (" << rec.name << ", " << seg.nf << " fibres, "
             << seg.ns << " cross-sections, periodic)\n";
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
          bmean       = (nb > 0 ? bmean / nb : 0.);
          double bstd = 0.;
          for (const double b : breaks)
            if (b >= 0.)
              bstd += (b - bmean) * (b - bmean);
          bstd            = (nb > 1 ? std::sqrt(bstd / (nb - 1)) : 0.);
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
                 << "  broken fibres                           " << nb << " of "
                 << seg.nf << '\n';
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
            (test.loading == ElementaryLoading::distortion
               ? test.confining_pressures
               : std::vector<double>{0.});
          for (const double pc : pressures)
            {
              const std::size_t first = rec.rows.size();
              run_plates(seg, rec, pc);
              // Peak of the loading branch, and the balance of the
              // internal virial with the walls' one.
              double peak_yy = 0., virial_gap = 0., ke_ratio = 0.;
              double ratio_peak = 0., servo_err = 0., servo_mean = 0.;
              unsigned int servo_rows = 0;
              const Row *at_peak      = nullptr;
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
                  virial_gap          = std::max(virial_gap,
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
                  const Row &r      = rec.rows[k];
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
                       << fixed(at_peak->strain, 3) << "): F_yy "
                       << fixed(at_peak->F[4], 4) << ", F_zz "
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
                         << fixed(100. * servo_err, 1) << " % (slip events)\n";
                  check("side walls hold the confining pressure within 2 % "
                        "on average over the loading",
                        std::abs(servo_mean - 1.) < 0.02);
                }
              if (peak_yy > 0.)
                check("virial of the contacts = virial of the plates within "
                      "5 % of the peak (quasi-static)",
                      virial_gap < 0.05);
              report << "  largest kinetic/stored energy (loading) "
                     << (testing ? fixed(ke_ratio, 3)
                                 : std::to_string(ke_ratio))
                     << '\n';
            }
        }
      if (!testing)
        report << "  neighbour-list rebuilds: " << seg.n_rebuilds
               << "\n  rows written to " << file << '\n';

      // The curves get their final name only once complete.
      collective_output(communicator, [&] {
        if (!root)
          return;
        std::error_code ec;
        std::filesystem::rename(partial, file, ec);
        if (ec)
          throw OutputError("cannot rename '" + partial + "' to '" + file +
                            "': " + ec.message() + ".");
      });
      if (root)
        out << report.str();
      collective_output(communicator, [&] {
        if (root)
          write_file_atomically(shared.output.directory + "/summary.txt",
                                report.str());
      });
      return passed;
    }
  } // namespace DEM
} // namespace YarnImpact
