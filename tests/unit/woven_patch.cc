// The plain-woven patch of `Model = fabric` (Fabric::WovenPatch,
// doc/fe-model.md section 8.3): 2 warp and 2 weft yarns, spacing 1 mm,
// crimp amplitude 0.1 mm, the paper's section, 8 cells per spacing. In one
// triangulation: 4 x 16 x 12 = 768 cells and every yarn's vertices, none
// shared (4 x 17 x 17 = 1156); each cell's material id is the yarn that
// holds its centre, found by point location (yarn_of); no vertex of a
// yarn lies inside another yarn's elliptical tube; every Jacobian is
// positive at the Gauss points; 2 x 12 end faces per yarn; at each
// crossing one centreline is at +A and the other at -A, alternately (the
// plain weave); the fibre direction at every Gauss point is unit, in its
// yarn's vertical plane (no component across it), and the tangent of its
// yarn. Yarns that would touch (A <= a_y, or a spacing not above the
// width) are refused. Three plies of it, h = 0.5 mm apart: 3 x 768 cells,
// each cell's material id the yarn found by point location, ply p's yarn
// ids p (n_warp + n_weft) to (p + 1) (n_warp + n_weft) - 1, 12 cells in
// every section of every yarn (section_of), and the gap between
// consecutive plies' vertices h - ply_thickness(), 2 (A + a_y) with a_y
// scaled by the section's area-preserving factor (h - 2 (A + a_y) =
// 0.185 mm of the ellipses); plies whose meshes would touch
// (h = ply_thickness()) are refused.

#include <yarn_impact/fabric/woven_patch.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

using namespace YarnImpact;
using dealii::Point;
using dealii::Tensor;

int
main()
{
  const Fabric::WovenPatchGeometry g; // 2 x 2, s = 1 mm, A = 0.1 mm
  const Fabric::WovenPatch patch(g);
  dealii::Triangulation<3> mesh;
  patch.create_mesh(mesh);
  std::printf("cells %u (768), vertices %u (1156)\n",
              mesh.n_active_cells(),
              mesh.n_vertices());

  // Material ids against point location; end faces; Jacobians and fibre
  // directions at the Gauss points.
  dealii::FE_Q<3> fe(1);
  dealii::QGauss<3> quadrature(2);
  dealii::FEValues<3> values(fe,
                             quadrature,
                             dealii::update_JxW_values |
                               dealii::update_quadrature_points);
  unsigned int wrong_id = 0, end_faces = 0, wrong_direction = 0;
  double smallest_jxw = std::numeric_limits<double>::max();
  for (const auto &cell : mesh.active_cell_iterators())
    {
      const unsigned int id = cell->material_id();
      if (patch.yarn_of(cell->center()) != id)
        ++wrong_id;
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary() &&
            face->boundary_id() == Fabric::BoundaryIds::end)
          ++end_faces;
      values.reinit(cell);
      for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          smallest_jxw         = std::min(smallest_jxw, values.JxW(q));
          const Point<3> &X    = values.quadrature_point(q);
          const Tensor<1, 3> M = patch.fibre_direction(X);
          const Tensor<1, 3> t =
            patch.yarn(id).fibre_direction(patch.to_yarn_frame(id, X));
          // The weft's own x is the patch's z.
          const double along  = patch.is_warp(id) ? M[0] : M[2];
          const double across = patch.is_warp(id) ? M[2] : M[0];
          if (std::abs(M.norm() - 1.) > 1e-12 || std::abs(across) > 1e-12 ||
              std::abs(along - t[0]) > 1e-12 || std::abs(M[1] - t[1]) > 1e-12)
            ++wrong_direction;
        }
    }
  std::printf("material id = yarn found by point location: %s\n"
              "end faces %u (96)\n"
              "every Jacobian positive: %s\n"
              "fibre direction = its yarn's tangent at every Gauss point: "
              "%s\n",
              wrong_id == 0 ? "OK" : "WRONG",
              end_faces,
              smallest_jxw > 0. ? "OK" : "WRONG",
              wrong_direction == 0 ? "OK" : "WRONG");

  // No vertex inside another yarn: its section radius there above 1.
  std::vector<unsigned int> owner(mesh.n_vertices());
  for (const auto &cell : mesh.active_cell_iterators())
    for (const unsigned int v : cell->vertex_indices())
      owner[cell->vertex_index(v)] = cell->material_id();
  double closest = std::numeric_limits<double>::max();
  for (unsigned int v = 0; v < mesh.n_vertices(); ++v)
    for (unsigned int id = 0; id < patch.n_yarns(); ++id)
      if (id != owner[v])
        closest =
          std::min(closest, patch.section_radius(id, mesh.get_vertices()[v]));
  std::printf("no vertex inside another yarn (smallest section radius "
              "%.3f > 1): %s\n",
              std::sqrt(closest),
              closest > 1. ? "OK" : "WRONG");

  // The plain weave: over and under, alternately.
  bool woven = true;
  for (unsigned int i = 0; i < g.n_warp; ++i)
    for (unsigned int j = 0; j < g.n_weft; ++j)
      {
        const double x_j  = (j - 0.5 * (g.n_weft - 1.)) * g.spacing;
        const double z_i  = (i - 0.5 * (g.n_warp - 1.)) * g.spacing;
        const double sign = (i + j) % 2 == 0 ? 1. : -1.;
        const double warp = patch.yarn(i).centreline(x_j)[1];
        const double weft = patch.yarn(g.n_warp + j).centreline(z_i)[1];
        woven = woven && std::abs(warp - sign * g.amplitude) < 1e-15 &&
                std::abs(weft + sign * g.amplitude) < 1e-15;
      }
  std::printf("at each crossing one yarn at +A, the other at -A, "
              "alternately: %s\n",
              woven ? "OK" : "WRONG");

  // Refusals.
  const auto refused = [](Fabric::WovenPatchGeometry bad) {
    try
      {
        Fabric::WovenPatch p(bad);
        return false;
      }
    catch (const std::invalid_argument &)
      {
        return true;
      }
  };
  Fabric::WovenPatchGeometry touching = g, crowded = g;
  touching.amplitude = g.thickness_semi_axis;
  crowded.spacing    = 2. * g.width_semi_axis;
  std::printf("refused: A = a_y %s, spacing = 2 a_z %s\n",
              refused(touching) ? "OK" : "WRONG",
              refused(crowded) ? "OK" : "WRONG");

  // Three plies.
  Fabric::WovenPatchGeometry stacked = g;
  stacked.n_plies                    = 3;
  stacked.ply_spacing                = 0.5e-3;
  const Fabric::WovenPatch plies(stacked);
  dealii::Triangulation<3> stack;
  plies.create_mesh(stack);
  const unsigned int per_ply = plies.yarns_per_ply();
  unsigned int wrong_ply_id  = 0;
  std::vector<unsigned int> section_cells(plies.n_yarns() * 16, 0);
  for (const auto &cell : stack.active_cell_iterators())
    {
      const unsigned int id = cell->material_id();
      const Point<3> c      = cell->center();
      if (plies.yarn_of(c) != id || plies.ply(id) != id / per_ply ||
          std::abs(c[1] - plies.ply_height(plies.ply(id))) >
            g.amplitude + g.thickness_semi_axis)
        ++wrong_ply_id;
      ++section_cells[id * 16 + plies.section_of(id, c)];
    }
  const bool sections = std::all_of(section_cells.begin(),
                                    section_cells.end(),
                                    [](unsigned n) { return n == 12; });
  // Each ply's lowest and highest vertex.
  std::vector<double> low(3, 1.), high(3, -1.);
  for (const auto &cell : stack.active_cell_iterators())
    for (const unsigned int v : cell->vertex_indices())
      {
        const unsigned int p = plies.ply(cell->material_id());
        low[p]               = std::min(low[p], cell->vertex(v)[1]);
        high[p]              = std::max(high[p], cell->vertex(v)[1]);
      }
  const double gap =
    stacked.ply_spacing - Fabric::WovenPatch::ply_thickness(stacked);
  double worst_gap = 0.;
  for (unsigned int p = 0; p + 1 < 3; ++p)
    worst_gap = std::max(worst_gap, std::abs(low[p] - high[p + 1] - gap));
  Fabric::WovenPatchGeometry touching_plies = stacked;
  touching_plies.ply_spacing = Fabric::WovenPatch::ply_thickness(stacked);
  std::printf("3 plies: cells %u (2304), vertices %u (3468); material id = "
              "yarn found by point location, in its ply: %s; 12 cells in "
              "each of the %zu sections: %s; gap between plies %.4f mm "
              "(h - ply_thickness() %.4f mm): %s; refused: h = "
              "ply_thickness() %s\n",
              stack.n_active_cells(),
              stack.n_vertices(),
              wrong_ply_id == 0 ? "OK" : "WRONG",
              section_cells.size(),
              sections ? "OK" : "WRONG",
              (low[0] - high[1]) * 1e3,
              gap * 1e3,
              worst_gap < 1e-12 ? "OK" : "WRONG",
              refused(touching_plies) ? "OK" : "WRONG");
}
