// The eroding yarn contact (Fabric::YarnContact::remove_cells(),
// doc/fe-model.md section 8.4, "Failed cells"): a block (yarn 1, 4 x 1 x 3
// cells, a x h x w) pressed by d = 1 um, in one step, onto the lateral face
// of another (yarn 0), both sides slaves at half the penalty p.
// (a) Before any removal the normal force on each block is p d a w
//     (closed form), equal and opposite.
// (b) The cells of yarn 1 with x < a/2 fail (remove_cells()): in the next
//     evaluation at the same positions the contacts that lost their faces
//     or their node end, and the energy their springs held goes to the
//     dissipated work, so that stored plus dissipated is unchanged to
//     round-off (no velocity: no damping or slip work); the forces still
//     balance; the nodes of yarn 1 whose faces all failed carry no force;
//     the faces left out are the 6 bottom and 6 top faces of the failed
//     cells and the sides among them (the surface's faces of those cells,
//     counted from the mesh). Without the hand-over the sum would fall by
//     the ended contacts' energy, which the test prints.
// (c) A restart after the failure (see below) gives the uninterrupted
//     contact's forces, energy and dissipated work bit for bit.
// (d) A fresh contact whose cells with x < a/2 failed before the press
//     (remove_cells(..., restored = true): nothing handed): the force is
//     p d w (a/2 + a/16), the remaining half of the face plus the strip of
//     half a cell that the lower block's nodes on the line x = a/2 bring
//     (their area is not reduced: their own faces are whole), within
//     1e-12.

#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/fabric/yarn_contact.h>

#include <deal.II/base/mpi.h>
#include <deal.II/grid/tria.h>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

#include "two_blocks.h"

using namespace YarnImpact;

namespace
{
  const double a = 1e-3, w = 0.6e-3, h = 0.2e-3, d = 1e-6, dt = 1e-9;

  /** The reference positions of the vertices of yarn 1's cells with
   * x < a/2, 24 values a cell, and the number of their boundary faces. */
  std::vector<double>
  failed_cells(const dealii::Triangulation<3> &mesh, unsigned int &faces)
  {
    std::vector<double> cells;
    faces = 0;
    for (const auto &cell : mesh.active_cell_iterators())
      if (cell->material_id() == 1 && cell->center()[0] < 0.5 * a)
        {
          for (unsigned int v = 0; v < 8; ++v)
            for (unsigned int c = 0; c < 3; ++c)
              cells.push_back(cell->vertex(v)[c]);
          for (const auto &face : cell->face_iterators())
            faces += face->at_boundary();
        }
    return cells;
  }

  /** Positions at the press, and velocities that bring yarn 1 down by d
   * in the step (@p moving) or none. */
  void
  state(const Fabric::ContactSurface &s,
        const bool moving,
        std::vector<double> &x,
        std::vector<double> &v)
  {
    x.assign(3 * s.n_nodes(), 0.);
    v.assign(x.size(), 0.);
    for (unsigned int i = 0; i < s.n_nodes(); ++i)
      for (unsigned int c = 0; c < 3; ++c)
        x[3 * i + c] = s.reference[i][c];
    if (moving)
      for (unsigned int i = 0; i < s.n_nodes(); ++i)
        if (s.node_yarn[i] == 1)
          v[3 * i + 1] = -d / dt;
  }

  /** The y forces [N] on yarn 0 and yarn 1 in @p f, and the largest |f|
   * on a node of yarn 1 whose x is below a/2 - a/8 (its faces all
   * failed). */
  void
  sums(const Fabric::ContactSurface &s,
       const std::vector<double> &f,
       double &f0,
       double &f1,
       double &failed_node_force)
  {
    f0 = f1 = failed_node_force = 0.;
    for (unsigned int i = 0; i < s.n_nodes(); ++i)
      {
        (s.node_yarn[i] == 0 ? f0 : f1) += f[3 * i + 1];
        if (s.node_yarn[i] == 1 && s.reference[i][0] < 0.5 * a - 0.125 * a)
          for (unsigned int c = 0; c < 3; ++c)
            failed_node_force =
              std::max(failed_node_force, std::abs(f[3 * i + c]));
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const char *yes_no[] = {"no", "yes"};
  Fabric::YarnContactParameters prm;
  prm.penalty    = 5e13;
  prm.friction   = 0.2;
  const double N = prm.penalty * d * a * w;

  // Yarn 1 on top of yarn 0, pressed by d (its bottom at y = 0, yarn 0's
  // top at y = d).
  dealii::Triangulation<3> both;
  two_blocks(both, a, h, w, d, {4, 1, 3}, {4, 1, 3});
  const Fabric::ContactSurface s = Fabric::make_contact_surface(both, 1440.);
  std::vector<unsigned int> owned(s.n_nodes());
  std::iota(owned.begin(), owned.end(), 0);
  unsigned int failed_faces        = 0;
  const std::vector<double> failed = failed_cells(both, failed_faces);
  std::printf("blocks of %.1f x %.1f mm pressed by d = 1 um, p = 5e13 Pa/m: "
              "p d a w = %.6f N; 6 cells of yarn 1 fail (x < a/2), %u of "
              "their faces on the surface\n",
              a * 1e3,
              w * 1e3,
              N,
              failed_faces);

  // (a) and (b): pressed, then half of yarn 1 fails.
  {
    Fabric::YarnContact contact(prm, s, owned, MPI_COMM_SELF);
    std::vector<double> x, v, f(3 * s.n_nodes(), 0.);
    state(s, true, x, v);
    contact.add_forces(x, v, dt, f);
    double f0, f1, free_force;
    sums(s, f, f0, f1, free_force);
    const double stored = contact.energy(), work = contact.dissipated();
    std::printf(
      "(a) pressed: force on yarn 0 %.9f N, on yarn 1 %.9f N; "
      "p d a w within 1e-12 and opposite to 1e-14: %s\n",
      f0,
      f1,
      yes_no[std::abs(-f0 - N) < 1e-12 * N && std::abs(f0 + f1) < 1e-14 * N]);

    contact.remove_cells(failed, false);
    state(s, false, x, v);
    std::fill(f.begin(), f.end(), 0.);
    contact.add_forces(x, v, dt, f);
    sums(s, f, f0, f1, free_force);
    const double stored_after = contact.energy(),
                 work_after   = contact.dissipated();
    const double handed       = work_after - work;
    std::printf("(b) after the failure: %u faces left out (all of the "
                "failed cells' faces: %s); stored %.6e J -> %.6e J, "
                "dissipated %.6e J -> %.6e J\n",
                contact.n_removed_faces(),
                yes_no[contact.n_removed_faces() == failed_faces],
                stored,
                stored_after,
                work,
                work_after);
    std::printf("    stored + dissipated unchanged within 1e-12: %s "
                "(without the hand-over it would fall by %.1f %%)\n",
                yes_no[std::abs(stored_after + work_after - stored - work) <
                       1e-12 * stored],
                100. * handed / stored);
    std::printf("    forces balanced to 1e-14: %s; nodes of yarn 1 whose "
                "faces all failed free of force: %s; yarn 1 still pressed "
                "(force on yarn 0 %.6f N): %s\n",
                yes_no[std::abs(f0 + f1) < 1e-14 * N],
                yes_no[free_force == 0.],
                f0,
                yes_no[-f0 > 0.25 * N && -f0 < 0.75 * N]);
  }

  // (c) A restart after the failure: A pressed, half of yarn 1 failed,
  // evaluated, then yarn 1 lifted by 2 d so that every contact ends; B
  // restored from A's checkpoint before the lift, told the failed cells
  // again as a restart does (restored = true). B's forces, energy and
  // dissipated work after the lift are A's bit for bit; told them as new
  // (restored = false) it would hand the springs that still pressed the
  // removed faces' neighbours once more, which the test prints.
  {
    Fabric::YarnContact A(prm, s, owned, MPI_COMM_SELF);
    std::vector<double> x, v, f(3 * s.n_nodes(), 0.);
    state(s, true, x, v);
    A.add_forces(x, v, dt, f);
    A.remove_cells(failed, false);
    state(s, false, x, v);
    A.add_forces(x, v, dt, f);
    Checkpoint::Writer out;
    A.save(out);
    // The lift: every contact ends (no velocity, so no damping or slip).
    for (unsigned int i = 0; i < s.n_nodes(); ++i)
      if (s.node_yarn[i] == 1)
        x[3 * i + 1] += 2. * d;
    std::vector<double> fa(f.size(), 0.);
    A.add_forces(x, v, dt, fa);
    double work[2];
    for (const bool restored : {true, false})
      {
        Fabric::YarnContact B(prm, s, owned, MPI_COMM_SELF);
        Checkpoint::Reader in("memory", out.contents());
        B.load(in);
        B.remove_cells(failed, restored);
        std::vector<double> fb(f.size(), 0.);
        B.add_forces(x, v, dt, fb);
        work[restored ? 0 : 1] = B.dissipated();
        if (restored)
          std::printf("(c) restarted after the failure, then lifted: forces, "
                      "energy and dissipated work the uninterrupted "
                      "contact's bit for bit: %s (dissipated %.6e J)\n",
                      yes_no[fb == fa && B.energy() == A.energy() &&
                             B.dissipated() == A.dissipated()],
                      B.dissipated());
      }
    std::printf("    told the failed cells as new after the restart: "
                "dissipated %.6e J (%s)\n",
                work[1],
                work[1] != work[0] ? "differs" : "the same");
  }

  // (d) Failed before the press: the force of the remaining surface.
  {
    Fabric::YarnContact contact(prm, s, owned, MPI_COMM_SELF);
    contact.remove_cells(failed, true);
    std::vector<double> x, v, f(3 * s.n_nodes(), 0.);
    state(s, true, x, v);
    contact.add_forces(x, v, dt, f);
    double f0, f1, free_force;
    sums(s, f, f0, f1, free_force);
    const double expected = prm.penalty * d * w * (0.5 * a + a / 16.);
    std::printf("(d) failed before the press: force on yarn 0 %.9f N, "
                "p d w (a/2 + a/16) = %.9f N; within 1e-12: %s; nothing "
                "dissipated: %s\n",
                f0,
                -expected,
                yes_no[std::abs(-f0 - expected) < 1e-12 * expected],
                yes_no[contact.dissipated() == 0.]);
  }
  return 0;
}
