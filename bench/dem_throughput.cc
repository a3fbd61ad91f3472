// Throughput benchmark of the DEM step (not a test): sphere-steps per second
// and peak memory for a yarn of 400 fibres, half symmetry.
//
//   mpirun -np 2 build/bench_dem_throughput [length_m=0.004] [steps=400]
//                                           [skin_m=default] [warm-up_us=0]
//                                           [list_block=default]
//
// The timed steps start at the impact, or after the warm-up time (untimed),
// e.g. 10 us into the impact, where the sections have flattened and spread
// and the transverse wave has crossed half the yarn.
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/core/time_stepping.h>
#include <yarn_impact/dem/dem_model.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

namespace
{
  /** Peak resident memory of this process (VmHWM) [MB]. */
  double
  peak_memory_mb()
  {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
      if (line.rfind("VmHWM:", 0) == 0)
        {
          std::istringstream s(line.substr(6));
          double kb = 0.;
          s >> kb;
          return kb / 1024.;
        }
    return 0.;
  }
} // namespace

int
main(int argc, char **argv)
{
  using namespace YarnImpact;
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm comm = MPI_COMM_WORLD;
  const bool is_root  = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  const double length = (argc > 1 ? std::stod(argv[1]) : 0.004);
  const unsigned int n_steps =
    (argc > 2 ? static_cast<unsigned int>(std::stoul(argv[2])) : 400);

  Parameters::Shared shared;
  shared.general.symmetry = Parameters::Symmetry::half;
  shared.yarn.length      = length;
  shared.projectile.diameter =
    std::min(shared.projectile.diameter, 0.5 * length);
  DEM::Parameters dem;
  // "default" (as the usage line offers) or "-" keeps the default value.
  const auto given = [&](const int i) {
    return argc > i && std::string(argv[i]) != "default" &&
           std::string(argv[i]) != "-";
  };
  if (given(3))
    dem.skin = std::stod(argv[3]);
  const double warm_up = (given(4) ? std::stod(argv[4]) * 1e-6 : 0.);
  if (given(5))
    dem.list_block = static_cast<unsigned int>(std::stoul(argv[5]));

  auto model = DEM::create_model(shared, dem, comm);
  Projectile projectile(shared.projectile, shared.yarn.thickness_semi_axis);
  std::ostringstream setup_log;
  model->setup(projectile, setup_log);
  if (is_root)
    std::cout << setup_log.str();
  const double dt = shared.time.safety_factor * model->stable_time_step();
  double force    = model->compute_forces(projectile, dt);
  const double memory_setup = peak_memory_mb();
  const auto step   = [&]() { force = advance(*model, projectile, force, dt); };
  const auto n_warm = static_cast<unsigned long>(warm_up / dt + 0.5);
  for (unsigned long s = 0; s < n_warm; ++s)
    step();
  const std::string statistics_warm = DEM::statistics(*model);

  MPI_Barrier(comm);
  dealii::Timer timer;
  for (unsigned int s = 0; s < n_steps; ++s)
    step();
  MPI_Barrier(comm);
  const double wall = timer.wall_time();
  (void)memory_setup;
  const double memory_max = dealii::Utilities::MPI::max(peak_memory_mb(), comm);
  const double memory_sum = dealii::Utilities::MPI::sum(peak_memory_mb(), comm);
  const auto obs          = model->observables();
  const std::string statistics_end = DEM::statistics(*model); // collective
  const unsigned long n_whole      = model->n_elements() / shared.yarn.n_fibres;
  const unsigned long modelled =
    shared.yarn.n_fibres * ((n_whole - 1) / 2 + 1); // half symmetry
  if (is_root)
    std::cout << std::setprecision(4) << "length " << length * 1e3
              << " mm, ranks " << dealii::Utilities::MPI::n_mpi_processes(comm)
              << ", modelled spheres " << modelled << ", steps " << n_steps
              << ", dt " << dt * 1e9 << " ns, after " << n_warm * dt * 1e6
              << " us of impact, wall " << wall << " s\n"
              << "throughput " << modelled * double(n_steps) / wall / 1e6
              << " million sphere-steps/s\n"
              << "peak memory " << memory_max << " MB per rank (max), "
              << memory_sum << " MB all ranks\n"
              << "before the timed steps: " << statistics_warm << "\n"
              << "after: " << statistics_end << "\n"
              << "projectile velocity " << projectile.impact_speed()
              << " m/s, max strain " << obs.max_strain
              << "\n"
              // The same as "key: value" lines, for the registry of runs
              // (scripts/registry.py, extractor summary).
              << "modelled spheres: " << modelled << "\n"
              << "timed steps: " << n_steps << "\n"
              << "wall time of the timed steps [s]: " << wall << "\n"
              << "M sphere-steps/s: " << modelled * double(n_steps) / wall / 1e6
              << "\n"
              << "peak memory per rank [MB]: " << memory_max << "\n"
              << "peak memory, all ranks [MB]: " << memory_sum << "\n";
  return 0;
}
