// The yarn mesh: 12 cells per section and 1200 cells by default; the section
// area converges to the ellipse's under refinement (plain polygon) and is
// exact with area preservation; the FE yarn's mass against rho * pi a b L
// for every symmetry.

#include <yarn_impact/app/application.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/core/yarn_section.h>
#include <yarn_impact/fe/yarn_mesh.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <cmath>
#include <cstdio>
#include <sstream>

using namespace YarnImpact;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double a_y = 0.0575e-3, a_z = 0.267e-3;
  const double ellipse = M_PI * a_y * a_z;

  std::printf(
    "section area / ellipse area (boundary vertices on the ellipse)\n");
  double previous_error = 1.;
  for (unsigned int r = 0; r < 5; ++r)
    {
      dealii::Triangulation<2> section;
      create_yarn_section(section, a_y, a_z, r, false, false);
      const double ratio = dealii::GridTools::volume(section) / ellipse;
      const double error = 1. - ratio;
      std::printf(
        "  refinements %u: %5u cells, ratio %.6f, error ratio %.3f %s\n",
        r,
        section.n_active_cells(),
        ratio,
        error / previous_error,
        r == 0 || error < 0.3 * previous_error ? "converging"
                                               : "NOT CONVERGING");
      previous_error = error;
    }
  for (const bool half : {false, true})
    {
      dealii::Triangulation<2> section;
      create_yarn_section(section, a_y, a_z, 0, half, true);
      std::printf("area-preserving %s section: ratio %.12f\n",
                  half ? "half" : "full",
                  dealii::GridTools::volume(section) / ellipse *
                    (half ? 2. : 1.));
    }

  std::printf("FE yarn (default parameters): cells and mass\n");
  for (const std::string symmetry : {"none", "half", "quarter"})
    for (const unsigned int refinements : {0u, 2u})
      {
        dealii::ParameterHandler prm;
        AllParameters::declare_parameters(prm);
        std::ostringstream input;
        input << "set Symmetry = " << symmetry
              << "\nsubsection FE\n set Section refinements = " << refinements
              << "\n set Preserve section area = false\nend\n";
        prm.parse_input_from_string(input.str());
        AllParameters p;
        p.parse_parameters(prm);
        auto model = create_model("fe", p, MPI_COMM_WORLD);
        Projectile projectile(p.shared.projectile, a_y);
        std::ostringstream sink;
        model->setup(projectile, sink);
        const double expected = 1267. * ellipse * 0.0254;
        std::printf("  symmetry %-8s section refinements %u: %6lu cells, mass "
                    "%.5f mg, ellipse %.5f mg, ratio %.5f\n",
                    symmetry.c_str(),
                    refinements,
                    model->n_elements(),
                    model->mass() * 1e6,
                    expected * 1e6,
                    model->mass() / expected);
      }
}
