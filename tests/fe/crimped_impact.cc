// The transverse impact of a crimped yarn approaches the straight yarn's
// as the crimp amplitude goes to 0 (doc/fe-model.md section 8): the
// paper's case (25.4 mm yarn, 100 cells along, the paper's section,
// Charmetant law, free 9.91 mg projectile at 120 m/s, friction 0.2) for
// 5 us, half model, straight and crimped with the wavelength 2.54 mm (10
// cells each, a crest under the projectile and at the clamps) and the
// amplitudes 40, 20, 10 and 5 um (crimps 0.24, 0.061, 0.015 and
// 0.0038 %). The projectile's velocity at 5 us must differ from the
// straight yarn's by less the smaller the amplitude, and by less than
// 0.03 m/s per um of amplitude (a tolerance that shrinks with it). The
// largest fibre strain (a maximum over Gauss points) is printed, not
// checked: it differs by 0.04 % (strain) from the straight yarn's at both
// 10 and 5 um, and does not shrink with the amplitude on this mesh. The
// crimped yarn modelled whole (symmetry none) must give the half model's
// velocity to 1e-6 relative at A = 40 um: the crimp is mirror-symmetric
// about the impact point, and its stations and clamps do not depend on
// the modelled part.

#include <yarn_impact/app/application.h>
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

using namespace YarnImpact;

namespace
{
  /** The last history row of the paper's case with the crimp amplitude
   * @p A [m] and symmetry @p symmetry, run in @p directory. */
  HistoryRow
  run(const double A, const std::string &symmetry, const std::string &directory)
  {
    std::ostringstream text;
    text << "set Model = fe\nset Symmetry = " << symmetry
         << "\nsubsection Time\n set End time = 5e-6\nend\n"
         << "subsection FE\n subsection Crimp\n  set Amplitude = " << A
         << "\n  set Wavelength = 2.54e-3\n end\nend\n"
         << "subsection Output\n set Directory = " << directory
         << "\n set Overwrite = true\n set Snapshot interval = 0"
         << "\n set History interval = 0.1e-6\n set Verbosity = quiet\nend\n";
    dealii::ParameterHandler prm;
    AllParameters::declare_parameters(prm);
    prm.parse_input_from_string(text.str());
    AllParameters p;
    p.parse_parameters(prm);
    FE::Parameters fe;
    fe.parse_parameters(prm);
    std::filesystem::create_directories(directory);
    std::ostringstream sink;
    ImpactSimulation simulation(p.shared,
                                FE::create_model(p.shared, fe, MPI_COMM_WORLD),
                                MPI_COMM_WORLD,
                                sink);
    simulation.run();
    return simulation.history().back();
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const HistoryRow straight = run(0., "half", "run_straight");
  std::printf("straight:   v(5 us) = %.3f m/s, largest strain %.4f %%\n",
              straight.projectile_velocity,
              straight.model.max_strain * 100.);
  const double amplitudes[] = {40e-6, 20e-6, 10e-6, 5e-6};
  std::vector<double> difference;
  bool within = true;
  for (const double A : amplitudes)
    {
      const HistoryRow r =
        run(A, "half", "run_" + std::to_string(int(A * 1e6 + 0.5)));
      const double dv = r.projectile_velocity - straight.projectile_velocity;
      const double de = r.model.max_strain - straight.model.max_strain;
      difference.push_back(std::abs(dv));
      within = within && std::abs(dv) < 0.03 * A * 1e6;
      std::printf("A = %2.0f um: v(5 us) = %.3f m/s (%+.3f), largest strain "
                  "%.4f %% (%+.4f)\n",
                  A * 1e6,
                  r.projectile_velocity,
                  dv,
                  r.model.max_strain * 100.,
                  de * 100.);
    }
  bool shrinks = true;
  for (unsigned int k = 1; k < difference.size(); ++k)
    shrinks = shrinks && difference[k] < difference[k - 1];
  std::printf("The velocity difference shrinks with the amplitude: %s; "
              "below 0.03 m/s per um of amplitude: %s\n",
              shrinks ? "OK" : "WRONG",
              within ? "OK" : "WRONG");
  const HistoryRow half  = run(40e-6, "half", "run_half");
  const HistoryRow whole = run(40e-6, "none", "run_whole");
  std::printf("A = 40 um, whole yarn against half: the same v(5 us) to "
              "1e-6: %s\n",
              std::abs(whole.projectile_velocity / half.projectile_velocity -
                       1.) < 1e-6
                ? "OK"
                : "WRONG");
}
