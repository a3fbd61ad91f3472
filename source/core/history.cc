#include <yarn_impact/core/history.h>

#include <iomanip>
#include <sstream>
#include <utility>

namespace YarnImpact
{
  std::vector<std::string>
  History::column_names()
  {
    return {"t [us]",
            "step",
            "dt [ns]",
            "projectile displacement [mm]",
            "projectile velocity [m/s]",
            "contact force [N]",
            "yarn kinetic energy [mJ]",
            "projectile kinetic energy [mJ]",
            "elastic energy [mJ]",
            "contact energy [mJ]",
            "dissipated energy [mJ]",
            "external work [mJ]",
            "energy error [%]",
            "max longitudinal strain [-]",
            "failed elements",
            "longitudinal front [mm]",
            "transverse front [mm]",
            "spreading front [mm]",
            "section width at impact [mm]",
            "plateau strain [-]",
            "section RMS width at impact [mm]",
            "eroded elements",
            "damaged elements"};
  }

  void
  History::open(const std::string &directory,
                const std::string &model_name,
                const bool is_root,
                const std::vector<std::string> &extra_columns)
  {
    if (!is_root)
      return;
    file.open(directory + "/history_" + model_name + ".csv");
    std::ostringstream header;
    const auto names = column_names();
    for (unsigned int i = 0; i < names.size(); ++i)
      header << (i > 0 ? "," : "") << names[i];
    for (const auto &name : extra_columns)
      header << ',' << name;
    header << '\n';
    file.append(header.str());
  }

  History::History(const std::string &directory,
                   const std::string &model_name,
                   const bool is_root,
                   const std::vector<std::string> &extra_columns)
  {
    open(directory, model_name, is_root, extra_columns);
  }

  History::History(const std::string &directory,
                   const std::string &model_name,
                   const bool is_root,
                   std::vector<HistoryRow> rows,
                   const std::vector<std::string> &extra_columns)
    : all_rows(std::move(rows))
  {
    open(directory, model_name, is_root, extra_columns);
    if (!file.is_open())
      return;
    std::string text;
    for (const auto &row : all_rows)
      text += format(row);
    file.append(text);
  }

  void
  History::save(Checkpoint::Writer &out) const
  {
    out.tag("history");
    out.put(static_cast<std::uint64_t>(all_rows.size()));
    for (const auto &r : all_rows)
      {
        const auto &m = r.model;
        out.put(r.time);
        out.put(r.step);
        out.put(r.time_step);
        out.put(r.projectile_displacement);
        out.put(r.projectile_velocity);
        out.put(r.contact_force);
        out.put(r.projectile_kinetic_energy);
        out.put(r.external_work);
        out.put(r.energy_error);
        out.put(m.kinetic_energy);
        out.put(m.elastic_energy);
        out.put(m.contact_energy);
        out.put(m.dissipated_energy);
        out.put(m.max_strain);
        out.put(m.n_failed);
        out.put(m.n_eroded);
        out.put(m.n_damaged);
        out.put(m.cut_through);
        out.put(m.momentum);
        out.put(m.extra_columns);
        out.put(r.fronts);
      }
  }

  std::vector<HistoryRow>
  History::load_rows(Checkpoint::Reader &in)
  {
    in.tag("history");
    std::uint64_t n = 0;
    in.get(n);
    std::vector<HistoryRow> rows;
    for (std::uint64_t i = 0; i < n; ++i)
      {
        HistoryRow r;
        auto &m = r.model;
        in.get(r.time);
        in.get(r.step);
        in.get(r.time_step);
        in.get(r.projectile_displacement);
        in.get(r.projectile_velocity);
        in.get(r.contact_force);
        in.get(r.projectile_kinetic_energy);
        in.get(r.external_work);
        in.get(r.energy_error);
        in.get(m.kinetic_energy);
        in.get(m.elastic_energy);
        in.get(m.contact_energy);
        in.get(m.dissipated_energy);
        in.get(m.max_strain);
        in.get(m.n_failed);
        in.get(m.n_eroded);
        in.get(m.n_damaged);
        in.get(m.cut_through);
        in.get(m.momentum);
        in.get(m.extra_columns);
        in.get(r.fronts);
        rows.push_back(std::move(r));
      }
    return rows;
  }

  void
  History::add(const HistoryRow &r)
  {
    all_rows.push_back(r);
    if (file.is_open())
      file.append(format(r));
  }

  std::string
  History::format(const HistoryRow &r)
  {
    const auto &m = r.model;
    std::ostringstream line;
    line << std::setprecision(10);
    line << r.time * 1e6 << ',' << r.step << ',' << r.time_step * 1e9 << ','
         << r.projectile_displacement * 1e3 << ',' << r.projectile_velocity
         << ',' << r.contact_force << ',' << m.kinetic_energy * 1e3 << ','
         << r.projectile_kinetic_energy * 1e3 << ',' << m.elastic_energy * 1e3
         << ',' << m.contact_energy * 1e3 << ',' << m.dissipated_energy * 1e3
         << ',' << r.external_work * 1e3 << ',' << r.energy_error * 1e2 << ','
         << m.max_strain << ',' << m.n_failed << ','
         << r.fronts.longitudinal * 1e3 << ',' << r.fronts.transverse * 1e3
         << ',' << r.fronts.spreading * 1e3 << ','
         << r.fronts.width_at_impact * 1e3 << ',' << r.fronts.plateau_strain
         << ',' << r.fronts.rms_width_at_impact * 1e3 << ',' << m.n_eroded
         << ',' << m.n_damaged;
    // The model's own columns with every digit of a double, so that
    // balances among them (a momentum's) can be checked to round-off.
    line << std::setprecision(17);
    for (const double value : m.extra_columns)
      line << ',' << value;
    line << '\n';
    return line.str();
  }
} // namespace YarnImpact
