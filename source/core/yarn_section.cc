#include <yarn_impact/core/yarn_section.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <cmath>
#include <set>

namespace YarnImpact
{
  using namespace dealii;

  void
  create_yarn_section(Triangulation<2, 2> &section,
                      const double a_y,
                      const double a_z,
                      const unsigned int refinements,
                      const bool half_section,
                      const bool preserve_area)
  {
    Triangulation<2> disk;
    GridGenerator::hyper_ball_balanced(disk, Point<2>(), 1.);
    disk.refine_global(refinements);

    Triangulation<2> flat;
    flat.copy_triangulation(disk);
    if (half_section)
      {
        std::set<Triangulation<2>::active_cell_iterator> removed;
        for (const auto &cell : flat.active_cell_iterators())
          if (cell->center()[1] < 0.)
            removed.insert(cell);
        Triangulation<2> half;
        GridGenerator::create_triangulation_with_removed_cells(flat,
                                                               removed,
                                                               half);
        flat.clear();
        flat.copy_triangulation(half);
      }
    GridTools::transform(
      [a_y, a_z](const Point<2> &p) {
        return Point<2>(a_y * p[0], a_z * p[1]);
      },
      flat);
    if (preserve_area)
      {
        const double ellipse =
          (half_section ? 0.5 : 1.) * numbers::PI * a_y * a_z;
        const double k = std::sqrt(ellipse / GridTools::volume(flat));
        GridTools::scale(k, flat);
      }
    // Keep only the geometry: the manifolds of the unit disk do not
    // describe the ellipse.
    flat.reset_all_manifolds();
    flat.set_all_manifold_ids(numbers::flat_manifold_id);

    // Flatten to a coarse mesh (no hierarchy) for the extrusion.
    section.clear();
    GridGenerator::flatten_triangulation(flat, section);
  }
} // namespace YarnImpact
