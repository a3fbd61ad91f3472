// Model-level checks of the DEM yarn: a truss breaks exactly when its strain
// passes the failure strain; the full, half and quarter models give the same
// history (reported quantities are those of the whole yarn).
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/dem/dem_model.h>

#include <deal.II/base/mpi.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

using namespace YarnImpact;

namespace
{
  const char *
  verdict(const bool ok)
  {
    return ok ? "PASSED" : "FAILED";
  }

  void
  check_truss_break()
  {
    Parameters::Shared p;
    p.general.model              = Parameters::ModelType::dem;
    p.general.symmetry           = Parameters::Symmetry::half;
    p.yarn.length                = 10e-3;
    p.yarn.n_fibres              = 1;
    p.yarn.thickness_semi_axis   = 6e-6;
    p.yarn.width_semi_axis       = 6e-6;
    p.yarn.failure_strain        = 0.01;
    p.projectile.initial_velocity = 400.;
    p.projectile.motion = Parameters::ProjectileMotion::prescribed_velocity;
    DEM::Parameters dem;
    auto            model = DEM::create_model(p, dem, MPI_COMM_WORLD);
    Projectile      projectile(p.projectile, p.yarn.thickness_semi_axis);
    std::ostringstream log;
    model->setup(projectile, log);
    const double dt    = 0.8 * model->stable_time_step();
    double       force = model->compute_forces(projectile, dt);
    double       previous = 0., before_previous = 0.;
    bool         below_until_break = true;
    for (unsigned int step = 1; step < 4000; ++step)
      {
        model->kick(0.5 * dt);
        projectile.kick(0.5 * dt, force);
        model->drift(dt);
        projectile.drift(dt);
        force = model->compute_forces(projectile, dt);
        model->kick(0.5 * dt);
        projectile.kick(0.5 * dt, force);
        const auto o = model->observables();
        if (o.n_failed > 0)
          {
            // The step before held every truss at or below the limit, and
            // the strain was rising so that it passes the limit now.
            const double predicted = previous + (previous - before_previous);
            std::cout << std::fixed << std::setprecision(4)
                      << "truss break: first broken truss after " << step
                      << " steps, largest strain of the previous step "
                      << 100. * previous << " % <= limit 1.0000 % "
                      << verdict(below_until_break && previous <= 0.01)
                      << ", extrapolated to this step beyond the limit "
                      << verdict(predicted > 0.01) << ", broken trusses "
                      << o.n_failed << '\n';
            return;
          }
        below_until_break = below_until_break && o.max_strain <= 0.01;
        before_previous   = previous;
        previous          = o.max_strain;
      }
    std::cout << "truss break: no truss broke FAILED\n";
  }

  std::vector<HistoryRow>
  run(const Parameters::Symmetry symmetry, const std::string &directory)
  {
    Parameters::Shared p;
    p.general.model            = Parameters::ModelType::dem;
    p.general.symmetry         = symmetry;
    p.yarn.length              = 2e-3;
    p.yarn.n_fibres            = 13;
    p.yarn.thickness_semi_axis = 12e-6;
    p.yarn.width_semi_axis     = 30e-6;
    p.projectile.mass          = 0.3e-6;
    p.projectile.diameter      = 1e-3;
    p.time.end_time            = 0.5e-6;
    p.output.directory         = directory;
    p.output.snapshot_interval = 0.;
    p.output.history_interval  = 0.05e-6;
    p.output.verbosity         = Parameters::Verbosity::test;
    std::filesystem::create_directories(directory);
    DEM::Parameters dem;
    dem.layout     = DEM::FibreLayout::file;
    dem.fibre_file = "fibres.txt";
    std::ostringstream sink;
    ImpactSimulation   simulation(
      p, DEM::create_model(p, dem, MPI_COMM_WORLD), MPI_COMM_WORLD, sink);
    simulation.run();
    return simulation.history();
  }

  void
  check_symmetry()
  {
    // 13 fibres, symmetric about y = 0 and z = 0 (hexagonal, spacing d).
    {
      std::ofstream f("fibres.txt");
      const double  d = 12e-6, h = 0.5 * std::sqrt(3.) * d;
      f << std::setprecision(17) << "# y z [m]\n";
      for (const int i : {-2, -1, 0, 1, 2})
        f << 0. << ' ' << i * d << '\n';
      for (const double y : {-h, h})
        for (const double z : {-1.5, -0.5, 0.5, 1.5})
          f << y << ' ' << z * d << '\n';
    }
    const auto full    = run(Parameters::Symmetry::none, "run_none");
    const auto half    = run(Parameters::Symmetry::half, "run_half");
    const auto quarter = run(Parameters::Symmetry::quarter, "run_quarter");
    const double E0    = full[0].projectile_kinetic_energy;
    for (const auto *other : {&half, &quarter})
      {
        double dv = 0., dE = 0., df = 0.;
        for (unsigned int r = 0; r < std::min(full.size(), other->size()); ++r)
          {
            const auto &a = full[r].model, &b = (*other)[r].model;
            dv = std::max(dv,
                          std::abs(full[r].projectile_velocity -
                                   (*other)[r].projectile_velocity));
            for (const double e :
                 {a.kinetic_energy - b.kinetic_energy,
                  a.elastic_energy - b.elastic_energy,
                  a.contact_energy - b.contact_energy,
                  a.dissipated_energy - b.dissipated_energy})
              dE = std::max(dE, std::abs(e) / E0);
            df = std::max(df, std::abs(full[r].contact_force -
                                       (*other)[r].contact_force));
          }
        std::cout << (other == &half ? "half" : "quarter")
                  << " symmetry against the full model: " << full.size()
                  << " and " << other->size() << " history rows, velocity "
                  << verdict(dv < 1e-6) << ", energies "
                  << verdict(dE < 1e-6) << ", contact force "
                  << verdict(df < 1e-6) << '\n';
      }
    std::cout << std::fixed << std::setprecision(4)
              << "full model: final velocity "
              << full.back().projectile_velocity << " m/s, yarn energy "
              << (full.back().model.kinetic_energy +
                  full.back().model.elastic_energy) *
                   1e3
              << " mJ\n";
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check_truss_break();
  check_symmetry();
  return 0;
}
