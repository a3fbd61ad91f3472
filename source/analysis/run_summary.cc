// What analysis measures on a run of the time loop: the wave fronts of each
// history row, and the summary (Smith-theory checks in the verification
// window).
#include <yarn_impact/analysis/run_summary.h>
#include <yarn_impact/analysis/smith_theory.h>
#include <yarn_impact/analysis/wave_fronts.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>

namespace YarnImpact
{
  namespace
  {
    /** Linear interpolation of a history quantity at time t. */
    template <typename Getter>
    double
    interpolate(const std::vector<HistoryRow> &rows,
                const double t,
                const Getter &get)
    {
      if (rows.empty())
        return 0.;
      if (t <= rows.front().time)
        return get(rows.front());
      for (unsigned int i = 1; i < rows.size(); ++i)
        if (rows[i].time >= t)
          {
            const double a =
              (t - rows[i - 1].time) / (rows[i].time - rows[i - 1].time);
            return (1. - a) * get(rows[i - 1]) + a * get(rows[i]);
          }
      return get(rows.back());
    }

    /** Least-squares slope of a history quantity over [t0, t1]. */
    template <typename Getter>
    double
    fitted_rate(const std::vector<HistoryRow> &rows,
                const double t0,
                const double t1,
                const Getter &get)
    {
      double st = 0., sy = 0., stt = 0., sty = 0.;
      unsigned int n = 0;
      for (const auto &r : rows)
        if (r.time >= t0 - 1e-15 && r.time <= t1 + 1e-15)
          {
            st += r.time;
            sy += get(r);
            stt += r.time * r.time;
            sty += r.time * get(r);
            ++n;
          }
      const double det = n * stt - st * st;
      return (n >= 2 && det > 0. ? (n * sty - st * sy) / det : 0.);
    }

    std::string
    format_check(const std::string &name,
                 const double measured,
                 const double reference,
                 const double scale,
                 const std::string &unit,
                 const double tolerance,
                 bool &passed,
                 std::vector<std::string> &brief)
    {
      const double error = (measured - reference) / std::abs(reference);
      const bool ok      = std::abs(error) <= tolerance;
      passed             = passed && ok;
      std::ostringstream b;
      b << std::fixed << std::setprecision(2) << name
        << " against Smith theory within " << 100. * tolerance
        << " %: " << (ok ? "PASSED" : "FAILED");
      brief.push_back(b.str());
      std::ostringstream s;
      s << std::fixed << std::setprecision(4) << name << ": measured "
        << measured * scale << " " << unit << ", Smith " << reference * scale
        << " " << unit << ", relative error " << std::setprecision(2)
        << 100. * error << " % (tolerance " << 100. * tolerance << " %) "
        << (ok ? "PASSED" : "FAILED");
      return s.str();
    }
  } // namespace


  namespace Analysis
  {
    RunHooks
    run_hooks(const YarnImpact::Parameters::Shared &shared,
              const Parameters &analysis)
    {
      RunHooks hooks;
      const WaveFrontThresholds thresholds = analysis.wave_fronts;
      hooks.measure_fronts = [thresholds](const StationProfile &profile) {
        return measure_wave_fronts(profile, thresholds);
      };
      const YarnImpact::Parameters::Projectile projectile = shared.projectile;
      hooks.report_setup = [projectile](const ImpactModel &model,
                                        std::ostream &out) {
        const auto smith = smith_solution(model.axial_properties(),
                                          projectile.initial_velocity,
                                          projectile.mass);
        out << std::setprecision(5) << "[" << model.name()
            << "] Smith theory at " << projectile.initial_velocity
            << " m/s: strain " << smith.strain << ", transverse wave "
            << smith.lab_speed << " m/s, deceleration " << smith.deceleration
            << " m/s^2\n";
      };
      return hooks;
    }


    RunSummary
    summarise_run(const RunResult &result,
                  const std::vector<HistoryRow> &rows,
                  const AxialProperties &axial,
                  const YarnImpact::Parameters::Shared &p,
                  const Parameters &analysis)
    {
      RunSummary summary;
      static_cast<RunResult &>(summary) = result;
      summary.regression_format =
        YarnImpact::Parameters::deterministic(p.output.verbosity);
      const auto smith =
        smith_solution(axial, p.projectile.initial_velocity, p.projectile.mass);
      const double t     = result.end_time;
      const double eps_t = 1e-9 * p.time.end_time;
      for (unsigned int k = 1; k <= 10; ++k)
        {
          const double ts = 0.1 * k * t;
          auto it         = std::lower_bound(rows.begin(),
                                     rows.end(),
                                     ts - eps_t,
                                     [](const HistoryRow &r, const double x) {
                                       return r.time < x;
                                     });
          if (it != rows.end())
            summary.samples.push_back(*it);
        }

      // Smith-theory quantities in the verification window.
      const double t0 = analysis.verification.window_start;
      const double t1 = std::min(analysis.verification.window_end, t);
      if (t1 > t0)
        {
          const auto v = [](const HistoryRow &r) {
            return r.projectile_velocity;
          };
          summary.mean_deceleration =
            (interpolate(rows, t0, v) - interpolate(rows, t1, v)) / (t1 - t0);
          // The longitudinal front stops at the clamp: its speed is fitted
          // only while it runs (up to 95 % of the half-length).
          double t1_front = t1;
          for (const auto &r : rows)
            if (r.time > t0 &&
                r.fronts.longitudinal >= 0.95 * 0.5 * p.yarn.length)
              {
                t1_front = std::min(t1, r.time);
                break;
              }
          if (t1_front < t1)
            summary.front_at_clamp_time = t1_front;
          // Too short a run to the clamp (a tenth of the window) gives no
          // speed worth reporting.
          summary.longitudinal_speed =
            (t1_front - t0 > 0.1 * (t1 - t0)
               ? fitted_rate(rows,
                             t0,
                             t1_front,
                             [](const HistoryRow &r) {
                               return r.fronts.longitudinal;
                             })
               : 0.);
          summary.transverse_speed =
            fitted_rate(rows, t0, t1, [](const HistoryRow &r) {
              return r.fronts.transverse;
            });
          double sum     = 0.;
          unsigned int n = 0;
          for (const auto &r : rows)
            if (r.time >= t0 && r.time <= t1)
              {
                sum += r.fronts.plateau_strain;
                ++n;
              }
          summary.plateau_strain = (n > 0 ? sum / n : 0.);
        }

      const auto &v    = analysis.verification;
      const double tol = v.tolerance;
      bool &ok         = summary.checks_passed;
      if (v.check_deceleration)
        summary.checks.push_back(format_check("mean deceleration",
                                              summary.mean_deceleration,
                                              smith.deceleration,
                                              1e-5,
                                              "1e5 m/s^2",
                                              tol,
                                              ok,
                                              summary.brief_checks));
      if (v.check_plateau_strain)
        summary.checks.push_back(format_check("strain behind the front",
                                              summary.plateau_strain,
                                              smith.strain,
                                              1e2,
                                              "%",
                                              tol,
                                              ok,
                                              summary.brief_checks));
      if (v.check_longitudinal_speed)
        summary.checks.push_back(format_check("longitudinal front speed",
                                              summary.longitudinal_speed,
                                              smith.wave_speed,
                                              1.,
                                              "m/s",
                                              tol,
                                              ok,
                                              summary.brief_checks));
      if (v.check_transverse_speed)
        summary.checks.push_back(format_check("transverse front speed",
                                              summary.transverse_speed,
                                              smith.lab_speed,
                                              1.,
                                              "m/s",
                                              tol,
                                              ok,
                                              summary.brief_checks));
      if (v.check_energy)
        {
          const bool e_ok = summary.max_energy_error <= v.energy_tolerance;
          std::ostringstream s;
          s << std::fixed << std::setprecision(4)
            << "energy balance: largest error "
            << 100. * summary.max_energy_error << " % of the initial energy "
            << "(tolerance " << 100. * v.energy_tolerance << " %) "
            << (e_ok ? "PASSED" : "FAILED");
          summary.checks.push_back(s.str());
          std::ostringstream b;
          b << std::fixed << std::setprecision(2) << "energy balance within "
            << 100. * v.energy_tolerance
            << " % of the initial energy: " << (e_ok ? "PASSED" : "FAILED");
          summary.brief_checks.push_back(b.str());
          ok = ok && e_ok;
        }

      return summary;
    }
  } // namespace Analysis


  namespace
  {
    /** The verification window's Smith quantities of @p s. */
    void
    print_window(const RunSummary &s, std::ostream &out)
    {
      out << "  window: mean deceleration   " << s.mean_deceleration * 1e-5
          << " 1e5 m/s^2\n"
          << "  window: plateau strain      " << s.plateau_strain * 1e2
          << " %\n"
          << "  window: longitudinal speed  ";
      if (s.front_at_clamp_time > 0. && s.longitudinal_speed == 0.)
        out << "not measured (the front reached the clamp at "
            << s.front_at_clamp_time * 1e6 << " us)";
      else
        out << s.longitudinal_speed << " m/s";
      if (s.front_at_clamp_time > 0. && s.longitudinal_speed != 0.)
        out << " (fitted up to " << s.front_at_clamp_time * 1e6
            << " us, when the front reached the clamp)";
      out << "\n  window: transverse speed    " << s.transverse_speed
          << " m/s\n";
    }


    /** The history samples, checks and remarks of @p s. */
    void
    print_samples(const RunSummary &s, std::ostream &out)
    {
      // The contact force jitters as surface nodes touch and leave the
      // projectile: the regression format leaves it out.
      out << "  history samples: t [us], v [m/s], "
          << (s.regression_format ? "" : "force [N], ")
          << "max strain [%], energy error [%], transverse front [mm], "
             "spreading front [mm]\n";
      for (const auto &r : s.samples)
        if (!s.regression_format || r.time <= 16e-6 * (1. + 1e-9))
          {
            out << "   " << std::setprecision(3) << std::setw(8) << r.time * 1e6
                << std::setprecision(4) << std::setw(10)
                << r.projectile_velocity;
            if (!s.regression_format)
              out << std::setprecision(3) << std::setw(9) << r.contact_force;
            out << std::setprecision(4) << std::setw(8)
                << 100. * r.model.max_strain << std::setw(9)
                << 100. * r.energy_error << std::setprecision(3) << std::setw(8)
                << 1e3 * r.fronts.transverse << std::setw(8)
                << 1e3 * r.fronts.spreading << '\n';
          }
      for (const auto &c : (s.regression_format ? s.brief_checks : s.checks))
        out << "  check " << c << '\n';
      if (!s.model_remarks.empty())
        out << "  " << s.model_remarks << '\n';
      out << std::defaultfloat;
    }
  } // namespace


  void
  print_summary(const RunSummary &s, std::ostream &out)
  {
    out << std::fixed << "Summary (" << s.model_name << " model)\n"
        << std::setprecision(4)
        << "  end time:                   " << s.end_time * 1e6 << " us\n";
    if (!s.regression_format)
      out << "  final projectile velocity:  " << s.final_velocity << " m/s\n"
          << "  largest energy error:       " << 100. * s.max_energy_error
          << " % of the initial energy\n";
    out << "  first failure:              ";
    if (s.first_failure_time >= 0.)
      out << s.first_failure_time * 1e6 << " us\n";
    else
      out << "none\n";
    // Erosion (cells crushed below J = 0.2, inverted or non-finite) is a
    // numerical removal, not a material failure: its own line, for the
    // models with FE cells.
    if (s.erodes_cells)
      {
        out << "  eroded cells:               ";
        if (s.first_erosion_time >= 0.)
          out << s.n_eroded << " (first at " << s.first_erosion_time * 1e6
              << " us)\n";
        else
          out << "none\n";
      }
    out << "  yarn cut through:           ";
    if (s.cut_through_time >= 0.)
      out << s.cut_through_time * 1e6 << " us\n";
    else
      out << "no\n";
    // The window's Smith quantities are those of one yarn struck
    // transversely; a woven patch has no such single yarn, so its summary
    // leaves them out (doc/fabric.md).
    if (s.single_yarn)
      print_window(s, out);
    print_samples(s, out);
  }
} // namespace YarnImpact
