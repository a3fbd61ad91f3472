// Model-level checks of the DEM yarn: a truss breaks exactly when its strain
// passes the failure strain; the full, half and quarter models give the same
// history (reported quantities are those of the whole yarn).
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/core/time_stepping.h>
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
    // Two identical fibres hit at 400 m/s (Smith strain 1.2 %), one with
    // failure at 1 % and one without: the first must lose a truss at the
    // very step at which the second's largest strain passes 1 %.
    Parameters::Shared p;
    p.general.symmetry            = Parameters::Symmetry::half;
    p.yarn.length                 = 10e-3;
    p.yarn.n_fibres               = 1;
    p.yarn.thickness_semi_axis    = 6e-6;
    p.yarn.width_semi_axis        = 6e-6;
    p.yarn.failure_strain         = 0.01;
    p.projectile.initial_velocity = 400.;
    p.projectile.motion  = Parameters::ProjectileMotion::prescribed_velocity;
    Parameters::Shared q = p;
    q.yarn.failure       = false;
    DEM::Parameters dem;
    auto breaking = DEM::create_model(p, dem, MPI_COMM_WORLD);
    auto intact   = DEM::create_model(q, dem, MPI_COMM_WORLD);
    // One projectile per model, so that each model's step is the core's
    // advance(): the velocity is prescribed, so both projectiles move
    // alike and each model sees the one projectile it would share.
    Projectile projectile_breaking(p.projectile, p.yarn.thickness_semi_axis);
    Projectile projectile_intact(q.projectile, q.yarn.thickness_semi_axis);
    std::ostringstream log;
    breaking->setup(projectile_breaking, log);
    intact->setup(projectile_intact, log);
    const double dt       = 0.8 * breaking->stable_time_step();
    double force_breaking = breaking->compute_forces(projectile_breaking, dt);
    double force_intact   = intact->compute_forces(projectile_intact, dt);
    unsigned int first_break = 0, first_passed = 0;
    double strain_before = 0., strain_at = 0.;
    for (unsigned int step = 1; step < 4000 && first_break == 0; ++step)
      {
        force_breaking =
          advance(*breaking, projectile_breaking, force_breaking, dt);
        force_intact   = advance(*intact, projectile_intact, force_intact, dt);
        const double e = intact->observables().max_strain;
        if (first_passed == 0 && e > 0.01)
          {
            first_passed = step;
            strain_at    = e;
          }
        if (first_passed == 0)
          strain_before = e;
        if (breaking->observables().n_failed > 0)
          first_break = step;
      }
    std::cout << std::fixed << std::setprecision(4)
              << "truss break: first broken truss at step " << first_break
              << ", the intact fibre's largest strain passes 1 % at step "
              << first_passed << " (" << 100. * strain_before << " % -> "
              << 100. * strain_at << " %) "
              << verdict(first_break > 0 && first_break == first_passed)
              << '\n';
  }

  std::vector<HistoryRow>
  run(const Parameters::Symmetry symmetry,
      const std::string &directory,
      const bool breaking = false)
  {
    Parameters::Shared p;
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
    if (breaking)
      {
        // A fast, point-like nose and a low failure strain: the fibres
        // break at the impact point and their loose ends recoil along
        // x = 0, where they meet the mirror images of the other fibres'
        // ends.
        p.projectile.initial_velocity = 500.;
        p.projectile.motion = Parameters::ProjectileMotion::prescribed_velocity;
        p.projectile.diameter     = 0.05e-3;
        p.yarn.failure_strain     = 0.01;
        p.time.end_time           = 1e-6;
        p.output.history_interval = 0.1e-6;
      }
    std::filesystem::create_directories(directory);
    DEM::Parameters dem;
    dem.layout     = DEM::FibreLayout::file;
    dem.fibre_file = "fibres.txt";
    std::ostringstream sink;
    ImpactSimulation simulation(p,
                                DEM::create_model(p, dem, MPI_COMM_WORLD),
                                MPI_COMM_WORLD,
                                sink);
    simulation.run();
    return simulation.history();
  }

  void
  compare(const std::vector<HistoryRow> &full,
          const std::vector<HistoryRow> &half,
          const std::vector<HistoryRow> &quarter,
          const std::string &label);

  void
  check_symmetry()
  {
    // 13 fibres, symmetric about y = 0 and z = 0 (hexagonal, spacing d).
    {
      std::ofstream f("fibres.txt");
      const double d = 12e-6, h = 0.5 * std::sqrt(3.) * d;
      f << std::setprecision(17) << "# y z [m]\n";
      for (const int i : {-2, -1, 0, 1, 2})
        f << 0. << ' ' << i * d << '\n';
      for (const double y : {-h, h})
        for (const double z : {-1.5, -0.5, 0.5, 1.5})
          f << y << ' ' << z * d << '\n';
    }
    compare(run(Parameters::Symmetry::none, "run_none"),
            run(Parameters::Symmetry::half, "run_half"),
            run(Parameters::Symmetry::quarter, "run_quarter"),
            "");
    // With broken fibres: the loose ends near x = 0 touch the mirror images
    // of other spheres (mirror pairs in x = 0, and in x = 0 and z = 0).
    compare(run(Parameters::Symmetry::none, "run_none_break", true),
            run(Parameters::Symmetry::half, "run_half_break", true),
            run(Parameters::Symmetry::quarter, "run_quarter_break", true),
            " (fibres broken at the impact point)");
  }

  void
  compare(const std::vector<HistoryRow> &full,
          const std::vector<HistoryRow> &half,
          const std::vector<HistoryRow> &quarter,
          const std::string &label)
  {
    const double E0 = full[0].projectile_kinetic_energy;
    for (const auto *other : {&half, &quarter})
      {
        double dv = 0., dE = 0., df = 0.;
        for (unsigned int r = 0; r < std::min(full.size(), other->size()); ++r)
          {
            const auto &a = full[r].model, &b = (*other)[r].model;
            dv = std::max(dv,
                          std::abs(full[r].projectile_velocity -
                                   (*other)[r].projectile_velocity));
            for (const double e : {a.kinetic_energy - b.kinetic_energy,
                                   a.elastic_energy - b.elastic_energy,
                                   a.contact_energy - b.contact_energy,
                                   a.dissipated_energy - b.dissipated_energy})
              dE = std::max(dE, std::abs(e) / E0);
            df = std::max(df,
                          std::abs(full[r].contact_force -
                                   (*other)[r].contact_force));
          }
        std::cout << (other == &half ? "half" : "quarter")
                  << " symmetry against the full model" << label << ": "
                  << full.size() << " and " << other->size()
                  << " history rows, velocity " << verdict(dv < 1e-6)
                  << ", energies " << verdict(dE < 1e-6) << ", contact force "
                  << verdict(df < 1e-6) << '\n';
      }
    if (!label.empty())
      {
        std::cout << "broken trusses at the end: "
                  << verdict(full.back().model.n_failed > 0) << '\n';
        return;
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
