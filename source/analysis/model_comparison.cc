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


    std::string
    model_label(const std::string &name)
    {
      if (name == "fe")
        return "FE";
      if (name == "dem")
        return "DEM";
      return name;
    }


    std::vector<ComparisonSummary>
    compare_models(const std::vector<ComparedRun> &runs,
                   const unsigned int reference,
                   const std::string &directory)
    {
      const std::vector<HistoryRow> &dem = runs.at(reference).history;
      const std::string &ref             = runs[reference].label;
      std::vector<ComparisonSummary> summaries(runs.size());
      double end = dem.empty() ? 0. : dem.back().time;
      for (const ComparedRun &run : runs)
        end = std::min(end, run.history.empty() ? 0. : run.history.back().time);
      const double first_dem_break = first_failure(dem);
      for (unsigned int m = 0; m < runs.size(); ++m)
        if (m != reference)
          {
            ComparisonSummary &s = summaries[m];
            s.first_dem_break    = first_dem_break;
            s.first_fe_failure   = first_failure(runs[m].history);
            s.compared_until =
              (s.first_dem_break >= 0. ? std::min(s.first_dem_break, end)
                                       : end);
          }

      AtomicFile file(directory + "/comparison.csv");
      std::ostream &csv = file.stream();
      csv << "t [us]";
      for (const ComparedRun &run : runs)
        csv << ",v " << run.label << " [m/s]";
      for (unsigned int m = 0; m < runs.size(); ++m)
        if (m != reference)
          csv << ",v " << runs[m].label << " - v " << ref << " [m/s]";
      for (const char *front : {"longitudinal front",
                                "transverse front",
                                "spreading front",
                                "width at impact",
                                "RMS width at impact"})
        for (const ComparedRun &run : runs)
          csv << ',' << front << ' ' << run.label << " [mm]";
      csv << '\n' << std::setprecision(8);
      std::vector<HistoryRow> at(runs.size());
      for (const auto &row : runs.front().history)
        {
          if (row.time > end)
            break;
          for (unsigned int m = 0; m < runs.size(); ++m)
            at[m] = m == 0 ? row : interpolate(runs[m].history, row.time);
          csv << row.time * 1e6;
          for (const HistoryRow &r : at)
            csv << ',' << r.projectile_velocity;
          for (unsigned int m = 0; m < runs.size(); ++m)
            if (m != reference)
              {
                const double dv =
                  at[m].projectile_velocity - at[reference].projectile_velocity;
                ComparisonSummary &s = summaries[m];
                if (row.time <= s.compared_until &&
                    std::abs(dv) > s.max_velocity_difference)
                  {
                    s.max_velocity_difference = std::abs(dv);
                    s.time_of_max_difference  = row.time;
                  }
                csv << ',' << dv;
              }
          for (const auto front : {&WaveFrontPositions::longitudinal,
                                   &WaveFrontPositions::transverse,
                                   &WaveFrontPositions::spreading,
                                   &WaveFrontPositions::width_at_impact,
                                   &WaveFrontPositions::rms_width_at_impact})
            for (const HistoryRow &r : at)
              csv << ',' << r.fronts.*front * 1e3;
          csv << '\n';
        }
      file.commit();
      return summaries;
    }


    void
    print_comparison(const std::vector<ComparisonSummary> &summaries,
                     const std::vector<ComparedRun> &runs,
                     const unsigned int reference,
                     std::ostream &out)
    {
      const ComparedRun &dem = runs.at(reference);
      const std::string &ref = dem.label;
      for (unsigned int m = 0; m < runs.size(); ++m)
        {
          if (m == reference)
            continue;
          const ComparisonSummary &s = summaries.at(m);
          const ComparedRun &run     = runs[m];
          const std::string &name    = run.label;
          // The labels padded to the width the FE's lines have had.
          const auto field = [](const std::string &text) {
            return text +
                   std::string(text.size() < 28 ? 28 - text.size() : 1, ' ');
          };
          out << std::fixed << std::setprecision(4) << "Comparison of the "
              << name << " and " << ref << " models\n"
              << "  mass per length [mg/m]:     " << name << ' '
              << run.mass_per_length * 1e6 << ", " << ref << ' '
              << dem.mass_per_length * 1e6 << " (" << name << '/' << ref
              << " - 1 = "
              << 100. * (run.mass_per_length / dem.mass_per_length - 1.)
              << " %)\n"
              << "  axial stiffness EA [N]:     " << name << ' '
              << run.axial_stiffness << ", " << ref << ' '
              << dem.axial_stiffness << " (" << name << '/' << ref << " - 1 = "
              << 100. * (run.axial_stiffness / dem.axial_stiffness - 1.)
              << " %)\n"
              << "  largest |v_" << name << " - v_" << ref << "| up to "
              << s.compared_until * 1e6 << " us: " << s.max_velocity_difference
              << " m/s at " << s.time_of_max_difference * 1e6 << " us\n"
              << "  " << field("first " + ref + " fibre break:");
          if (s.first_dem_break >= 0.)
            out << s.first_dem_break * 1e6 << " us\n";
          else
            out << "none\n";
          out << "  " << field(name + " yarn failed:");
          if (s.first_fe_failure >= 0.)
            out << "yes, first " << (name == "FE" ? "cell" : "break") << " at "
                << s.first_fe_failure * 1e6 << " us\n";
          else
            out << "no\n";
          // The cost of the same problem, the runs one after the other on
          // the same ranks.
          if (run.wall_time >= 0. && dem.wall_time > 0.)
            out << std::setprecision(1) << "  " << field("wall time [s]:")
                << name << ' ' << run.wall_time << ", " << ref << ' '
                << dem.wall_time << std::setprecision(3) << " (" << name << '/'
                << ref << " = " << run.wall_time / dem.wall_time << ")\n"
                << std::setprecision(4);
          out << "  energy budget at the end [mJ]: projectile kinetic, yarn "
                 "kinetic, elastic, contact, dissipated, error [%]\n";
          for (const ComparedRun *r : {&run, &dem})
            if (!r->history.empty())
              {
                const auto &last  = r->history.back();
                std::string label = r->label;
                if (label.size() < 3)
                  label += std::string(3 - label.size(), ' ');
                out << "    " << label << std::setw(10)
                    << last.projectile_kinetic_energy * 1e3 << std::setw(10)
                    << last.model.kinetic_energy * 1e3 << std::setw(10)
                    << last.model.elastic_energy * 1e3 << std::setw(10)
                    << last.model.contact_energy * 1e3 << std::setw(10)
                    << last.model.dissipated_energy * 1e3 << std::setw(10)
                    << last.energy_error * 1e2 << '\n';
              }
          out << std::defaultfloat;
        }
    }
  } // namespace Analysis
} // namespace YarnImpact
