// The yarn contact's tie rule (Fabric::YarnContact, doc/fabric.md section
// 10): a node over an edge whose two faces it penetrates equally is shared
// equally among them. Yarn 0 is a roof, its top two faces meeting at a
// ridge along z at x = 0 with slopes -s and +s; yarn 1 is a block whose
// bottom lies d below the ridge, so that only its nodes on x = 0 (and the
// ridge's nodes, inside yarn 1's flat bottom) penetrate. Checks, against
// the mirror symmetry of the set-up (an exact identity):
// (a) each of yarn 1's nodes on x = 0 is pushed up, along the ridge's plane
//     of symmetry: |f_x| below 1e-12 of |f_y| (taking one face alone, as a
//     rule without ties does, leaves |f_x| / |f_y| = s);
// (b) the forces on the two yarns equal and opposite, to 1e-14 of them;
// (c) the same forces, node by node (matched by position) within 1e-14 of
//     the largest, when the roof's two cells are numbered in the other
//     order (the tie does not depend on the faces' order).

#include <yarn_impact/fabric/yarn_contact.h>

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

using namespace YarnImpact;
using dealii::Point;

namespace
{
  const double a = 1e-3, w = 0.5e-3, h = 0.2e-3; // block sizes [m]
  const double s = 0.2;                          // the roof's slope [-]
  const double d = 1e-6;                         // the ridge's depth [m]

  /** One half of the roof: the cell between x0 and x1 (one of them 0),
   * its top at y = -s |x|. */
  void
  roof_half(dealii::Triangulation<3> &t, const double x0, const double x1)
  {
    dealii::GridGenerator::subdivided_hyper_rectangle(t,
                                                      {1, 1, 1},
                                                      Point<3>(x0, -h, 0.),
                                                      Point<3>(x1, 0., w));
    dealii::GridTools::transform(
      [](const Point<3> &p) {
        return p[1] == 0. ? Point<3>(p[0], -s * std::abs(p[0]), p[2]) : p;
      },
      t);
  }

  /** The roof (yarn 0, its halves merged left first or right first) and
   * the block above it (yarn 1, two cells across x = 0, bottom at -d). */
  Fabric::ContactSurface
  roof_and_block(const bool left_first)
  {
    dealii::Triangulation<3> left, right, roof, block, both;
    roof_half(left, -0.5 * a, 0.);
    roof_half(right, 0., 0.5 * a);
    if (left_first)
      dealii::GridGenerator::merge_triangulations(left, right, roof);
    else
      dealii::GridGenerator::merge_triangulations(right, left, roof);
    dealii::GridGenerator::subdivided_hyper_rectangle(
      block,
      {2, 1, 1},
      Point<3>(-0.5 * a, -d, 0.),
      Point<3>(0.5 * a, h - d, w));
    for (const auto &cell : block.active_cell_iterators())
      cell->set_material_id(1);
    dealii::GridGenerator::merge_triangulations(roof, block, both);
    return Fabric::make_contact_surface(both, 1440.);
  }

  /** The contact forces [N] on every node of @p surface, the block
   * pressed onto the roof by d in the step. */
  std::vector<double>
  forces(const Fabric::ContactSurface &surface)
  {
    std::vector<unsigned int> owned(surface.n_nodes());
    std::iota(owned.begin(), owned.end(), 0);
    Fabric::YarnContactParameters prm;
    Fabric::YarnContact contact(prm, surface, owned, MPI_COMM_SELF);
    std::vector<double> x(3 * surface.n_nodes()), v(x.size(), 0.),
      f(x.size(), 0.);
    for (unsigned int i = 0; i < surface.n_nodes(); ++i)
      for (unsigned int c = 0; c < 3; ++c)
        x[3 * i + c] = surface.reference[i][c];
    // The block pressed down by d in the step (a contact's spring starts
    // at the depth its node had before the step).
    const double dt = 1e-9;
    for (unsigned int i = 0; i < surface.n_nodes(); ++i)
      if (surface.node_yarn[i] == 1)
        v[3 * i + 1] = -d / dt;
    contact.add_forces(x, v, dt, f);
    return f;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const char *yes_no[] = {"no", "yes"};

  const Fabric::ContactSurface one = roof_and_block(true),
                               two = roof_and_block(false);
  const std::vector<double> f1 = forces(one), f2 = forces(two);

  // (a) The block's nodes on the ridge's plane.
  bool along_plane      = true;
  unsigned int on_ridge = 0;
  double largest        = 0.;
  for (unsigned int i = 0; i < one.n_nodes(); ++i)
    {
      largest = std::max(largest, std::abs(f1[3 * i + 1]));
      if (one.node_yarn[i] == 1 && one.reference[i][0] == 0. &&
          one.reference[i][1] == -d)
        {
          ++on_ridge;
          along_plane = along_plane && f1[3 * i + 1] > 0. &&
                        std::abs(f1[3 * i]) < 1e-12 * std::abs(f1[3 * i + 1]);
        }
    }
  std::printf("(a) %u nodes of the block over the ridge, pushed up along "
              "the plane x = 0 (|f_x| < 1e-12 |f_y|): %s\n",
              on_ridge,
              yes_no[on_ridge == 2 && along_plane && largest > 0.]);

  // (b) Equal and opposite.
  double sum[2][3] = {};
  for (unsigned int i = 0; i < one.n_nodes(); ++i)
    for (unsigned int c = 0; c < 3; ++c)
      sum[one.node_yarn[i]][c] += f1[3 * i + c];
  bool opposite = true;
  for (unsigned int c = 0; c < 3; ++c)
    opposite = opposite && std::abs(sum[0][c] + sum[1][c]) < 1e-14 * largest;
  std::printf("(b) the yarns' forces equal and opposite: %s\n",
              yes_no[opposite && sum[1][1] > 0.]);

  // (c) The roof's cells in the other order.
  bool same = one.n_nodes() == two.n_nodes();
  for (unsigned int i = 0; same && i < one.n_nodes(); ++i)
    {
      unsigned int j = 0;
      while (j < two.n_nodes() && !(two.reference[j] == one.reference[i] &&
                                    two.node_yarn[j] == one.node_yarn[i]))
        ++j;
      same = j < two.n_nodes();
      for (unsigned int c = 0; same && c < 3; ++c)
        same = std::abs(f1[3 * i + c] - f2[3 * j + c]) < 1e-14 * largest;
    }
  std::printf("(c) the same forces with the roof's cells in the other "
              "order: %s\n",
              yes_no[same]);
}
