/**
 * Fabric benchmark (not a test): a `Model = fabric` case run end to end
 * with `Fabric/Step timing` on, and its size, its speed and its step by
 * part (doc/fabric.md section 9).
 *
 * Usage: bench_fabric_throughput PRM [END_TIME_US or -] [OUTPUT_DIRECTORY]
 *
 * PRM is run as it is, but for `Fabric/Step timing = true`, `Output/
 * Verbosity = quiet`, `Output/Overwrite = true`, the end time END_TIME_US
 * [us] if given (a shorter run; the wall time to the PRM's own end time is
 * then extrapolated from the time per step, stated as such) and the output
 * directory (bench-results/fabric by default). It prints, as `key: value`
 * lines that scripts/fabric_scaling.py reads: cells, dofs, yarn-contact
 * surface nodes, ranks, steps, the stable step and the step used, the
 * simulated time, the wall time, cell-steps per second (per core, of the
 * wall time), the peak resident memory per rank (largest and mean over the
 * ranks) and the step by part (StepTimer's table).
 */
#include <yarn_impact/app/application.h>
#include <yarn_impact/app/model_factory.h>
#include <yarn_impact/core/impact_simulation.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <regex>
#include <sstream>
#include <sys/resource.h>

using namespace YarnImpact;

namespace
{
  /** The first number after @p label in @p text, or -1. */
  double
  number_after(const std::string &text, const std::string &label)
  {
    const std::regex pattern(label + R"(\s*([0-9.eE+-]+))");
    std::smatch m;
    if (std::regex_search(text, m, pattern))
      return std::stod(m[1]);
    return -1.;
  }

  /** Column @p k (0: wall s, 3: CPU s) of the line of part @p name in
   * StepTimer's table @p table, or -1. */
  double
  part_seconds(const std::string &table,
               const std::string &name,
               const unsigned int k)
  {
    std::istringstream lines(table);
    for (std::string line; std::getline(lines, line);)
      if (line.rfind("  " + name + " |", 0) == 0)
        {
          std::istringstream fields(line.substr(name.size() + 4));
          std::string field;
          for (unsigned int i = 0; std::getline(fields, field, '|'); ++i)
            if (i == k)
              return std::stod(field);
        }
    return -1.;
  }
} // namespace


int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm comm = MPI_COMM_WORLD;
  const bool is_root  = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  if (argc < 2)
    {
      if (is_root)
        std::cerr << "usage: bench_fabric_throughput PRM [END_TIME_US or -] "
                     "[OUTPUT_DIRECTORY]\n";
      return 1;
    }
  const std::string prm_file = argv[1];
  const bool shortened       = argc > 2 && std::string(argv[2]) != "-";
  const std::string directory =
    argc > 3 ? argv[3] : std::string("bench-results/fabric");

  std::ifstream in(prm_file);
  if (!in)
    {
      if (is_root)
        std::cerr << "bench_fabric_throughput: cannot read " << prm_file
                  << "\n";
      return 1;
    }
  std::stringstream text;
  text << in.rdbuf();

  // The PRM's own end time, for the extrapolation.
  AllParameters p;
  double own_end_time;
  {
    dealii::ParameterHandler prm;
    AllParameters::declare_parameters(prm);
    prm.parse_input_from_string(text.str());
    p.parse_parameters(prm);
    own_end_time = p.shared.time.end_time;
  }
  // The benchmark's settings after the file's: the last `set` wins.
  text << "\nsubsection Fabric\n  set Step timing = true\nend\n"
       << "subsection Output\n  set Verbosity = quiet\n  set Overwrite = true\n"
       << "  set Directory = " << directory << "\nend\n";
  if (shortened)
    text << "subsection Time\n  set End time = " << std::stod(argv[2]) * 1e-6
         << "\nend\n";
  {
    dealii::ParameterHandler prm;
    AllParameters::declare_parameters(prm);
    prm.parse_input_from_string(text.str());
    p = AllParameters();
    p.parse_parameters(prm);
  }
  if (p.model != "fabric")
    {
      if (is_root)
        std::cerr << "bench_fabric_throughput: " << prm_file
                  << " must set Model = fabric\n";
      return 1;
    }
  std::filesystem::create_directories(directory);

  std::ostringstream report;
  ImpactSimulation simulation(p.shared,
                              create_model("fabric", p, comm),
                              comm,
                              report,
                              RunHooks());
  const RunResult result = simulation.run();

  // Peak resident memory of each rank [MB].
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  const double rss_mb  = usage.ru_maxrss / 1024.;
  const double rss_max = dealii::Utilities::MPI::max(rss_mb, comm);
  const double rss_sum = dealii::Utilities::MPI::sum(rss_mb, comm);
  // The process's CPU time: on a shared machine the wall time also counts
  // the time other jobs held the core.
  const double cpu = usage.ru_utime.tv_sec + 1e-6 * usage.ru_utime.tv_usec +
                     usage.ru_stime.tv_sec + 1e-6 * usage.ru_stime.tv_usec;
  const double cpu_max = dealii::Utilities::MPI::max(cpu, comm);

  if (is_root)
    {
      const std::string r   = report.str();
      const double cells    = number_after(r, R"(\[fe\] mesh:)");
      const double dofs     = number_after(r, R"(cells \([^)]*\),)");
      const double nodes    = number_after(r, R"(\[fabric\] yarn contact:)");
      const double stable   = number_after(r, R"(stable time step)");
      const double used     = number_after(r, R"(ns, used)");
      const double steps    = result.n_steps;
      const double wall     = result.wall_time;
      const std::string &rm = result.model_remarks;
      // The loop's time: the timed sum of the largest rank (set-up and
      // the history's file writes are outside it).
      const double loop     = part_seconds(rm, "timed sum (largest rank)", 0);
      const double loop_cpu = part_seconds(rm, "timed sum (largest rank)", 3);
      std::cout << std::setprecision(6) << "case: " << prm_file << "\n"
                << "ranks: " << n_ranks << "\n"
                << "cells: " << cells << "\n"
                << "dofs: " << dofs << "\n"
                << "contact surface nodes: " << nodes << "\n"
                << "steps: " << steps << "\n"
                << "stable step [ns]: " << stable << "\n"
                << "step used at the start [ns]: " << used << "\n"
                << "mean step [ns]: " << result.end_time / steps * 1e9 << "\n"
                << "simulated time [us]: " << result.end_time * 1e6 << "\n"
                << "wall time [s]: " << wall << "\n"
                << "timed loop [s]: " << loop << "\n"
                << "set-up and the rest [s]: " << wall - loop << "\n"
                << "timed loop, CPU [s]: " << loop_cpu << "\n"
                << "CPU time per rank, largest [s]: " << cpu_max << "\n"
                << "cell-steps per second per core: "
                << cells * steps / wall / n_ranks << "\n"
                << "cell-steps per second per core, loop only: "
                << cells * steps / loop / n_ranks << "\n"
                << "cell-steps per CPU second per rank, loop only: "
                << cells * steps / loop_cpu / n_ranks << "\n"
                << "peak memory per rank, largest [MB]: " << rss_max << "\n"
                << "peak memory per rank, mean [MB]: " << rss_sum / n_ranks
                << "\n"
                << "projectile velocity at the end [m/s]: "
                << result.final_velocity << "\n";
      if (shortened)
        {
          // Steps to the PRM's end time at the mean step so far (the step
          // shrinks a little as cells compact: an estimate); the loop's
          // time but the snapshots' per step, the snapshots' per
          // snapshot.
          const double steps_to_end = own_end_time / (result.end_time / steps);
          const double output       = part_seconds(rm, "output", 0);
          const double output_cpu   = part_seconds(rm, "output", 3);
          const double interval     = p.shared.output.snapshot_interval;
          const auto snapshots      = [interval](const double t) {
            // One at the start, one per interval and one at the end.
            if (!(interval > 0.))
              return 0.;
            const double n = std::floor(t / interval * (1. + 1e-12)) + 1.;
            return n + (t - (n - 1.) * interval > 1e-9 * t ? 1. : 0.);
          };
          const double per_snapshot =
            output / std::max(1., snapshots(result.end_time));
          std::cout << "extrapolated to " << own_end_time * 1e6
                    << " us (the loop's time per step so far, the snapshots' "
                       "per snapshot): "
                    << steps_to_end << " steps, wall time "
                    << (wall - loop) + (loop - output) / steps * steps_to_end +
                         per_snapshot * snapshots(own_end_time)
                    << " s, CPU time of the largest rank "
                    << (cpu_max - loop_cpu) +
                         (loop_cpu - output_cpu) / steps * steps_to_end +
                         output_cpu / std::max(1., snapshots(result.end_time)) *
                           snapshots(own_end_time)
                    << " s\n";
        }
      std::cout << rm << std::endl;
    }
}
