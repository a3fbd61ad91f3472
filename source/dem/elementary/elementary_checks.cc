// What the DEM elementary tests measure on their rows, and the checks of
// the summary (elementary_phases.h; the theory in doc/identification.md).
#include <algorithm>
#include <cmath>
#include <iomanip>

#include "elementary_phases.h"

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      namespace
      {
        constexpr double PI = 3.14159265358979323846;

        std::string
        fixed(const double value, const int digits)
        {
          std::ostringstream s;
          s << std::fixed << std::setprecision(digits) << value;
          return s.str();
        }
      } // namespace


      void
      Report::check(const std::string &what, const bool ok)
      {
        text << "  check " << what << ": " << (ok ? "PASSED" : "FAILED")
             << '\n';
        passed = passed && ok;
      }


      TensionMeasures
      measure_tension(const std::vector<Row> &rows,
                      const std::vector<double> &breaks,
                      const double E_phi)
      {
        TensionMeasures m;
        // Before the first break the stress is E phi (lambda - 1) lambda
        // exactly: the trusses are linear in length and stretch affinely.
        double k_fit_num = 0., k_fit_den = 0.;
        for (const Row &r : rows)
          {
            m.peak = std::max(m.peak, r.tau[0]);
            if (r.broken_fibres > 0)
              continue;
            const double lambda = r.F[0];
            const double exact  = E_phi * (lambda - 1.) * lambda;
            if (exact > 0.)
              m.deviation =
                std::max(m.deviation, std::abs(r.tau[0] / exact - 1.));
            k_fit_num += r.tau[0] * r.inv.elongation;
            k_fit_den += r.inv.elongation * r.inv.elongation;
          }
        m.k_fit = k_fit_num / k_fit_den;
        for (const double b : breaks)
          if (b >= 0.)
            {
              m.break_min = std::min(m.break_min, b);
              m.break_max = std::max(m.break_max, b);
              m.break_mean += b;
              ++m.n_broken;
            }
        const unsigned int nb = m.n_broken;
        m.break_mean          = (nb > 0 ? m.break_mean / nb : 0.);
        for (const double b : breaks)
          if (b >= 0.)
            m.break_std += (b - m.break_mean) * (b - m.break_mean);
        m.break_std   = (nb > 1 ? std::sqrt(m.break_std / (nb - 1)) : 0.);
        m.last_tau_xx = rows.back().tau[0];
        return m;
      }


      void
      check_tension(const TensionMeasures &m,
                    const PeriodicSegment &seg,
                    const double phi,
                    const double E_phi,
                    Report &report)
      {
        const auto &y = seg.shared.yarn;
        report.text << "  fibre area fraction of the FE ellipse   "
                    << fixed(phi, 5) << '\n'
                    << "  E phi (closed form)                     "
                    << fixed(E_phi * 1e-6, 1) << " MPa\n"
                    << "  k_e fitted to tau_xx = k_e I_e          "
                    << fixed(m.k_fit * 1e-6, 1)
                    << " MPa (before the first break)\n"
                    << "  peak axial Kirchhoff stress             "
                    << fixed(m.peak * 1e-6, 1) << " MPa\n"
                    << "  broken fibres                           "
                    << m.n_broken << " of " << seg.nf << '\n';
        if (m.n_broken > 0)
          report.text << "  fibre break strains: min, mean, max     "
                      << fixed(m.break_min * 100., 4) << ", "
                      << fixed(m.break_mean * 100., 4) << ", "
                      << fixed(m.break_max * 100., 4) << " %, std "
                      << fixed(m.break_std * 100., 4) << " %\n";
        report.check("axial stress = E phi (lambda - 1) lambda before the "
                     "first break within 1e-6",
                     m.deviation < 1e-6);
        if (y.failure && seg.test.max_strain > y.failure_strain)
          {
            report.check("first break within 2e-5 of the failure strain",
                         m.n_broken > 0 &&
                           m.break_min >= y.failure_strain - 1e-12 &&
                           m.break_min < y.failure_strain + 2e-5);
            report.check("every fibre broken and the stress released (below "
                         "1e-3 of the peak)",
                         m.n_broken == seg.nf &&
                           std::abs(m.last_tau_xx) < 1e-3 * m.peak);
          }
      }


      PlateMeasures
      measure_plates(const std::vector<Row> &rows,
                     const std::size_t first,
                     const double pc,
                     const double max_strain)
      {
        PlateMeasures m;
        m.first = &rows[first];
        m.end   = &rows.back();
        // Peak of the loading branch, and the balance of the internal
        // virial with the walls' one.
        unsigned int servo_rows = 0;
        for (std::size_t k = first; k < rows.size(); ++k)
          {
            const Row &r = rows[k];
            if (r.phase != "load")
              continue;
            if (-r.tau[1] >= m.peak_yy)
              {
                m.peak_yy = -r.tau[1];
                m.at_peak = &r;
              }
          }
        for (std::size_t k = first; k < rows.size(); ++k)
          {
            const Row &r = rows[k];
            if (r.phase != "load" || r.strain < 0.25 * max_strain)
              continue;
            m.virial_gap        = std::max(m.virial_gap,
                                    std::abs(r.tau[1] - r.tau_boundary[0]) /
                                      std::max(m.peak_yy, 1e-300));
            const double stored = r.sums.truss + r.sums.contact;
            m.ke_ratio          = std::max(m.ke_ratio, r.sums.kinetic / stored);
            if (pc > 0.)
              {
                const double ratio = r.wall_load / r.plate_gap / pc;
                m.servo_err = std::max(m.servo_err, std::abs(ratio - 1.));
                m.servo_mean += ratio;
                ++servo_rows;
              }
          }
        m.servo_mean /= std::max(servo_rows, 1u);
        // Peak ratio of the Cauchy stresses of the box of walls, on the
        // rows where the side walls hold the pressure.
        for (std::size_t k = first; pc > 0. && k < rows.size(); ++k)
          {
            const Row &r      = rows[k];
            const double s_yy = r.plate_load / r.wall_gap,
                         s_zz = r.wall_load / r.plate_gap;
            if (r.phase == "load" && std::abs(s_zz / pc - 1.) < 0.05)
              m.ratio_peak = std::max(m.ratio_peak, s_yy / s_zz);
          }
        return m;
      }


      void
      check_plates(const PlateMeasures &m,
                   const double pc,
                   const double friction,
                   const bool testing,
                   Report &report)
      {
        std::ostringstream &text = report.text;
        text << "  confining pressure                      "
             << fixed(pc * 1e-6, 2) << " MPa\n";
        if (const Row *p = m.at_peak)
          text << "  at the peak of -tau_yy (plate strain "
               << fixed(p->strain, 3) << "): F_yy " << fixed(p->F[4], 4)
               << ", F_zz " << fixed(p->F[8], 4) << ", I_tc "
               << fixed(p->inv.compaction, 4) << ", I_td "
               << fixed(p->inv.distortion, 4) << '\n'
               << "    tau_yy " << fixed(p->tau[1] * 1e-6, 3) << " MPa, tau_zz "
               << fixed(p->tau[2] * 1e-6, 3) << " MPa, width/width_0 "
               << fixed(p->width / m.first->width, 4) << '\n';
        text << "  after unloading: F_yy " << fixed(m.end->F[4], 4) << ", F_zz "
             << fixed(m.end->F[8], 4) << ", tau_yy "
             << fixed(m.end->tau[1] * 1e-6, 3) << " MPa\n";
        if (pc > 0.)
          {
            const double phi_mu = std::atan(friction);
            const double closed = std::sqrt(3.) / std::tan(PI / 6. - phi_mu);
            text << "  peak stress ratio sigma_yy/sigma_zz     "
                 << fixed(m.ratio_peak, 3)
                 << " (rows of a hexagonal packing slide at "
                 << fixed(closed, 3) << ")\n";
            text << "  side walls: sigma_zz / p_c on average "
                 << fixed(m.servo_mean, 4) << ", at worst off by "
                 << fixed(100. * m.servo_err, 1) << " % (slip events)\n";
            report.check("side walls hold the confining pressure within 2 % "
                         "on average over the loading",
                         std::abs(m.servo_mean - 1.) < 0.02);
          }
        if (m.peak_yy > 0.)
          report.check("virial of the contacts = virial of the plates within "
                       "5 % of the peak (quasi-static)",
                       m.virial_gap < 0.05);
        text << "  largest kinetic/stored energy (loading) "
             << (testing ? fixed(m.ke_ratio, 3) : std::to_string(m.ke_ratio))
             << '\n';
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
