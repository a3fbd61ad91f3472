// The FE model's stable step, step phases, coupling view and
// create_model(); its set-up is in fe_setup.cc.
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/core/reproducible_sum.h>
#include <yarn_impact/fe/constitutive_law.h>
#include <yarn_impact/fe/fe_model.h>
#include <yarn_impact/fe/yarn_mesh.h>

#include <deal.II/base/mpi.h>
#include <deal.II/fe/fe_q.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <type_traits>

#include "yarn_model.h"

namespace YarnImpact
{
  namespace FE
  {
    using namespace dealii;


    template <class Law>
    YarnModel<Law>::YarnModel(const YarnImpact::Parameters::Shared &shared,
                              const Parameters &parameters,
                              const Law &law,
                              const MPI_Comm communicator)
      : shared(shared)
      , parameters(parameters)
      , law(law)
      , communicator(communicator)
      , symmetry(
          YarnImpact::Parameters::symmetry_factor(shared.general.symmetry))
      , tria(communicator)
      , fe(FE_Q<3>(1), 3)
      , dof_handler(tria)
      , contact(parameters.contact)
    {
      if (parameters.crimp.crimped())
        crimped.emplace(crimped_yarn_geometry(shared.yarn,
                                              shared.general.symmetry,
                                              parameters.n_axial_cells,
                                              parameters.section_refinements,
                                              parameters.preserve_section_area,
                                              parameters.crimp));
    }


    template <class Law>
    double
    YarnModel<Law>::stable_time_step() const
    {
      // Per cell, the bound 1/sqrt(sum_k (c_k/h_k)^2) over its three local
      // directions (doc/theory.md section 3.3) with the current sizes h_k:
      // the yarn flattens under the projectile and its cells thin. h_k is
      // the cell's altitude across its pair of faces k, V / |a_i x a_j|
      // with a_k the vectors between opposite face centroids and
      // V = |a_0 . (a_1 x a_2)|: for a brick it is the distance between
      // the faces, and it shrinks when the cell is sheared, which the
      // distance between face centroids does not see (a cell of broken
      // fibres sheared flat by the projectile has long face-centroid
      // distances but a small altitude, and the old bound let it go
      // unstable: doc/validation.md section 4).
      const double c_axial2 = law.axial_modulus() / law.density;
      double rate2          = 0.;
      double min_h2         = std::numeric_limits<double>::max();
      for (const unsigned int c : owned_cells)
        {
          if (cells.failed[c] != CellState::active)
            continue;
          double p[n_nodes][3];
          vertex_positions(c, p);
          Mechanics::Invariants inv;
          inv.compaction        = cells.compaction[c];
          const double c_trans2 = law.transverse_modulus(inv) / law.density;
          double d[3][3]        = {};
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int a = 0; a < n_nodes; ++a)
              for (unsigned int i = 0; i < 3; ++i)
                d[k][i] += ((a >> k) & 1 ? 0.25 : -0.25) * p[a][i];
          double cross[3][3]; // cross[k] = d[k+1] x d[k+2]
          for (unsigned int k = 0; k < 3; ++k)
            {
              const double *u = d[(k + 1) % 3], *v = d[(k + 2) % 3];
              cross[k][0] = u[1] * v[2] - u[2] * v[1];
              cross[k][1] = u[2] * v[0] - u[0] * v[2];
              cross[k][2] = u[0] * v[1] - u[1] * v[0];
            }
          const double volume =
            std::abs(d[0][0] * cross[0][0] + d[0][1] * cross[0][1] +
                     d[0][2] * cross[0][2]);
          double r2 = 0.;
          for (unsigned int k = 0; k < 3; ++k)
            {
              const double area2 = cross[k][0] * cross[k][0] +
                                   cross[k][1] * cross[k][1] +
                                   cross[k][2] * cross[k][2];
              const double h2 = volume * volume / std::max(area2, 1e-300);
              r2 += (k == cell_axis[c] ? c_axial2 : c_trans2) /
                    std::max(h2, 1e-300);
              min_h2 = std::min(min_h2, h2);
            }
          rate2 = std::max(rate2, r2);
        }
      rate2                = Utilities::MPI::max(rate2, communicator);
      const double dt_bulk = 1. / std::sqrt(rate2);
      double dt_waves =
        1. / std::sqrt(1. / (dt_bulk * dt_bulk) +
                       1. / (contact_time_step * contact_time_step));
      // The extra forces' springs act on the same nodes: their squared
      // frequencies add.
      for (const auto &forces : parameters.extra_forces)
        {
          const double dt_extra = forces->stable_time_step();
          dt_waves              = 1. / std::sqrt(1. / (dt_waves * dt_waves) +
                                    1. / (dt_extra * dt_extra));
        }
      // The wave bound above holds for small strain increments. A fast
      // impact crushes the cells under the projectile faster than any wave
      // runs: no node may close more than a quarter of the smallest cell
      // size in one step, so that a cell reaches the erosion threshold
      // (J < 0.2) before it can invert. It binds above a few hundred m/s
      // (doc/fe-model.md).
      min_h2 = Utilities::MPI::min(min_h2, communicator);
      const double closing_speed =
        std::max(projectile_speed, velocity.linfty_norm());
      if (closing_speed > 0. && min_h2 < std::numeric_limits<double>::max())
        return std::min(dt_waves,
                        closing_fraction * std::sqrt(min_h2) / closing_speed);
      return dt_waves;
    }


    template <class Law>
    double
    YarnModel<Law>::compute_forces(const Projectile &projectile,
                                   const double dt)
    {
      displacement.update_ghost_values();
      force = 0.;
      // Owned and ghost cells (setup()): the owned entries of force are
      // complete, with no compress. The loop's energy sums include the
      // ghost cells; the observables sum CellData::energy and
      // CellData::dissipated over the owned cells instead.
      double released = 0.;
      internal_forces(law, cells, displacement, force, failure_law, released);
      projectile_speed = std::abs(projectile.velocity());
      contact.add_forces(projectile,
                         reference_coordinate,
                         displacement,
                         velocity,
                         force,
                         dt);
      add_extra_forces(dt);
      ReproducibleSum reaction(1);
      contact.add_reactions(reaction, 0);
      return symmetry * reaction.sum(communicator)[0];
    }


    template <class Law>
    void
    YarnModel<Law>::report_failed_cells(const bool restored)
    {
      if (parameters.extra_forces.empty())
        return;
      failure_reported.resize(cells.failed.size(), 0);
      std::vector<double> failed;
      for (const unsigned int c : owned_cells)
        if (cells.failed[c] != CellState::active && !failure_reported[c])
          {
            failure_reported[c] = 1;
            for (unsigned int k = 0; k < n_cell_dofs; ++k)
              failed.push_back(
                reference_coordinate[cells.dofs[c * n_cell_dofs + k]]);
          }
      for (const auto &forces : parameters.extra_forces)
        forces->remove_cells(failed, restored);
    }


    template <class Law>
    void
    YarnModel<Law>::add_extra_forces(const double dt)
    {
      report_failed_cells(false);
      for (unsigned int s = 0; s < extra.size(); ++s)
        {
          ExtraNodes &e = extra[s];
          for (unsigned int k = 0; k < e.nodes.size(); ++k)
            for (unsigned int d = 0; d < 3; ++d)
              {
                const unsigned int i = nodes[e.nodes[k]][d];
                e.x[3 * k + d] =
                  reference_coordinate[i] + displacement.local_element(i);
                e.v[3 * k + d] = velocity.local_element(i);
              }
          std::fill(e.f.begin(), e.f.end(), 0.);
          parameters.extra_forces[s]->add_forces(e.x, e.v, dt, e.f);
          for (unsigned int k = 0; k < e.nodes.size(); ++k)
            for (unsigned int d = 0; d < 3; ++d)
              force.local_element(nodes[e.nodes[k]][d]) += e.f[3 * k + d];
        }
    }


    template <class Law>
    void
    YarnModel<Law>::kick(const double dt)
    {
      const unsigned int n  = velocity.locally_owned_size();
      double *const v       = velocity.begin();
      const double *const f = force.begin();
      const double *const m = inverse_mass.begin();
      for (unsigned int i = 0; i < n; ++i)
        v[i] += dt * f[i] * m[i];
    }


    template <class Law>
    void
    YarnModel<Law>::drift(const double dt)
    {
      displacement.zero_out_ghost_values();
      const unsigned int n  = displacement.locally_owned_size();
      double *const u       = displacement.begin();
      const double *const v = velocity.begin();
      for (unsigned int i = 0; i < n; ++i)
        u[i] += dt * v[i];
    }


    template <class Law>
    AxialProperties
    YarnModel<Law>::axial_properties() const
    {
      AxialProperties a;
      a.density = law.density;
      // The discretised section (a polygon inside the ellipse).
      a.area           = total_mass / (law.density * shared.yarn.length);
      a.modulus        = law.axial_modulus();
      const Law copy   = law;
      a.nominal_stress = [copy](const double e) {
        return copy.uniaxial_nominal_stress(e);
      };
      return a;
    }


    CouplingView
    coupling_view(ImpactModel &model)
    {
#define YARN_IMPACT_FE_VIEW(type, Law, member)           \
  if (auto *fe = dynamic_cast<YarnModel<Law> *>(&model)) \
    return fe->coupling_view();
      YARN_IMPACT_FE_FOR_EACH_LAW(YARN_IMPACT_FE_VIEW)
#undef YARN_IMPACT_FE_VIEW
      throw std::logic_error("FE::coupling_view: not an FE model");
    }


    std::unique_ptr<ImpactModel>
    create_model(const YarnImpact::Parameters::Shared &shared,
                 const Parameters &parameters,
                 const MPI_Comm communicator)
    {
      validate(shared, parameters);
      Parameters law_parameters = with_fibre_data(shared, parameters);
      // A crimped yarn's fibres follow its centreline: each Gauss point
      // gets the tangent at its section (doc/fe-model.md section 8).
      if (parameters.crimp.crimped())
        {
          const Fabric::CrimpedYarn crimped(
            crimped_yarn_geometry(shared.yarn,
                                  shared.general.symmetry,
                                  parameters.n_axial_cells,
                                  parameters.section_refinements,
                                  parameters.preserve_section_area,
                                  parameters.crimp));
          law_parameters.fibre_direction = [crimped](const double *X,
                                                     double *M) {
            crimped.fibre_direction(X, M);
          };
        }
      const double density = law_parameters.density;
      return with_law(law_parameters,
                      density,
                      [&](const auto &law) -> std::unique_ptr<ImpactModel> {
                        using Law = std::decay_t<decltype(law)>;
                        return std::make_unique<YarnModel<Law>>(shared,
                                                                law_parameters,
                                                                law,
                                                                communicator);
                      });
    }
  } // namespace FE
} // namespace YarnImpact
