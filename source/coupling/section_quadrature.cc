// The FE part's section quadrature from the fibres of the DEM part
// (doc/hybrid.md section 3.3), and where a fibre lies in the section.

#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/core/yarn_section.h>
#include <yarn_impact/coupling/hybrid_parts.h>
#include <yarn_impact/dem/packing.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace YarnImpact
{
  namespace Coupling
  {
    using namespace dealii;
    using YarnImpact::Parameters::require;


    unsigned int
    section_vertex(const Triangulation<2> &section,
                   const Point<2> &p,
                   const double semi_axis)
    {
      const std::vector<Point<2>> &vertices = section.get_vertices();
      unsigned int v                        = 0;
      for (unsigned int k = 1; k < vertices.size(); ++k)
        if (p.distance(vertices[k]) < p.distance(vertices[v]))
          v = k;
      if (!(p.distance(vertices[v]) < 1e-6 * semi_axis))
        throw std::logic_error("Hybrid: an FE node of a part is not a "
                               "vertex of the section it was extruded from");
      return v;
    }


    std::vector<LayerNode>
    layer_nodes(ImpactModel &fe_model,
                const Triangulation<2> &section,
                const double x_begin,
                const double h,
                const unsigned int n_layers,
                const double semi_axis,
                const MPI_Comm communicator)
    {
      const unsigned int n_vertices = section.n_vertices();
      const FE::CouplingView fe     = FE::coupling_view(fe_model);
      std::vector<LayerNode> nodes;
      std::vector<double> found(n_layers * n_vertices, 0.);
      for (const auto &node : *fe.nodes)
        {
          const double t = ((*fe.reference_coordinate)[node[0]] - x_begin) / h;
          if (t < -1e-6 || t > n_layers - 1 + 1e-6)
            continue;
          const unsigned int layer = std::lround(t);
          if (std::abs(t - layer) > 1e-6)
            throw std::logic_error("Hybrid: an FE node of a part lies "
                                   "between its node layers");
          const unsigned int v =
            section_vertex(section,
                           Point<2>((*fe.reference_coordinate)[node[1]],
                                    (*fe.reference_coordinate)[node[2]]),
                           semi_axis);
          nodes.push_back({layer * n_vertices + v, node});
          found[layer * n_vertices + v] += 1.;
        }
      Utilities::MPI::sum(found, communicator, found);
      for (const double x : found)
        if (x != 1.)
          throw std::logic_error("Hybrid: a node of a part's layers is "
                                 "missing from the FE part or owned twice");
      return nodes;
    }


    namespace
    {
      /** The unit coordinates @p u of the point @p p [m] in the section
       * cell @p cell; false where the mapping cannot invert there. */
      bool
      unit_point(const Triangulation<2>::active_cell_iterator &cell,
                 const Point<2> &p,
                 Point<2> &u)
      {
        static const MappingQ1<2> mapping;
        try
          {
            u = mapping.transform_real_to_unit_cell(cell, p);
          }
        catch (...)
          {
            return false;
          }
        return true;
      }
    } // namespace


    void
    locate_in_section(const Triangulation<2> &section,
                      const Point<2> &p,
                      unsigned int &cell_index,
                      std::array<unsigned int, 4> &vertices,
                      std::array<double, 4> &values)
    {
      static const FE_Q<2> q1(1);
      double best = std::numeric_limits<double>::max();
      for (const auto &cell : section.active_cell_iterators())
        {
          Point<2> u;
          if (!unit_point(cell, p, u))
            continue;
          double outside = 0.;
          for (unsigned int d = 0; d < 2; ++d)
            outside = std::max({outside, -u[d], u[d] - 1.});
          if (outside < best)
            {
              best = outside;
              for (unsigned int d = 0; d < 2; ++d)
                u[d] = std::clamp(u[d], 0., 1.);
              cell_index = cell->active_cell_index();
              for (unsigned int v = 0; v < 4; ++v)
                {
                  vertices[v] = cell->vertex_index(v);
                  values[v]   = q1.shape_value(v, u);
                }
            }
        }
      AssertThrow(best < std::numeric_limits<double>::max(),
                  ExcMessage("Hybrid: a fibre centre could not be placed "
                             "in the FE section"));
    }


    std::function<double(const double *)>
    section_quadrature(const YarnImpact::Parameters::Shared &shared,
                       const FE::Parameters &fe,
                       const DEM::Parameters &dem)
    {
      // With quarter symmetry the section is its half z >= 0.
      const bool quarter =
        shared.general.symmetry == YarnImpact::Parameters::Symmetry::quarter;
      Triangulation<2> section;
      create_yarn_section(section,
                          shared.yarn.thickness_semi_axis,
                          shared.yarn.width_semi_axis,
                          fe.section_refinements,
                          quarter,
                          fe.preserve_section_area);
      const DEM::FibreCentres centres =
        DEM::fibre_centres(shared, dem, quarter);
      const double share = shared.yarn.section_area() / centres.size();
      std::vector<std::array<double, 4>> target(section.n_active_cells(),
                                                {{0., 0., 0., 0.}});
      // A fibre on an edge (or a vertex) of the section's cells goes to
      // each of them in equal parts, so that the quadrature is as
      // symmetric as the section and the fibres; in a quarter model a fibre
      // on z = 0 is half a fibre.
      static const FE_Q<2> shape(1);
      for (unsigned int f = 0; f < centres.size(); ++f)
        {
          const Point<2> p(centres.y[f] * (1. + 1e-9),
                           centres.z[f] * (1. + 1e-9));
          if (quarter && p[1] < 0.)
            continue;
          const double weight = (quarter && p[1] == 0.) ? 0.5 : 1.;
          std::vector<std::pair<unsigned int, std::array<double, 4>>> cells;
          for (const auto &cell : section.active_cell_iterators())
            {
              Point<2> u;
              if (!unit_point(cell, p, u))
                continue;
              if (std::min(u[0], u[1]) < -1e-10 ||
                  std::max(u[0], u[1]) > 1. + 1e-10)
                continue;
              std::array<double, 4> psi;
              for (unsigned int v = 0; v < 4; ++v)
                psi[v] = shape.shape_value(v,
                                           Point<2>(std::clamp(u[0], 0., 1.),
                                                    std::clamp(u[1], 0., 1.)));
              cells.emplace_back(cell->active_cell_index(), psi);
            }
          if (cells.empty())
            {
              // Outside the polygonal section: the nearest cell.
              unsigned int c;
              std::array<unsigned int, 4> vertices;
              std::array<double, 4> psi;
              locate_in_section(section, p, c, vertices, psi);
              cells.emplace_back(c, psi);
            }
          for (const auto &[c, psi] : cells)
            for (unsigned int v = 0; v < 4; ++v)
              target[c][v] += weight / cells.size() * share * psi[v];
        }
      const FE_Q<2> q1(1);
      const QGauss<2> quadrature(2);
      FEValues<2> values(q1,
                         quadrature,
                         update_values | update_JxW_values |
                           update_quadrature_points);
      auto points  = std::make_shared<std::vector<Point<2>>>();
      auto factors = std::make_shared<std::vector<double>>();
      for (const auto &cell : section.active_cell_iterators())
        {
          values.reinit(cell);
          // sum_q w_q psi_v(q) = t_v: the 4 x 4 system (Psi^T w = t).
          FullMatrix<double> psi_t(4, 4);
          Vector<double> t(4), w(4);
          for (unsigned int v = 0; v < 4; ++v)
            {
              t[v] = target[cell->active_cell_index()][v];
              for (unsigned int q = 0; q < 4; ++q)
                psi_t(v, q) = values.shape_value(v, q);
            }
          psi_t.gauss_jordan();
          psi_t.vmult(w, t);
          for (unsigned int q = 0; q < 4; ++q)
            {
              std::ostringstream s;
              s << "gives a section cell of the overlap a Gauss weight "
                << w[q] / values.JxW(q)
                << " times its area's: too few fibres in that cell for "
                   "the overlap's section quadrature (refine less with "
                   "FE/Section refinements)";
              require(w[q] > 0., "FE/Section refinements", s.str());
              points->push_back(values.quadrature_point(q));
              factors->push_back(w[q] / values.JxW(q));
            }
        }
      const double tol = 1e-6 * shared.yarn.thickness_semi_axis;
      return [points, factors, tol](const double *xyz) {
        const Point<2> p(xyz[1], xyz[2]);
        unsigned int best = 0;
        for (unsigned int k = 1; k < points->size(); ++k)
          if (p.distance((*points)[k]) < p.distance((*points)[best]))
            best = k;
        if (!(p.distance((*points)[best]) < tol))
          throw std::logic_error("Hybrid: a Gauss point of the overlap is "
                                 "not one of the section's");
        return (*factors)[best];
      };
    }
  } // namespace Coupling
} // namespace YarnImpact
