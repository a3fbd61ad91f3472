// The clamps' finite grip (Fabric::ClampGrip, doc/fabric.md section 11)
// against the closed form of a spring with Coulomb's cap. One straight
// yarn end, a box of 2 x 2 x 2 cells (h = 0.1 mm along x, the section
// 0.1 x 0.4 mm), its face x = 0.2 mm gripped, pull-out force F = 10 N:
// - the default stiffness is E A / h and the grip's stable step alone
//   sqrt(2) h / c (c = sqrt(E / rho));
// - the end section pulled along x by u up to u_max = 3 F / k, then back
//   by 1.5 F / k: the total force is k u while k u < F, then F; unloaded,
//   F - k (u_max - u), down to -F / 2, short of slipping back; the slip
//   max(0, u - F / k) stays on unloading; the dissipation is F times the
//   slip, the stored energy f^2 / (2 k);
// - pulled along z, in the fabric's plane, the same cap holds; along y,
//   the normal the jaws press along, the spring holds whatever the force;
// - the half of the section z >= 0 (Symmetry: its mirror z < 0) carries
//   half the whole's force, and energy() scaled by 2 is the whole's.

#include <yarn_impact/fabric/clamp_grip.h>

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace YarnImpact;

namespace
{
  const double h = 0.1e-3, E = 80e9, rho = 1440., F = 10.;
  const unsigned int gripped = 5;

  /** The box yarn end, its section z in [z0, 0.2 mm]; the face x = 2 h
   * gripped. */
  void
  make_end(dealii::Triangulation<3> &mesh, const double z0)
  {
    dealii::GridGenerator::subdivided_hyper_rectangle(
      mesh,
      {2, 2, z0 < 0. ? 2u : 1u},
      dealii::Point<3>(0., -0.05e-3, z0),
      dealii::Point<3>(2 * h, 0.05e-3, 0.2e-3));
    for (const auto &cell : mesh.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() &&
            std::abs(cell->face(f)->center()[0] - 2 * h) < 1e-12)
          cell->face(f)->set_boundary_id(gripped);
  }

  /** A grip on the end of section z >= @p z0 and its nodes' reference
   * positions. */
  struct End
  {
    dealii::Triangulation<3> mesh;
    std::unique_ptr<Fabric::ClampGrip> grip;
    std::vector<double> x;
    std::vector<unsigned int> nodes;

    End(const double z0, const bool half)
    {
      make_end(mesh, z0);
      Fabric::ClampGripParameters p;
      p.pull_out_force = F;
      p.mirror_z       = half;
      grip             = std::make_unique<Fabric::ClampGrip>(p,
                                                 mesh,
                                                 gripped,
                                                 rho,
                                                 half ? 2. : 1.);
      grip->set_axial_modulus(E);
      std::vector<double> reference;
      for (const auto &v : mesh.get_vertices())
        for (unsigned int d = 0; d < 3; ++d)
          reference.push_back(v[d]);
      nodes = grip->setup(reference, MPI_COMM_WORLD);
      for (const unsigned int n : nodes)
        for (unsigned int d = 0; d < 3; ++d)
          x.push_back(reference[3 * n + d]);
    }

    /** The total force [N] along @p d on the nodes moved by @p u along
     * @p d from their reference positions. */
    double
    pull(const double u, const unsigned int d, std::vector<double> &X0)
    {
      std::vector<double> y = X0, v(y.size(), 0.), f(y.size(), 0.);
      for (unsigned int i = d; i < y.size(); i += 3)
        y[i] += u;
      grip->add_forces(y, v, 1e-9, f);
      double total = 0.;
      for (unsigned int i = d; i < f.size(); i += 3)
        total -= f[i];
      return total;
    }
  };

  bool
  near(const double a, const double b, const double tol = 1e-12)
  {
    return std::abs(a - b) <= tol * std::max(std::abs(b), 1e-300);
  }
} // namespace


int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double A = 0.1e-3 * 0.4e-3, k = E * A / h;

  End whole(-0.2e-3, false);
  std::printf("gripped nodes: %u (9 expected)\n",
              static_cast<unsigned int>(whole.nodes.size()));
  // The stiffness from a tiny pull, and the stable step.
  const double u_small   = 1e-3 * F / k;
  std::vector<double> X0 = whole.x;
  {
    End probe(-0.2e-3, false);
    const double f = probe.pull(u_small, 0, X0);
    // The nodes' positions round off 1e-20 m of the 3e-10 m pull.
    std::printf("default stiffness E A / h: %s\n",
                near(f / u_small, k, 1e-8) ? "OK" : "FAILED");
  }
  std::printf("stable step alone sqrt(2) h / c: %s\n",
              near(whole.grip->stable_time_step(),
                   std::sqrt(2.) * h / std::sqrt(E / rho))
                ? "OK"
                : "FAILED");

  // Along x: load to 3 F / k, unload to F / k.
  bool stick = true, slip = true, unload = true, energy = true;
  const double u_max = 3. * F / k;
  for (int s = 0; s <= 55; ++s)
    {
      const double u =
        s <= 40 ? u_max * s / 40. : u_max - (s - 40) * F / k / 10.;
      const double f = whole.pull(u, 0, X0);
      double expected, slipped;
      if (s <= 40)
        {
          expected = std::min(k * u, F);
          slipped  = std::max(0., u - F / k);
          (k * u < F ? stick : slip) &=
            near(f, expected) &&
            near(whole.grip->largest_slip() + 1e-300, slipped + 1e-300, 1e-9);
        }
      else
        {
          expected = F - k * (u_max - u);
          slipped  = u_max - F / k;
          // The force passes through 0: to 1e-9 of F.
          unload &= std::abs(f - expected) <= 1e-9 * F &&
                    near(whole.grip->largest_slip(), slipped, 1e-9);
        }
      energy &= near(whole.grip->energy(), f * f / (2. * k), 1e-9) &&
                near(whole.grip->dissipated(), F * slipped, 1e-9);
    }
  std::printf("pulled along x, sticking: force k u, no slip: %s\n",
              stick ? "OK" : "FAILED");
  std::printf("pulled along x, slipping: force F, slip u - F / k: %s\n",
              slip ? "OK" : "FAILED");
  std::printf("unloaded: force F - k (u_max - u), the slip kept: %s\n",
              unload ? "OK" : "FAILED");
  std::printf("stored energy f^2 / (2 k), dissipation F times the slip: %s\n",
              energy ? "OK" : "FAILED");
  std::printf("slipping yarn ends: %u (1 expected)\n",
              whole.grip->n_slipping_ends());

  // Across: fresh grips, pulled along z and along y past the cap.
  End along_z(-0.2e-3, false), along_y(-0.2e-3, false);
  std::vector<double> Z0 = along_z.x, Y0 = along_y.x;
  const double fz_small = along_z.pull(0.5 * F / k, 2, Z0);
  const double fz_large = along_z.pull(4. * F / k, 2, Z0);
  std::printf("pulled along z: k u below the cap, F above: %s\n",
              near(fz_small, 0.5 * F, 1e-9) && near(fz_large, F, 1e-9)
                ? "OK"
                : "FAILED");
  const double fy_large = along_y.pull(4. * F / k, 1, Y0);
  std::printf("pulled along y: k u past the cap, no slip: %s\n",
              near(fy_large, 4. * F, 1e-9) && along_y.grip->largest_slip() == 0.
                ? "OK"
                : "FAILED");

  // The half section z >= 0 of a model mirrored about z = 0.
  End half(0., true);
  std::vector<double> H0    = half.x;
  const double f_half_stick = half.pull(0.5 * F / k, 0, H0);
  End whole_again(-0.2e-3, false);
  std::vector<double> W0 = whole_again.x;
  whole_again.pull(0.5 * F / k, 0, W0);
  const double f_half_slip = half.pull(2. * F / k, 0, H0);
  std::printf("half section: %u nodes, force k u / 2 sticking, F / 2 "
              "slipping: %s\n",
              static_cast<unsigned int>(half.nodes.size()),
              near(f_half_stick, 0.25 * F) && near(f_half_slip, 0.5 * F)
                ? "OK"
                : "FAILED");
  whole_again.pull(2. * F / k, 0, W0);
  std::printf("half section: energy() and dissipated() scaled by 2 are the "
              "whole's: %s\n",
              near(half.grip->energy(), whole_again.grip->energy(), 1e-12) &&
                  near(half.grip->dissipated(),
                       whole_again.grip->dissipated(),
                       1e-12)
                ? "OK"
                : "FAILED");
  return 0;
}
