#include <yarn_impact/core/history.h>

#include <iomanip>
#include <sstream>

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

  History::History(const std::string &directory,
                   const std::string &model_name,
                   const bool is_root)
  {
    if (!is_root)
      return;
    file.open(directory + "/history_" + model_name + ".csv");
    std::ostringstream header;
    const auto names = column_names();
    for (unsigned int i = 0; i < names.size(); ++i)
      header << (i > 0 ? "," : "") << names[i];
    header << '\n';
    file.append(header.str());
  }

  void
  History::add(const HistoryRow &r)
  {
    all_rows.push_back(r);
    if (!file.is_open())
      return;
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
         << ',' << m.n_damaged << '\n';
    file.append(line.str());
  }
} // namespace YarnImpact
