// The straight yarn through the force loop's path for fibres at any angle
// (every Gauss point given the fibre frame of e_x through
// FE::Parameters::fibre_direction, doc/theory.md section 1.8) gives the
// history of the straight path byte for byte: the paper's yarn hit at
// 600 m/s with progressive failure (Charmetant law, SIMD lanes, the
// damage's fibre stretch from the frames) and with the linear law (one
// Gauss point at a time).

#include <yarn_impact/app/application.h>
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

using namespace YarnImpact;

namespace
{
  std::string
  read_file(const std::string &name)
  {
    std::ifstream in(name, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in),
                       std::istreambuf_iterator<char>());
  }

  /** Runs the case @p settings with or without frames in the directory
   * @p directory; returns the history CSV and prints the last row. */
  std::string
  run(const std::string &settings,
      const std::string &directory,
      const bool frames)
  {
    dealii::ParameterHandler prm;
    AllParameters::declare_parameters(prm);
    prm.parse_input_from_string(
      settings + "\nsubsection Output\n set Directory = " + directory +
      "\n set Snapshot interval = 0\n set History interval = 0.1e-6"
      "\n set Verbosity = test\nend\n");
    AllParameters p;
    p.parse_parameters(prm);
    FE::Parameters fe;
    fe.parse_parameters(prm);
    if (frames)
      fe.fibre_direction = [](const double *, double *M) {
        M[0] = 1.;
        M[1] = M[2] = 0.;
      };
    std::filesystem::create_directories(directory);
    std::ostringstream sink;
    ImpactSimulation simulation(p.shared,
                                FE::create_model(p.shared, fe, MPI_COMM_WORLD),
                                MPI_COMM_WORLD,
                                sink);
    simulation.run();
    const HistoryRow &last = simulation.history().back();
    std::printf("  %-9s t = %.2f us, v = %.4f m/s, largest strain %.4f, "
                "damaged cells %lu\n",
                frames ? "frames" : "straight",
                last.time * 1e6,
                last.projectile_velocity,
                last.model.max_strain,
                last.model.n_damaged);
    return read_file(directory + "/history_fe.csv");
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const std::string common =
    "set Model = fe\nset Symmetry = half\n"
    "subsection Projectile\n set Initial velocity = 600\nend\n";
  const std::string cases[2][2] = {
    {"Charmetant law, progressive failure, 3 us",
     common + "subsection Yarn\n set Failure model = progressive\nend\n"
              "subsection Time\n set End time = 3e-6\nend\n"},
    {"linear law, 1 us",
     common + "subsection FE\n set Constitutive law = Linear transversely "
              "isotropic\nend\nsubsection Time\n set End time = 1e-6\nend\n"
              "subsection Yarn\n set Failure model = sudden\nend\n"}};
  for (unsigned int k = 0; k < 2; ++k)
    {
      std::printf("%s\n", cases[k][0].c_str());
      const std::string name     = "run_" + std::to_string(k);
      const std::string straight = run(cases[k][1], name + "_straight", false);
      const std::string frames   = run(cases[k][1], name + "_frames", true);
      std::printf("  history with frames = straight history, byte for byte: "
                  "%s\n",
                  !straight.empty() && straight == frames ? "OK" : "WRONG");
    }
}
