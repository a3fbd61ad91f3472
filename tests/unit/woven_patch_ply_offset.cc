// Plies shifted in the fabric's plane (WovenPatchGeometry::ply_offset_x,
// ply_offset_z; doc/fabric.md section 1), a geometry test on 3 plies of
// 3 x 4 yarns of the paper's section (s = 1 mm, A = 0.1 mm, 8 cells per
// spacing), each ply shifted by (0.5, 0.25) mm from the one above, against
// the same stack aligned:
// - ply 0 is the aligned stack's, vertex for vertex, bit for bit;
// - ply p's vertices are the aligned ply p's moved by p (0.5, 0, 0.25) mm,
//   within 1e-15 m, and none is left over;
// - at the centre of every cell of the aligned stack, and at the same
//   point moved with its ply: the same yarn (yarn_of), the same section
//   (section_of), the same height across it (section_radius) within
//   1e-12, and the same fibre direction within 1e-12;
// - every yarn's position across its axis (by which the primary yarns,
//   under the projectile, are found) is the stack's geometry within
//   1e-18 m: ply p's warp i at z = (i - (n_warp - 1) / 2) s + p 0.25 mm,
//   its weft j at x = (j - (n_weft - 1) / 2) s + p 0.5 mm;
// - shifted plies with a symmetry plane are refused.

#include <yarn_impact/fabric/woven_patch.h>

#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <vector>

using namespace YarnImpact;
using dealii::Point;

namespace
{
  /** The vertices of the cells of each ply of @p mesh, in cell order. */
  std::vector<std::vector<Point<3>>>
  ply_vertices(const dealii::Triangulation<3> &mesh,
               const Fabric::WovenPatch &patch)
  {
    std::vector<std::vector<Point<3>>> v(patch.geometry().n_plies);
    for (const auto &cell : mesh.active_cell_iterators())
      for (const unsigned int i : cell->vertex_indices())
        v[patch.ply(cell->material_id())].push_back(cell->vertex(i));
    return v;
  }
} // namespace

int
main()
{
  const char *yes_no[] = {"no", "yes"};
  Fabric::WovenPatchGeometry g;
  g.n_warp                           = 3;
  g.n_weft                           = 4;
  g.n_plies                          = 3;
  Fabric::WovenPatchGeometry shifted = g;
  shifted.ply_offset_x               = 0.5e-3;
  shifted.ply_offset_z               = 0.25e-3;
  const Fabric::WovenPatch aligned_patch(g), shifted_patch(shifted);
  dealii::Triangulation<3> aligned_mesh, shifted_mesh;
  aligned_patch.create_mesh(aligned_mesh);
  shifted_patch.create_mesh(shifted_mesh);
  std::printf("3 plies of 3 x 4 yarns, %u cells; each ply shifted by "
              "(0.5, 0.25) mm from the one above\n",
              shifted_mesh.n_active_cells());

  // Vertices, ply by ply, in the order of the cells.
  const auto a = ply_vertices(aligned_mesh, aligned_patch);
  const auto s = ply_vertices(shifted_mesh, shifted_patch);
  for (unsigned int p = 0; p < g.n_plies; ++p)
    {
      const Point<3> shift(p * shifted.ply_offset_x,
                           0.,
                           p * shifted.ply_offset_z);
      double worst   = 0.;
      bool same_bits = a[p].size() == s[p].size();
      for (unsigned int i = 0; same_bits && i < a[p].size(); ++i)
        {
          worst     = std::max(worst, (s[p][i] - (a[p][i] + shift)).norm());
          same_bits = same_bits && (p > 0 || s[p][i] == a[p][i]);
        }
      std::printf("  ply %u: %zu cell vertices; %s: %s (largest distance "
                  "%.2g m)\n",
                  p,
                  s[p].size(),
                  p == 0 ? "the aligned ply's bit for bit"
                         : "the aligned ply's moved by p (0.5, 0, 0.25) mm "
                           "within 1e-15 m",
                  yes_no[same_bits && worst <= 1e-15],
                  worst);
    }

  // The yarn, section, height and fibre direction of moved points.
  unsigned int points = 0, yarn_differs = 0, section_differs = 0;
  double radius_error = 0., direction_error = 0.;
  for (const auto &cell : aligned_mesh.active_cell_iterators())
    {
      const Point<3> X = cell->center();
      const unsigned int p =
        aligned_patch.ply(aligned_patch.yarn_of(X)); // the cell's ply
      const Point<3> Y =
        X + Point<3>(p * shifted.ply_offset_x, 0., p * shifted.ply_offset_z);
      const unsigned int ya = aligned_patch.yarn_of(X),
                         ys = shifted_patch.yarn_of(Y);
      ++points;
      yarn_differs += ya != ys || ya != cell->material_id();
      section_differs +=
        aligned_patch.section_of(ya, X) != shifted_patch.section_of(ys, Y);
      radius_error    = std::max(radius_error,
                              std::abs(aligned_patch.section_radius(ya, X) -
                                       shifted_patch.section_radius(ys, Y)));
      direction_error = std::max(direction_error,
                                 (aligned_patch.fibre_direction(X) -
                                  shifted_patch.fibre_direction(Y))
                                   .norm());
    }
  std::printf("  %u cell centres moved with their ply: another yarn at %u, "
              "another section at %u (0); section radius within %.2g, "
              "fibre direction within %.2g (1e-12): %s\n",
              points,
              yarn_differs,
              section_differs,
              radius_error,
              direction_error,
              yes_no[yarn_differs == 0 && section_differs == 0 &&
                     radius_error <= 1e-12 && direction_error <= 1e-12]);

  // Every yarn's position across its axis against the stack's geometry.
  bool positions = true;
  for (unsigned int id = 0; id < shifted_patch.n_yarns(); ++id)
    {
      const unsigned int p = shifted_patch.ply(id);
      const bool warp      = shifted_patch.is_warp(id);
      const double n       = warp ? g.n_warp : g.n_weft;
      const double expected =
        (shifted_patch.index_in_family(id) - 0.5 * (n - 1.)) * g.spacing +
        p * (warp ? shifted.ply_offset_z : shifted.ply_offset_x);
      positions =
        positions && std::abs(shifted_patch.position(id) - expected) <= 1e-18;
    }
  std::printf("  every yarn's position across its axis that of the stack's "
              "geometry, its ply's shift included: %s\n",
              yes_no[positions]);

  // A symmetry plane with shifted plies.
  Fabric::WovenPatchGeometry mirrored = shifted;
  mirrored.n_warp = mirrored.n_weft = 3;
  mirrored.mirror_x                 = true;
  bool refused                      = false;
  try
    {
      const Fabric::WovenPatch patch(mirrored);
    }
  catch (const std::invalid_argument &e)
    {
      refused = true;
      std::printf("  with a symmetry plane: refused (%s)\n", e.what());
    }
  if (!refused)
    std::printf("  with a symmetry plane: NOT refused\n");
  return 0;
}
