// What the crimped-yarn tests (crimped_rest, crimped_pull) share: an FE
// model of a crimped yarn (FE/Crimp) built from parameter text, stepped by
// velocity Verlet without the projectile, and its nodes with the
// abscissa of their section, through FE::coupling_view.
#ifndef yarn_impact_tests_fe_crimped_yarn_runs_h
#define yarn_impact_tests_fe_crimped_yarn_runs_h

#include <yarn_impact/app/application.h>
#include <yarn_impact/core/crimped_yarn.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/fe/fe_model.h>
#include <yarn_impact/fe/yarn_mesh.h>

#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <memory>
#include <sstream>
#include <string>

namespace CrimpedYarnRuns
{
  using namespace YarnImpact;

  /** A short yarn of length @p length [m], clamped at both ends, modelled
   * whole, with
   * @p cells along it, crimped by @p amplitude [m] with the wavelength
   * @p wavelength [m] (no projectile contact: the projectile is placed 1 m
   * above it). */
  struct Run
  {
    AllParameters all;
    FE::Parameters fe;
    std::unique_ptr<ImpactModel> model;
    std::unique_ptr<Projectile> projectile;
    /** The crimped yarn (none: the straight yarn). */
    std::unique_ptr<Fabric::CrimpedYarn> crimped;

    Run(const double length,
        const unsigned int cells,
        const double amplitude,
        const double wavelength,
        const std::string &extra = "")
    {
      std::ostringstream text;
      text << "set Model = fe\nset Symmetry = none\nsubsection Yarn\n set "
              "Length = "
           << length << "\n set Failure = false\nend\n"
           << "subsection FE\n set Cells along the axis = " << cells
           << "\n subsection Crimp\n  set Amplitude = " << amplitude
           << "\n  set Wavelength = " << wavelength << "\n end\nend\n"
           << "subsection Projectile\n set Diameter = 0.5e-3\nend\n"
           << extra;
      dealii::ParameterHandler prm;
      AllParameters::declare_parameters(prm);
      prm.parse_input_from_string(text.str());
      all.parse_parameters(prm);
      fe.parse_parameters(prm);
      model = FE::create_model(all.shared, fe, MPI_COMM_WORLD);
      projectile =
        std::make_unique<Projectile>(all.shared.projectile,
                                     all.shared.yarn.thickness_semi_axis);
      std::ostringstream sink;
      model->setup(*projectile, sink);
      projectile->place_on(model->yarn_top() + 1.);
      if (amplitude > 0.)
        crimped = std::make_unique<Fabric::CrimpedYarn>(
          FE::crimped_yarn_geometry(all.shared.yarn,
                                    all.shared.general.symmetry,
                                    cells,
                                    fe.section_refinements,
                                    fe.preserve_section_area,
                                    fe.crimp));
    }

    /** The reference position [m] of the owned node @p node of @p v. */
    static dealii::Point<3>
    reference(const FE::CouplingView &v, const unsigned int node)
    {
      const auto &n = (*v.nodes)[node];
      return dealii::Point<3>((*v.reference_coordinate)[n[0]],
                              (*v.reference_coordinate)[n[1]],
                              (*v.reference_coordinate)[n[2]]);
    }

    /** The abscissa [m] of the section of the owned node @p node of
     * @p v: its reference x on the straight yarn. */
    double
    abscissa(const FE::CouplingView &v, const unsigned int node) const
    {
      const dealii::Point<3> X = reference(v, node);
      return crimped ? crimped->abscissa_of(X) : X[0];
    }

    /** One velocity-Verlet step of @p dt [s] (kick, drift, forces, kick)
     * with the projectile held far away; @p after_drift, if given, may
     * prescribe displacements before the forces. */
    void
    step(const double dt, const std::function<void()> &after_drift = {})
    {
      model->kick(0.5 * dt);
      model->drift(dt);
      if (after_drift)
        after_drift();
      model->compute_forces(*projectile, dt);
      model->kick(0.5 * dt);
    }
  };
} // namespace CrimpedYarnRuns

#endif
