#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/core/reproducible_sum.h>
#include <yarn_impact/fe/constitutive_law.h>
#include <yarn_impact/fe/fe_model.h>
#include <yarn_impact/fe/yarn_mesh.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <sstream>
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
    {}


    template <class Law>
    void
    YarnModel<Law>::setup(const Projectile &projectile, std::ostream &out)
    {
      const auto &yarn = shared.yarn;
      projectile_speed = std::abs(projectile.velocity());
      // A part of a hybrid yarn (FE::Parameters::layer_weight), or the
      // whole yarn.
      const bool part = !parameters.layer_weight.empty();
      const double part_end =
        parameters.part_end < 0. ? 0.5 * yarn.length : parameters.part_end;
      if (part)
        create_yarn_part_mesh(tria,
                              yarn,
                              parameters.part_begin,
                              part_end,
                              parameters.layer_weight.size(),
                              parameters.section_refinements,
                              parameters.preserve_section_area);
      else
        create_yarn_mesh(tria,
                         yarn,
                         shared.general.symmetry,
                         parameters.n_axial_cells,
                         parameters.section_refinements,
                         parameters.preserve_section_area);
      tria.refine_global(parameters.global_refinements);
      dof_handler.distribute_dofs(fe);

      const IndexSet owned = dof_handler.locally_owned_dofs();
      IndexSet relevant;
      DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
      for (VectorType *v :
           {&displacement, &velocity, &force, &lumped_mass, &inverse_mass})
        v->reinit(owned, relevant, communicator);
      const auto &partitioner = displacement.get_partitioner();
      const unsigned int n_local =
        partitioner->locally_owned_size() + partitioner->n_ghost_indices();
      reference_coordinate.assign(n_local, 0.);

      const bool reduced =
        shared.general.symmetry != YarnImpact::Parameters::Symmetry::none;
      const unsigned int refinement_factor = 1u
                                             << parameters.global_refinements;
      n_layers =
        (reduced ? parameters.n_axial_cells / 2 : parameters.n_axial_cells) *
        refinement_factor;
      station_spacing =
        yarn.length / (parameters.n_axial_cells * refinement_factor);
      n_stations = parameters.n_axial_cells / 2 * refinement_factor + 1;
      if (part)
        {
          n_layers        = parameters.layer_weight.size();
          station_spacing = (part_end - parameters.part_begin) / n_layers;
          n_stations      = n_layers + 1;
          station_origin  = parameters.part_begin;
        }
      cells_per_layer    = tria.n_global_active_cells() / n_layers;
      const double x_min = part      ? parameters.part_begin
                           : reduced ? 0.
                                     : -0.5 * yarn.length;

      FE_Q<3> scalar_fe(1);
      QGauss<3> quadrature(2);
      FEValues<3> fe_values(scalar_fe,
                            quadrature,
                            update_values | update_gradients |
                              update_JxW_values | update_quadrature_points);
      QGauss<2> face_quadrature(2);
      FEFaceValues<3> fe_face_values(scalar_fe,
                                     face_quadrature,
                                     update_values | update_JxW_values);
      VectorType area;
      area.reinit(owned, relevant, communicator);

      // The force loop visits the owned and the ghost cells, in one global
      // order (by CellId). Every owned dof then gets the forces of all its
      // cells from its own rank, added in the same order whatever the
      // partition, and nothing is added across ranks (no compress): with
      // compress(add), the partial sums of the ranks sharing a dof would be
      // added in another order than a serial loop's, and the histories
      // would depend on the number of ranks. Ghost cells are the vertex
      // neighbours of the owned cells, which is all that touch an owned
      // dof (checked below). The masses and areas are summed the same way.
      std::vector<typename DoFHandler<3>::active_cell_iterator> loop_cells;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() || cell->is_ghost())
          loop_cells.push_back(cell);
      std::sort(loop_cells.begin(),
                loop_cells.end(),
                [](const auto &a, const auto &b) { return a->id() < b->id(); });
      // The owned cells' masses added by compress(add), for the check.
      VectorType mass_check;
      mass_check.reinit(owned, relevant, communicator);

      for (const auto &cell : loop_cells)
        {
          if (cell->is_locally_owned())
            owned_cells.push_back(cell_index.size());
          fe_values.reinit(typename Triangulation<3>::cell_iterator(cell));
          cell_index.push_back(cell->active_cell_index());
          // The continuum weight of the cell's layer (a hybrid's part).
          const double weight =
            part ? parameters.layer_weight[std::min<unsigned int>(
                     n_layers - 1,
                     static_cast<unsigned int>(std::floor(
                       (cell->center()[0] - x_min) / station_spacing)))]
                 : 1.;
          double x_lo = std::numeric_limits<double>::max(), x_hi = -x_lo;
          double y_top = -std::numeric_limits<double>::max();
          for (unsigned int a = 0; a < n_nodes; ++a)
            {
              y_top            = std::max(y_top, cell->vertex(a)[1]);
              double node_mass = 0.;
              for (unsigned int q = 0; q < n_q; ++q)
                node_mass +=
                  law.density * fe_values.shape_value(a, q) * fe_values.JxW(q);
              if (part)
                node_mass *= weight;
              for (unsigned int d = 0; d < 3; ++d)
                {
                  const auto local =
                    partitioner->global_to_local(cell->vertex_dof_index(a, d));
                  cells.dofs.push_back(local);
                  reference_coordinate[local] = cell->vertex(a)[d];
                  lumped_mass.local_element(local) += node_mass;
                  if (cell->is_locally_owned())
                    mass_check.local_element(local) += node_mass;
                }
              x_lo = std::min(x_lo, cell->vertex(a)[0]);
              x_hi = std::max(x_hi, cell->vertex(a)[0]);
            }
          {
            const std::size_t offset = cells.grads.size();
            cells.grads.resize(offset + grad_size);
            for (unsigned int q = 0; q < n_q; ++q)
              {
                for (unsigned int a = 0; a < n_nodes; ++a)
                  for (unsigned int d = 0; d < 3; ++d)
                    cells.grads[offset + gradient_index(q, a, d)] =
                      fe_values.shape_grad(a, q)[d];
                double jxw = fe_values.JxW(q);
                if (part)
                  {
                    jxw *= weight;
                    if (parameters.section_quadrature_factor)
                      {
                        const Point<3> &p   = fe_values.quadrature_point(q);
                        const double xyz[3] = {p[0], p[1], p[2]};
                        jxw *= parameters.section_quadrature_factor(xyz);
                      }
                  }
                cells.JxW.push_back(jxw);
              }
          }
          // The local axis along the fibre: the one whose opposite faces
          // are farthest apart in x.
          unsigned char axis = 0;
          double best        = -1.;
          for (unsigned int k = 0; k < 3; ++k)
            {
              double dx = 0.;
              for (unsigned int a = 0; a < n_nodes; ++a)
                dx += ((a >> k) & 1 ? 1. : -1.) * cell->vertex(a)[0];
              if (std::abs(dx) > best)
                {
                  best = std::abs(dx);
                  axis = k;
                }
            }
          cell_axis.push_back(axis);
          // The crack band's width: the cell's reference length along the
          // fibre (x faces are planes x = const on the extruded mesh).
          cells.fibre_length.push_back(x_hi - x_lo);
          // Depth below the struck face y = +a_y (the projectile comes
          // from +y), 0 there and 1 at y = -a_y, of the cell's shallowest
          // point: its fibres nearest the struck face break first, and
          // its damage starts when they do (doc/theory.md section 5.4).
          {
            const double a_y = shared.yarn.thickness_semi_axis;
            cells.depth.push_back(
              std::clamp((a_y - y_top) / (2. * a_y), 0., 1.));
          }
          double volume = 0.;
          for (unsigned int q = 0; q < n_q; ++q)
            volume += fe_values.JxW(q);
          cell_volume.push_back(volume);
          cell_layer.push_back(static_cast<unsigned int>(
            std::floor((0.5 * (x_lo + x_hi) - x_min) / station_spacing)));

          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == BoundaryIds::lateral)
              {
                fe_face_values.reinit(typename Triangulation<3>::cell_iterator(
                                        cell),
                                      f);
                for (unsigned int a = 0; a < n_nodes; ++a)
                  {
                    double a_area = 0.;
                    for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                      a_area += fe_face_values.shape_value(a, q) *
                                fe_face_values.JxW(q);
                    area.local_element(partitioner->global_to_local(
                      cell->vertex_dof_index(a, 0))) += a_area;
                  }
              }
        }
      // The ghost entries hold partial sums: only the owned ones are used.
      lumped_mass.zero_out_ghost_values();
      area.zero_out_ghost_values();
      mass_check.compress(VectorOperation::add);
      bool complete = true;
      for (unsigned int i = 0; i < partitioner->locally_owned_size(); ++i)
        complete = complete && std::abs(mass_check.local_element(i) -
                                        lumped_mass.local_element(i)) <=
                                 1e-12 * lumped_mass.local_element(i);
      AssertThrow(!Utilities::MPI::logical_or(!complete, communicator),
                  ExcMessage("FE set-up: a cell next to an owned node is "
                             "neither owned nor a ghost cell"));

      const unsigned int n_loop_cells = cell_index.size();
      cells.reset_state(n_loop_cells);
      failure_law =
        make_failure_law(shared.yarn, parameters.failure, law.axial_modulus());

      // Owned nodes, their constraints and stations. The x dof of a vertex
      // identifies it; all three dofs of a vertex have the same owner.
      const double tol = 1e-6 * station_spacing;
      std::vector<bool> seen(n_local, false);
      for (const unsigned int c : owned_cells)
        for (unsigned int a = 0; a < n_nodes; ++a)
          {
            const unsigned int ix = cells.dofs[c * n_cell_dofs + 3 * a];
            if (seen[ix] || ix >= partitioner->locally_owned_size())
              continue;
            seen[ix]                               = true;
            const std::array<unsigned int, 3> node = {
              {ix,
               cells.dofs[c * n_cell_dofs + 3 * a + 1],
               cells.dofs[c * n_cell_dofs + 3 * a + 2]}};
            nodes.push_back(node);
            const double x = reference_coordinate[node[0]];
            const double z = reference_coordinate[node[2]];
            node_station.push_back(static_cast<unsigned int>(
              std::round((std::abs(x) - station_origin) / station_spacing)));
            std::array<bool, 3> fixed = {{false, false, false}};
            if (std::abs(std::abs(x) - 0.5 * yarn.length) < tol)
              fixed = {{true, true, true}};
            if (reduced && std::abs(x) < tol)
              fixed[0] = true;
            if (shared.general.symmetry ==
                  YarnImpact::Parameters::Symmetry::quarter &&
                std::abs(z) < 1e-9 * yarn.width_semi_axis)
              fixed[2] = true;
            for (unsigned int d = 0; d < 3; ++d)
              inverse_mass.local_element(node[d]) =
                fixed[d] ? 0. : 1. / lumped_mass.local_element(node[d]);

            const double node_area = area.local_element(node[0]);
            if (node_area > 0. && !fixed[1])
              contact.add_node(node,
                               node_area,
                               lumped_mass.local_element(node[0]));
          }

      // Mass of the whole yarn (each node's x dof carries its mass once).
      ReproducibleSum mass_sum(1);
      for (const auto &node : nodes)
        mass_sum.add(0, lumped_mass.local_element(node[0]));
      total_mass       = symmetry * mass_sum.sum(communicator)[0];
      double local_top = -std::numeric_limits<double>::max();
      for (const auto &node : nodes)
        local_top = std::max(local_top, reference_coordinate[node[1]]);
      top = Utilities::MPI::max(local_top, communicator);

      contact_time_step = contact.stable_time_step(communicator);

      displacement = 0.;
      velocity     = 0.;
      displacement.update_ghost_values();

      // The initial section widths, measured as at every history row.
      initial_width.assign(n_stations, 0.);
      {
        const Observables o = observables();
        (void)o;
      }

      out << "[fe] mesh: " << tria.n_global_active_cells() << " cells ("
          << cells_per_layer << " per section, " << n_layers
          << " along the modelled length), " << dof_handler.n_dofs()
          << " dofs, " << Utilities::MPI::n_mpi_processes(communicator)
          << " MPI rank(s)\n"
          << "[fe] contact penalty " << parameters.contact.penalty
          << " Pa/m: stable step of a surface node on it "
          << contact_time_step * 1e9 << " ns\n";
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
      const double dt_waves =
        1. / std::sqrt(1. / (dt_bulk * dt_bulk) +
                       1. / (contact_time_step * contact_time_step));
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
      ReproducibleSum reaction(1);
      contact.add_reactions(reaction, 0);
      return symmetry * reaction.sum(communicator)[0];
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
      const Parameters law_parameters = with_fibre_data(shared, parameters);
      const double density            = law_parameters.density;
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
