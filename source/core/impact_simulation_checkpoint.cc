// The checkpoint of the time loop's state: what ImpactSimulation writes
// and reads so that a restart makes bitwise the steps the uninterrupted run
// would make (doc/user-guide.md, "Checkpoint and restart").

#include "impact_simulation_implementation.h"

namespace YarnImpact
{
  std::string
  ImpactSimulation::Implementation::checkpoint_state(
    const Schedule &schedule,
    const double force,
    const RunResult &result,
    const std::string &stop_reason) const
  {
    Checkpoint::Writer w;
    w.tag("yarn-impact checkpoint");
    w.put(model->name());
    schedule.save(w);
    projectile.save(w);
    history->save(w);
    w.tag("loop");
    w.put(static_cast<std::uint64_t>(snapshots.size()));
    for (const auto &s : snapshots)
      {
        w.put(s.first);
        w.put(s.second);
      }
    w.put(initial_energy);
    w.put(force);
    w.put(next_checkpoint);
    w.put(result.max_energy_error);
    w.put(result.first_failure_time);
    w.put(result.cut_through_time);
    w.put(stop_reason);
    w.tag(model->name());
    model->save_state(w);
    w.tag("end");
    return w.contents();
  }


  void
  ImpactSimulation::Implementation::load_checkpoint(Checkpoint::Reader &in,
                                                    Schedule &schedule,
                                                    double &force,
                                                    RunResult &result,
                                                    std::string &stop_reason)
  {
    in.tag("yarn-impact checkpoint");
    std::string name;
    in.get(name);
    schedule.load(in);
    projectile.load(in);
    auto rows = History::load_rows(in);
    // A model's own columns may differ between versions (a column added):
    // rows of another count would shift the CSV's columns.
    const std::size_t n_columns = model->extra_column_names().size();
    for (const auto &row : rows)
      if (row.model.extra_columns.size() != n_columns)
        throw InputError("the checkpoint's history rows carry " +
                         std::to_string(row.model.extra_columns.size()) +
                         " columns of the " + name +
                         " model's own, where this program writes " +
                         std::to_string(n_columns) +
                         ": it was written by another version of the "
                         "program; start the run again without --restart.");
    in.tag("loop");
    std::uint64_t n_snapshots = 0;
    in.get(n_snapshots);
    snapshots.resize(n_snapshots);
    for (auto &s : snapshots)
      {
        in.get(s.first);
        in.get(s.second);
      }
    in.get(initial_energy);
    in.get(force);
    in.get(next_checkpoint);
    in.get(result.max_energy_error);
    in.get(result.first_failure_time);
    in.get(result.cut_through_time);
    in.get(stop_reason);
    in.tag(model->name());
    model->load_state(in);
    in.tag("end");
    in.expect_end();
    // The history as the uninterrupted run had it at the checkpoint: rows
    // written after it by the interrupted run are dropped.
    collective_output(communicator, [&] {
      history = std::make_unique<History>(parameters.output.directory,
                                          model->name(),
                                          is_root,
                                          std::move(rows),
                                          model->extra_column_names());
    });
    if (!snapshots.empty())
      write_pvd();
  }
} // namespace YarnImpact
