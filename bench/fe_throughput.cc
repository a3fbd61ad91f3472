/**
 * FE benchmark (not a test): throughput of the FE force loop with the
 * Charmetant law, in cell-steps per second per core, on the paper's mesh
 * refined along the axis, and the wall time of the default case.
 *
 * Usage: bench_fe_throughput [n_steps] [prm file of the default case, or -
 * to skip it] [frames or -] [sudden or progressive]
 *
 * With `frames` the model gives every Gauss point the fibre frame of e_x
 * (FE::Parameters::fibre_direction): the same numbers through the force
 * loop's path for fibres at any angle, to measure what that path costs
 * against the straight one. The last argument sets `Yarn/Failure model`
 * (the default law without it): the progressive law's step evaluates the
 * fibre damage before the forces, the sudden law's does not, so a
 * comparison with commits whose default was sudden names it.
 */
#include <yarn_impact/analysis/run_summary.h>
#include <yarn_impact/app/application.h>
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/core/time_stepping.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

using namespace YarnImpact;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm comm = MPI_COMM_WORLD;
  const bool is_root  = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  const unsigned int n_steps = argc > 1 ? std::stoi(argv[1]) : 400;
  const bool frames          = argc > 3 && std::string(argv[3]) == "frames";
  const std::string failure_model = argc > 4 ? argv[4] : "";
  std::ostream &out               = std::cout;

  if (is_root)
    out << "FE force-loop throughput, Charmetant law, "
        << (failure_model.empty() ? "default" : failure_model)
        << " failure model, " << n_ranks << " rank(s)"
        << (frames ? ", fibre frames (path for any M)" : "") << "\n"
        << std::setw(10) << "cells" << std::setw(12) << "steps" << std::setw(14)
        << "wall [s]" << std::setw(26) << "cell-steps/s per core"
        << std::setw(26) << "cell-steps per CPU s\n";
  // One "key: value" line a mesh after the table, for the registry of
  // runs (scripts/registry.py, extractor summary).
  std::ostringstream values;
  for (const unsigned int axial : {100u, 400u, 1600u})
    {
      dealii::ParameterHandler prm;
      AllParameters::declare_parameters(prm);
      std::ostringstream input;
      input << "set Symmetry = none\nsubsection FE\n set Cells along the axis"
            << " = " << axial << "\nend\n";
      if (!failure_model.empty())
        input << "subsection Yarn\n set Failure model = " << failure_model
              << "\nend\n";
      prm.parse_input_from_string(input.str());
      AllParameters p;
      p.parse_parameters(prm);

      std::unique_ptr<ImpactModel> model;
      if (frames)
        {
          FE::Parameters fe;
          fe.parse_parameters(prm);
          fe.fibre_direction = [](const double *, double *M) {
            M[0] = 1.;
            M[1] = M[2] = 0.;
          };
          model = FE::create_model(p.shared, fe, comm);
        }
      else
        model = create_model("fe", p, comm);
      Projectile projectile(p.shared.projectile,
                            p.shared.yarn.thickness_semi_axis);
      std::ostringstream sink;
      model->setup(projectile, sink);
      projectile.place_on(model->yarn_top());
      const double dt = 0.8 * model->stable_time_step();
      double f        = model->compute_forces(projectile, dt);
      // Run into the impact until the longitudinal wave has crossed the
      // yarn, so that every cell is deformed (undeformed cells take cheap
      // branches of the law).
      const unsigned int n_warm =
        static_cast<unsigned int>(1.2 * 0.5 * p.shared.yarn.length / 7950. /
                                  dt) +
        1;
      const auto step = [&]() { f = advance(*model, projectile, f, dt); };
      for (unsigned int s = 0; s < n_warm; ++s)
        step();
      MPI_Barrier(comm);
      dealii::Timer timer;
      for (unsigned int s = 0; s < n_steps; ++s)
        step();
      MPI_Barrier(comm);
      const double wall = timer.wall_time();
      // The process's CPU time as well: on a shared machine the wall time
      // also counts the time other jobs held the core.
      const double cpu = timer.cpu_time();
      const double rate =
        double(model->n_elements()) * n_steps / wall / n_ranks;
      const double cpu_rate = double(model->n_elements()) * n_steps / cpu;
      if (is_root)
        out << std::setw(10) << model->n_elements() << std::setw(12) << n_steps
            << std::setw(14) << std::setprecision(4) << wall << std::setw(24)
            << std::setprecision(4) << rate / 1e6 << " M" << std::setw(24)
            << std::setprecision(4) << cpu_rate / 1e6 << " M" << std::endl;
      values << std::setprecision(4) << model->n_elements() << " cells, "
             << n_ranks << " rank(s), M cell-steps/s per core: " << rate / 1e6
             << "\n"
             << model->n_elements() << " cells, " << n_ranks
             << " rank(s), M cell-steps per CPU s: " << cpu_rate / 1e6 << "\n";
    }
  if (is_root)
    out << values.str();

  if (argc > 2 && std::string(argv[2]) != "-")
    {
      dealii::ParameterHandler prm;
      AllParameters::declare_parameters(prm);
      AllParameters p           = read_parameters(argv[2], prm);
      p.shared.output.verbosity = Parameters::Verbosity::quiet;
      p.shared.output.directory = "bench-results";
      p.shared.output.overwrite = true; // the benchmark's own scratch folder
      std::filesystem::create_directories(p.shared.output.directory);
      std::ostringstream sink;
      dealii::Timer timer;
      ImpactSimulation simulation(p.shared,
                                  create_model("fe", p, comm),
                                  comm,
                                  sink,
                                  Analysis::run_hooks(p.shared, p.analysis));
      const auto summary = simulation.run();
      if (is_root)
        out << "default case " << argv[2] << ": " << summary.n_steps
            << " steps to " << summary.end_time * 1e6 << " us, wall time "
            << timer.wall_time() << " s (with output)\n"
            << "default case wall time [s]: " << timer.wall_time() << "\n";
    }
}
