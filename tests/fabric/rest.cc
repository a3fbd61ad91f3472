// A woven patch at rest stays at rest (Model = fabric, doc/fabric.md): the
// 2 x 2 patch of prm/fabric/km2_patch.prm's yarns (768 cells, 0.5 mg,
// crimped yarns 2 mm long along x and z, their fibre frames from
// WovenPatch::fibre_direction, every yarn end clamped), the projectile held
// 1 m above it, 2000 steps at 0.8 of the stable step (18.5 us, 73 axial
// transits of a yarn at 7950 m/s). Checked against zero: the crimped yarns'
// reference state is stress-free whatever their fibre directions, so a
// spurious force of the fibre frames would set the nodes moving (kinetic
// energy below 1e-20 J: speeds of 2e-7 m/s at most, where a force of the
// frames would reach cm/s within a transit; strain energy below 1e-18 J);
// the crossing yarns do not touch at rest (Fabric/Crimp amplitude >
// Yarn/Thickness semi-axis), so their contact stores, dissipates and
// exerts nothing (exactly 0, no touching contact); the projectile's force
// is exactly 0.

#include <yarn_impact/app/application.h>
#include <yarn_impact/core/projectile.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cstdio>
#include <sstream>

using namespace YarnImpact;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const std::string text = "set Model = fabric\nset Symmetry = none\n"
                           "subsection Fabric\n set Warp yarns = 2\n"
                           " set Weft yarns = 2\nend\n"
                           "subsection Projectile\n set Diameter = 1e-3\n"
                           "end\n";
  dealii::ParameterHandler prm;
  AllParameters::declare_parameters(prm);
  prm.parse_input_from_string(text);
  AllParameters all;
  all.parse_parameters(prm);
  auto model = all.models.at("fabric")->create(all.shared, MPI_COMM_WORLD);
  Projectile projectile(all.shared.projectile,
                        all.shared.yarn.thickness_semi_axis);
  std::ostringstream sink;
  model->setup(projectile, sink);
  projectile.place_on(model->yarn_top() + 1.);

  const double dt            = 0.8 * model->stable_time_step();
  const unsigned int n_steps = 2000;
  double largest_force       = 0.;
  double largest_kinetic     = 0.;
  double largest_elastic     = 0.;
  double largest_contact     = 0.;
  double largest_dissipated  = 0.;
  for (unsigned int s = 1; s <= n_steps; ++s)
    {
      model->kick(0.5 * dt);
      model->drift(dt);
      largest_force = std::max(largest_force,
                               std::abs(model->compute_forces(projectile, dt)));
      model->kick(0.5 * dt);
      if (s % 100 == 0)
        {
          const Observables o = model->observables();
          largest_kinetic     = std::max(largest_kinetic, o.kinetic_energy);
          largest_elastic     = std::max(largest_elastic, o.elastic_energy);
          largest_contact =
            std::max(largest_contact, std::abs(o.contact_energy));
          largest_dissipated =
            std::max(largest_dissipated, std::abs(o.dissipated_energy));
        }
    }
  const std::string remarks = model->remarks();
  if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    {
      std::printf("%lu cells, %u steps of %.2f ns\n",
                  model->n_elements(),
                  n_steps,
                  dt * 1e9);
      std::printf("kinetic energy below 1e-20 J: %s\n",
                  largest_kinetic < 1e-20 ? "OK" : "WRONG");
      std::printf("strain energy below 1e-18 J: %s\n",
                  largest_elastic < 1e-18 ? "OK" : "WRONG");
      std::printf("contact energy, dissipation, projectile force exactly 0: "
                  "%s\n",
                  largest_contact == 0. && largest_dissipated == 0. &&
                      largest_force == 0.
                    ? "OK"
                    : "WRONG");
      std::printf("no touching yarn contact: %s\n",
                  remarks.find("yarn contact: 0 touching contacts") == 0
                    ? "OK"
                    : "WRONG");
    }
}
