// The private implementation of ImpactSimulation (core/impact_simulation.h),
// shared by impact_simulation.cc (the loop and its output) and
// impact_simulation_checkpoint.cc (the checkpoint of the loop's state).
#ifndef yarn_impact_core_impact_simulation_implementation_h
#define yarn_impact_core_impact_simulation_implementation_h

#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/core/time_stepping.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <exception>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace YarnImpact
{
  using namespace dealii;

  class ImpactSimulation::Implementation
  {
  public:
    Implementation(const Parameters::Shared &parameters,
                   std::unique_ptr<ImpactModel> model,
                   const MPI_Comm communicator,
                   std::ostream &out,
                   RunHooks hooks,
                   CheckpointOptions checkpoints)
      : parameters(parameters)
      , model(std::move(model))
      , hooks(std::move(hooks))
      , checkpoints(checkpoints)
      , communicator(communicator)
      , is_root(Utilities::MPI::this_mpi_process(communicator) == 0)
      , out(out, is_root)
      , projectile(parameters.projectile, parameters.yarn.thickness_semi_axis)
    {}

    RunResult
    run();

    /** The run, timed by @p timer. */
    RunResult
    run_timed(TimerOutput &timer);

    HistoryRow
    make_row(const double time,
             const unsigned long step,
             const double dt,
             const double force) const;

    void
    write_snapshot(const double time);

    /** Write `<model>.pvd` listing #snapshots, whole or not at all
     * (collective). */
    void
    write_pvd() const;

    /** Add @p row to the history; an OutputError on any rank stops all. */
    void
    add_history_row(const HistoryRow &row);

    /** The checkpoint of everything the loop needs to go on: the clock,
     * the projectile, the history, the snapshot list, the loop's own
     * records and the model's state (this rank's part). */
    std::string
    checkpoint_state(const Schedule &schedule,
                     const double force,
                     const RunResult &result,
                     const std::string &stop_reason) const;

    /** Read what checkpoint_state() wrote into the same places. */
    void
    load_checkpoint(Checkpoint::Reader &in,
                    Schedule &schedule,
                    double &force,
                    RunResult &result,
                    std::string &stop_reason);

    const Parameters::Shared &parameters;
    std::unique_ptr<ImpactModel> model;
    RunHooks hooks;
    CheckpointOptions checkpoints;
    /** The last checkpoint written or read (generation 0: none). */
    Checkpoint::Info checkpoint_info;
    /** Simulated time of the next periodic checkpoint [s]. */
    double next_checkpoint = 0.;
    MPI_Comm communicator;
    bool is_root;
    ConditionalOStream out;
    Projectile projectile;
    std::unique_ptr<History> history;
    std::vector<std::pair<double, std::string>> snapshots;
    double initial_energy = 0.;
  };
} // namespace YarnImpact

#endif
