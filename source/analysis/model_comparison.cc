#include <yarn_impact/analysis/model_comparison.h>
#include <yarn_impact/core/output_file.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>

namespace YarnImpact
{
  namespace Analysis
  {
    namespace
    {
      /** Row of @p rows linearly interpolated at time t (all columns that
       * the comparison uses). */
      HistoryRow
      interpolate(const std::vector<HistoryRow> &rows, const double t)
      {
        if (rows.empty())
          return HistoryRow();
        if (t <= rows.front().time)
          return rows.front();
        if (t >= rows.back().time)
          return rows.back();
        const auto it =
          std::lower_bound(rows.begin(),
                           rows.end(),
                           t,
                           [](const HistoryRow &r, const double x) {
                             return r.time < x;
                           });
        const HistoryRow &b = *it;
        const HistoryRow &a = *(it - 1);
        const double w      = (t - a.time) / (b.time - a.time);
        const auto mix      = [w](const double x, const double y) {
          return (1. - w) * x + w * y;
        };
        HistoryRow r = a;
        r.time       = t;
        r.projectile_velocity =
          mix(a.projectile_velocity, b.projectile_velocity);
        r.fronts.longitudinal =
          mix(a.fronts.longitudinal, b.fronts.longitudinal);
        r.fronts.transverse = mix(a.fronts.transverse, b.fronts.transverse);
        r.fronts.spreading  = mix(a.fronts.spreading, b.fronts.spreading);
        r.fronts.width_at_impact =
          mix(a.fronts.width_at_impact, b.fronts.width_at_impact);
        r.fronts.rms_width_at_impact =
          mix(a.fronts.rms_width_at_impact, b.fronts.rms_width_at_impact);
        return r;
      }

      double
      first_failure(const std::vector<HistoryRow> &rows)
      {
        for (const auto &r : rows)
          if (r.model.n_failed > 0)
            return r.time;
        return -1.;
      }
    } // namespace


    ComparisonSummary
    compare_models(const std::vector<HistoryRow> &fe,
                   const std::vector<HistoryRow> &dem,
                   const std::string &directory)
    {
      ComparisonSummary s;
      s.first_dem_break  = first_failure(dem);
      s.first_fe_failure = first_failure(fe);
      const double end   = std::min(fe.empty() ? 0. : fe.back().time,
                                  dem.empty() ? 0. : dem.back().time);
      s.compared_until =
        (s.first_dem_break >= 0. ? std::min(s.first_dem_break, end) : end);

      AtomicFile file(directory + "/comparison.csv");
      std::ostream &csv = file.stream();
      csv << "t [us],v FE [m/s],v DEM [m/s],v FE - v DEM [m/s],"
             "longitudinal front FE [mm],longitudinal front DEM [mm],"
             "transverse front FE [mm],transverse front DEM [mm],"
             "spreading front FE [mm],spreading front DEM [mm],"
             "width at impact FE [mm],width at impact DEM [mm],"
             "RMS width at impact FE [mm],RMS width at impact DEM [mm]\n"
          << std::setprecision(8);
      for (const auto &row : fe)
        {
          if (row.time > end)
            break;
          const HistoryRow d = interpolate(dem, row.time);
          const double dv    = row.projectile_velocity - d.projectile_velocity;
          if (row.time <= s.compared_until &&
              std::abs(dv) > s.max_velocity_difference)
            {
              s.max_velocity_difference = std::abs(dv);
              s.time_of_max_difference  = row.time;
            }
          const auto &f = row.fronts, &g = d.fronts;
          csv << row.time * 1e6 << ',' << row.projectile_velocity << ','
              << d.projectile_velocity << ',' << dv << ','
              << f.longitudinal * 1e3 << ',' << g.longitudinal * 1e3 << ','
              << f.transverse * 1e3 << ',' << g.transverse * 1e3 << ','
              << f.spreading * 1e3 << ',' << g.spreading * 1e3 << ','
              << f.width_at_impact * 1e3 << ',' << g.width_at_impact * 1e3
              << ',' << f.rms_width_at_impact * 1e3 << ','
              << g.rms_width_at_impact * 1e3 << '\n';
        }
      file.commit();
      return s;
    }


    void
    print_comparison(const ComparisonSummary &s,
                     const double (&mass_per_length)[2],
                     const double (&axial_stiffness)[2],
                     const std::vector<HistoryRow> &fe,
                     const std::vector<HistoryRow> &dem,
                     std::ostream &out)
    {
      out << std::fixed << std::setprecision(4)
          << "Comparison of the FE and DEM models\n"
          << "  mass per length [mg/m]:     FE " << mass_per_length[0] * 1e6
          << ", DEM " << mass_per_length[1] * 1e6 << " (FE/DEM - 1 = "
          << 100. * (mass_per_length[0] / mass_per_length[1] - 1.) << " %)\n"
          << "  axial stiffness EA [N]:     FE " << axial_stiffness[0]
          << ", DEM " << axial_stiffness[1] << " (FE/DEM - 1 = "
          << 100. * (axial_stiffness[0] / axial_stiffness[1] - 1.) << " %)\n"
          << "  largest |v_FE - v_DEM| up to " << s.compared_until * 1e6
          << " us: " << s.max_velocity_difference << " m/s at "
          << s.time_of_max_difference * 1e6 << " us\n"
          << "  first DEM fibre break:      ";
      if (s.first_dem_break >= 0.)
        out << s.first_dem_break * 1e6 << " us\n";
      else
        out << "none\n";
      out << "  FE yarn failed:             ";
      if (s.first_fe_failure >= 0.)
        out << "yes, first cell at " << s.first_fe_failure * 1e6 << " us\n";
      else
        out << "no\n";
      out << "  energy budget at the end [mJ]: projectile kinetic, yarn "
             "kinetic, elastic, contact, dissipated, error [%]\n";
      for (const auto *rows : {&fe, &dem})
        if (!rows->empty())
          {
            const auto &r = rows->back();
            out << "    " << (rows == &fe ? "FE " : "DEM") << std::setw(10)
                << r.projectile_kinetic_energy * 1e3 << std::setw(10)
                << r.model.kinetic_energy * 1e3 << std::setw(10)
                << r.model.elastic_energy * 1e3 << std::setw(10)
                << r.model.contact_energy * 1e3 << std::setw(10)
                << r.model.dissipated_energy * 1e3 << std::setw(10)
                << r.energy_error * 1e2 << '\n';
          }
      out << std::defaultfloat;
    }
  } // namespace Analysis
} // namespace YarnImpact
