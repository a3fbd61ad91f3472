// The FE model's set-up, step by step as in deal.II's step-44: the mesh,
// the degrees of freedom, the data of the cells and their quadrature
// points, the nodes with their constraints and projectile contact, the
// initial state.
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/core/reproducible_sum.h>
#include <yarn_impact/fe/constitutive_law.h>
#include <yarn_impact/fe/fe_model.h>
#include <yarn_impact/fe/yarn_mesh.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>

#include "yarn_model.h"

namespace YarnImpact
{
  namespace FE
  {
    using namespace dealii;


    template <class Law>
    void
    YarnModel<Law>::setup(const Projectile &projectile, std::ostream &out)
    {
      projectile_speed = std::abs(projectile.velocity());
      make_grid();
      setup_system();
      const VectorType area = setup_cells();
      setup_nodes(area);
      setup_initial_state();

      out << "[fe] mesh: " << tria.n_global_active_cells() << " cells (";
      if (parameters.mesh.given())
        out << "given, " << parameters.n_axial_cells / 2 + 1
            << " stations along x";
      else
        out << cells_per_layer << " per section, " << n_layers
            << " along the modelled length";
      out << "), " << dof_handler.n_dofs() << " dofs, "
          << Utilities::MPI::n_mpi_processes(communicator)
          << " MPI rank(s), cell kernel: " << cell_kernel_variant() << "\n";
      if (parameters.projectile_contact)
        out << "[fe] contact penalty " << parameters.contact.penalty
            << " Pa/m: stable step of a surface node on it "
            << contact_time_step * 1e9 << " ns\n";
      else
        out << "[fe] no projectile contact on the surface (the coupling's "
               "fibres touch the projectile)\n";
      for (const auto &extra : parameters.extra_forces)
        out << extra->report();
    }


    template <class Law>
    void
    YarnModel<Law>::make_grid()
    {
      const auto &yarn = shared.yarn;
      if (parameters.mesh.given())
        parameters.mesh.create(tria);
      else if (is_part())
        create_yarn_part_mesh(tria,
                              yarn,
                              shared.general.symmetry,
                              parameters.part_begin,
                              part_end(),
                              parameters.layer_weight.size(),
                              parameters.section_refinements,
                              parameters.preserve_section_area);
      else if (crimped)
        create_crimped_yarn_mesh(tria, *crimped);
      else
        create_yarn_mesh(tria,
                         yarn,
                         shared.general.symmetry,
                         parameters.n_axial_cells,
                         parameters.section_refinements,
                         parameters.preserve_section_area);
      tria.refine_global(parameters.global_refinements);
    }


    template <class Law>
    void
    YarnModel<Law>::setup_system()
    {
      dof_handler.distribute_dofs(fe);
      const IndexSet owned = dof_handler.locally_owned_dofs();
      IndexSet relevant;
      DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
      for (VectorType *v :
           {&displacement, &velocity, &force, &lumped_mass, &inverse_mass})
        v->reinit(owned, relevant, communicator);
      const auto &partitioner = displacement.get_partitioner();
      reference_coordinate.assign(partitioner->locally_owned_size() +
                                    partitioner->n_ghost_indices(),
                                  0.);
      reference_abscissa.assign(reference_coordinate.size(), 0.);

      const unsigned int refinement_factor = 1u
                                             << parameters.global_refinements;
      n_layers =
        (reduced() ? parameters.n_axial_cells / 2 : parameters.n_axial_cells) *
        refinement_factor;
      station_spacing =
        shared.yarn.length / (parameters.n_axial_cells * refinement_factor);
      n_stations = parameters.n_axial_cells / 2 * refinement_factor + 1;
      if (is_part())
        {
          n_layers        = parameters.layer_weight.size();
          station_spacing = (part_end() - parameters.part_begin) / n_layers;
          n_stations      = n_layers + 1;
          station_origin  = parameters.part_begin;
        }
      cells_per_layer = tria.n_global_active_cells() / n_layers;
    }


    template <class Law>
    typename YarnModel<Law>::VectorType
    YarnModel<Law>::setup_cells()
    {
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
      area.reinit(displacement.get_partitioner());

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
      mass_check.reinit(displacement.get_partitioner());

      for (const auto &cell : loop_cells)
        {
          if (cell->is_locally_owned())
            owned_cells.push_back(cell_index.size());
          if (parameters.energy_group)
            cell_group.push_back(parameters.energy_group(cell->material_id()));
          if (parameters.mesh.section)
            {
              const Point<3> X     = cell->center();
              const unsigned int m = cell->material_id();
              const unsigned int k = parameters.mesh.section(m, &X[0]);
              AssertThrow(m < parameters.mesh.n_yarns &&
                            k < parameters.mesh.sections_per_yarn,
                          ExcMessage("FE set-up: a cell's yarn or section is "
                                     "beyond GivenMesh::n_yarns or "
                                     "sections_per_yarn"));
              cell_section.push_back(m * parameters.mesh.sections_per_yarn + k);
            }
          fe_values.reinit(typename Triangulation<3>::cell_iterator(cell));
          cell_index.push_back(cell->active_cell_index());
          // The continuum weight of the cell's layer (a hybrid's part).
          const double weight =
            is_part()
              ? parameters.layer_weight[std::min<unsigned int>(
                  n_layers - 1,
                  static_cast<unsigned int>(std::floor(
                    (cell->center()[0] - x_begin()) / station_spacing)))]
              : 1.;
          add_cell_nodes(cell, fe_values, weight, mass_check);
          add_cell_quadrature(fe_values, weight);
          add_cell_geometry(cell, fe_values);
          add_lateral_area(cell, fe_face_values, area);
        }
      if (parameters.mesh.section)
        {
          // Every section's cells over all ranks, for broken_yarns().
          section_cells.assign(parameters.mesh.n_yarns *
                                 parameters.mesh.sections_per_yarn,
                               0);
          for (const unsigned int c : owned_cells)
            ++section_cells[cell_section[c]];
          Utilities::MPI::sum(section_cells, communicator, section_cells);
        }
      // The ghost entries hold partial sums: only the owned ones are used.
      lumped_mass.zero_out_ghost_values();
      area.zero_out_ghost_values();
      mass_check.compress(VectorOperation::add);
      bool complete = true;
      for (unsigned int i = 0; i < lumped_mass.locally_owned_size(); ++i)
        complete = complete && std::abs(mass_check.local_element(i) -
                                        lumped_mass.local_element(i)) <=
                                 1e-12 * lumped_mass.local_element(i);
      AssertThrow(!Utilities::MPI::logical_or(!complete, communicator),
                  ExcMessage("FE set-up: a cell next to an owned node is "
                             "neither owned nor a ghost cell"));

      cells.reset_state(cell_index.size());
      failure_law =
        make_failure_law(shared.yarn, parameters.failure, law.axial_modulus());
      if (failure_law.kind == FailureLaw::Kind::none &&
          parameters.erode_crushed_cells)
        failure_law.kind = FailureLaw::Kind::erosion;
      return area;
    }


    template <class Law>
    void
    YarnModel<Law>::add_cell_nodes(
      const typename DoFHandler<3>::active_cell_iterator &cell,
      const FEValues<3> &fe_values,
      const double weight,
      VectorType &mass_check)
    {
      const auto &partitioner = displacement.get_partitioner();
      for (unsigned int a = 0; a < n_nodes; ++a)
        {
          double node_mass = 0.;
          for (unsigned int q = 0; q < n_q; ++q)
            node_mass +=
              law.density * fe_values.shape_value(a, q) * fe_values.JxW(q);
          if (is_part())
            node_mass *= weight;
          for (unsigned int d = 0; d < 3; ++d)
            {
              const auto local =
                partitioner->global_to_local(cell->vertex_dof_index(a, d));
              cells.dofs.push_back(local);
              reference_coordinate[local] = cell->vertex(a)[d];
              if (d == 0)
                reference_abscissa[local] = abscissa(cell->vertex(a));
              lumped_mass.local_element(local) += node_mass;
              if (cell->is_locally_owned())
                mass_check.local_element(local) += node_mass;
            }
        }
    }


    template <class Law>
    void
    YarnModel<Law>::add_cell_quadrature(const FEValues<3> &fe_values,
                                        const double weight)
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
          if (is_part())
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
      if (parameters.fibre_direction)
        {
          Mechanics::FibreFrame R[n_q];
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const Point<3> &p   = fe_values.quadrature_point(q);
              const double xyz[3] = {p[0], p[1], p[2]};
              double M[3];
              parameters.fibre_direction(xyz, M);
              Mechanics::fibre_frame(M, R[q]);
            }
          cells.set_fibre_frames(offset / grad_size, R);
        }
    }


    template <class Law>
    void
    YarnModel<Law>::add_cell_geometry(
      const typename DoFHandler<3>::active_cell_iterator &cell,
      const FEValues<3> &fe_values)
    {
      // The cell's mean fibre direction M: e_x on the straight yarn, the
      // normalised sum of its Gauss points' with FE::Parameters::
      // fibre_direction (exactly e_x again when they all are).
      double M[3] = {1., 0., 0.};
      if (parameters.fibre_direction)
        {
          M[0] = 0.;
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const Point<3> &p   = fe_values.quadrature_point(q);
              const double xyz[3] = {p[0], p[1], p[2]};
              double Mq[3];
              parameters.fibre_direction(xyz, Mq);
              for (unsigned int d = 0; d < 3; ++d)
                M[d] += Mq[d];
            }
          const double n = std::sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]);
          for (double &m : M)
            m /= n;
        }
      if (parameters.mesh.given())
        cell_fibre.push_back({{M[0], M[1], M[2]}});
      // A reference point's coordinate along M (x on the straight yarn).
      const auto along = [this, &M](const Point<3> &X) {
        return parameters.fibre_direction
                 ? X[0] * M[0] + X[1] * M[1] + X[2] * M[2]
                 : X[0];
      };
      // Its extent along the yarn (in abscissa) and its highest point
      // across it, for its layer and depth.
      double x_lo = std::numeric_limits<double>::max(), x_hi = -x_lo;
      double f_lo = x_lo, f_hi = x_hi;
      double y_top = -std::numeric_limits<double>::max();
      for (unsigned int a = 0; a < n_nodes; ++a)
        {
          y_top = std::max(y_top, section_height(cell->vertex(a)));
          x_lo  = std::min(x_lo, abscissa(cell->vertex(a)));
          x_hi  = std::max(x_hi, abscissa(cell->vertex(a)));
          f_lo  = std::min(f_lo, along(cell->vertex(a)));
          f_hi  = std::max(f_hi, along(cell->vertex(a)));
        }
      // The local axis along the fibre: the one whose opposite faces are
      // farthest apart along M.
      unsigned char axis = 0;
      double best        = -1.;
      for (unsigned int k = 0; k < 3; ++k)
        {
          double dx = 0.;
          for (unsigned int a = 0; a < n_nodes; ++a)
            dx += ((a >> k) & 1 ? 1. : -1.) * along(cell->vertex(a));
          if (std::abs(dx) > best)
            {
              best = std::abs(dx);
              axis = k;
            }
        }
      cell_axis.push_back(axis);
      // The crack band's width: the cell's reference length along the
      // fibre (the faces across the fibre are planes x = const on the
      // extruded mesh, and nearly normal to M on a swept one).
      cells.fibre_length.push_back(f_hi - f_lo);
      // Depth below the struck face y = +a_y (the projectile comes from
      // +y), 0 there and 1 at y = -a_y, of the cell's shallowest point: its
      // fibres nearest the struck face break first, and its damage starts
      // when they do (doc/theory.md section 5.4).
      const double a_y = shared.yarn.thickness_semi_axis;
      cells.depth.push_back(std::clamp((a_y - y_top) / (2. * a_y), 0., 1.));
      double volume = 0.;
      for (unsigned int q = 0; q < n_q; ++q)
        volume += fe_values.JxW(q);
      cell_volume.push_back(volume);
      cell_layer.push_back(static_cast<unsigned int>(
        std::floor((0.5 * (x_lo + x_hi) - x_begin()) / station_spacing)));
    }


    template <class Law>
    void
    YarnModel<Law>::add_lateral_area(
      const typename DoFHandler<3>::active_cell_iterator &cell,
      FEFaceValues<3> &fe_face_values,
      VectorType &area) const
    {
      const auto &partitioner = displacement.get_partitioner();
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
                for (unsigned int q = 0; q < fe_face_values.n_quadrature_points;
                     ++q)
                  a_area +=
                    fe_face_values.shape_value(a, q) * fe_face_values.JxW(q);
                area.local_element(partitioner->global_to_local(
                  cell->vertex_dof_index(a, 0))) += a_area;
              }
          }
    }


    template <class Law>
    void
    YarnModel<Law>::setup_nodes(const VectorType &area)
    {
      const auto &yarn        = shared.yarn;
      const auto &partitioner = displacement.get_partitioner();
      // The x dof of a vertex identifies it; all three dofs of a vertex
      // have the same owner.
      const double tol = 1e-6 * station_spacing;
      std::vector<bool> seen(reference_coordinate.size(), false);
      // A given mesh says where its clamps are (GivenMesh).
      const std::vector<bool> clamped = parameters.mesh.given()
                                          ? dofs_on_faces({BoundaryIds::clamp})
                                          : std::vector<bool>();
      // Nodes in a clamp's grip: the projectile would strike the clamp.
      const std::vector<bool> gripped =
        parameters.mesh.given()
          ? dofs_on_faces(parameters.mesh.outside_projectile_contact)
          : std::vector<bool>();
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
            if (!cell_group.empty())
              node_group.push_back(cell_group[c]);
            // Along the yarn: the abscissa of the node's section, whose
            // end sections are clamped.
            const double x = reference_abscissa[node[0]];
            const double z = reference_coordinate[node[2]];
            node_station.push_back(station_of(x));
            std::array<bool, 3> fixed = {{false, false, false}};
            if (parameters.mesh.given()
                  ? bool(clamped[node[0]])
                  : std::abs(std::abs(x) - 0.5 * yarn.length) < tol)
              fixed = {{true, true, true}};
            if (reduced() && std::abs(x) < tol)
              fixed[0] = true;
            if (shared.general.symmetry ==
                  YarnImpact::Parameters::Symmetry::quarter &&
                std::abs(z) < 1e-9 * yarn.width_semi_axis)
              fixed[2] = true;
            for (unsigned int d = 0; d < 3; ++d)
              inverse_mass.local_element(node[d]) =
                fixed[d] ? 0. : 1. / lumped_mass.local_element(node[d]);

            const double node_area = area.local_element(node[0]);
            if (node_area > 0. && !fixed[1] && parameters.projectile_contact &&
                (gripped.empty() || !gripped[node[0]]))
              contact.add_node(node,
                               node_area,
                               lumped_mass.local_element(node[0]));
          }
    }


    template <class Law>
    void
    YarnModel<Law>::setup_initial_state()
    {
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
      setup_extra_forces();

      displacement = 0.;
      velocity     = 0.;
      displacement.update_ghost_values();

      // The initial section widths, measured as at every history row.
      initial_width.assign(n_stations, 0.);
      {
        const Observables o = observables();
        (void)o;
      }
    }


    template <class Law>
    std::vector<bool>
    YarnModel<Law>::dofs_on_faces(const std::set<unsigned int> &ids) const
    {
      // The owned and ghost cells hold every face that touches an owned
      // node (setup_cells()).
      const auto &partitioner = displacement.get_partitioner();
      std::vector<bool> on(reference_coordinate.size(), false);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned() || cell->is_ghost())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                ids.count(cell->face(f)->boundary_id()) > 0)
              for (const unsigned int v : cell->face(f)->vertex_indices())
                on[partitioner->global_to_local(
                  cell->face(f)->vertex_dof_index(v, 0))] = true;
      return on;
    }


    template <class Law>
    void
    YarnModel<Law>::setup_extra_forces()
    {
      std::vector<double> reference(3 * nodes.size());
      for (unsigned int k = 0; k < nodes.size(); ++k)
        for (unsigned int d = 0; d < 3; ++d)
          reference[3 * k + d] = reference_coordinate[nodes[k][d]];
      extra.clear();
      failure_reported.assign(cells.failed.size(), 0);
      for (const auto &forces : parameters.extra_forces)
        {
          ExtraNodes e;
          e.nodes = forces->setup(reference, communicator);
          e.x.assign(3 * e.nodes.size(), 0.);
          e.v.assign(3 * e.nodes.size(), 0.);
          e.f.assign(3 * e.nodes.size(), 0.);
          extra.push_back(std::move(e));
        }
    }


    // The set-up, for each law (its steps are instantiated by it).
#define YARN_IMPACT_FE_INSTANTIATE(type, Law, member) \
  template void YarnModel<Law>::setup(const Projectile &, std::ostream &);
    YARN_IMPACT_FE_FOR_EACH_LAW(YARN_IMPACT_FE_INSTANTIATE)
#undef YARN_IMPACT_FE_INSTANTIATE
  } // namespace FE
} // namespace YarnImpact
