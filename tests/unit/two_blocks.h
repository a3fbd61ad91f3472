// Two blocks of yarn pressed together, the yarn contact's unit tests'
// set-up (yarn_contact.cc, yarn_contact_free_ends.cc,
// yarn_contact_erosion.cc).

#ifndef yarn_impact_tests_two_blocks_h
#define yarn_impact_tests_two_blocks_h

#include <deal.II/base/point.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <vector>

/**
 * Into @p both: block 0 (yarn 0) of a x h x w [m] below, its top at
 * y = @p top0 [m], subdivided @p n0; block 1 (yarn 1) above, its bottom at
 * y = 0, of (a + 2 m) x h x (w + 2 m), m = @p margin1 [m], from x = z = -m,
 * subdivided @p n1.
 */
inline void
two_blocks(dealii::Triangulation<3> &both,
           const double a,
           const double h,
           const double w,
           const double top0,
           const std::vector<unsigned int> &n0,
           const std::vector<unsigned int> &n1,
           const double margin1 = 0.)
{
  using dealii::Point;
  dealii::Triangulation<3> lower, upper;
  dealii::GridGenerator::subdivided_hyper_rectangle(lower,
                                                    n0,
                                                    Point<3>(0., top0 - h, 0.),
                                                    Point<3>(a, top0, w));
  dealii::GridGenerator::subdivided_hyper_rectangle(
    upper,
    n1,
    Point<3>(-margin1, 0., -margin1),
    Point<3>(a + margin1, h, w + margin1));
  for (const auto &cell : upper.active_cell_iterators())
    cell->set_material_id(1);
  dealii::GridGenerator::merge_triangulations(lower, upper, both);
}

#endif
