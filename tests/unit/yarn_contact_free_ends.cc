// The yarn contact's surface holds the free ends (Fabric::
// yarn_contact_boundary_ids(), doc/fe-model.md section 8.4), checked two
// ways:
// (a) topology: on a 3 x 3 woven patch (Fabric::WovenPatch, spacing 1 mm,
//     8 cells per spacing) whose warp yarns have free ends and whose weft
//     yarns are clamped, each warp yarn's surface is closed (every
//     directed edge of its faces is met once, and its reverse once: a
//     watertight surface with its normals all out of the yarn), and a
//     weft yarn's surface is open only along its two clamped end
//     sections (every node of an edge not closed is a node of a face with
//     the clamped id, BoundaryIds::end). The
//     lateral faces alone leave each warp yarn open at its ends, which
//     the test prints, so that the check can fail.
// (b) physics: a block (yarn 1) standing with its free end section on
//     the lateral face of another (yarn 0), pressed by d = 1 um: the
//     normal force on each is p d A, A the end section's area (both
//     sides slaves at half the penalty), equal and opposite, within
//     1e-12; its clamped top section is not in the surface. Without the
//     free end the force is not p d A.

#include <yarn_impact/fabric/woven_patch.h>
#include <yarn_impact/fabric/yarn_contact.h>

#include <deal.II/base/mpi.h>
#include <deal.II/grid/tria.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <set>
#include <utility>

#include "two_blocks.h"

using namespace YarnImpact;

namespace
{
  const double density = 1440.; // [kg/m^3]

  /** The surface of @p mesh that the fabric's yarn contact takes, with
   * the free ends (@p with_free_ends) or, as before them, of the lateral
   * faces alone. */
  Fabric::ContactSurface
  surface(const dealii::Triangulation<3> &mesh, const bool with_free_ends)
  {
    return Fabric::make_contact_surface(mesh,
                                        density,
                                        with_free_ends
                                          ? Fabric::yarn_contact_boundary_ids()
                                          : std::set<unsigned int>{
                                              Fabric::BoundaryIds::lateral});
  }

  /** For each yarn of @p s: the directed edges of its faces met other
   * than exactly once with their reverse once (0 for a closed surface),
   * and the nodes of the edges met once, the open rim. */
  std::map<unsigned int, std::pair<unsigned int, std::vector<unsigned int>>>
  open_edges(const Fabric::ContactSurface &s)
  {
    std::map<unsigned int, std::map<std::pair<unsigned int, unsigned int>, int>>
      directed;
    for (unsigned int f = 0; f < s.faces.size(); ++f)
      for (unsigned int e = 0; e < 4; ++e)
        ++directed[s.face_yarn[f]][{s.faces[f][e], s.faces[f][(e + 1) % 4]}];
    std::map<unsigned int, std::pair<unsigned int, std::vector<unsigned int>>>
      result;
    for (const auto &[yarn, edges] : directed)
      {
        auto &r = result[yarn];
        for (const auto &[edge, count] : edges)
          {
            const auto reverse = edges.find({edge.second, edge.first});
            if (count != 1 || reverse == edges.end() || reverse->second != 1)
              {
                ++r.first;
                r.second.push_back(edge.first);
                r.second.push_back(edge.second);
              }
          }
      }
    return result;
  }

  /** Whether yarn @p yarn of @p s runs along x (a warp yarn). */
  bool
  along_x(const Fabric::ContactSurface &s, const unsigned int yarn)
  {
    double lo[3] = {1., 1., 1.}, hi[3] = {-1., -1., -1.};
    for (unsigned int i = 0; i < s.n_nodes(); ++i)
      if (s.node_yarn[i] == yarn)
        for (unsigned int d = 0; d < 3; ++d)
          {
            lo[d] = std::min(lo[d], s.reference[i][d]);
            hi[d] = std::max(hi[d], s.reference[i][d]);
          }
    return hi[0] - lo[0] > hi[2] - lo[2];
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const char *yes_no[] = {"no", "yes"};

  // (a) The woven patch: warp ends free, weft ends clamped.
  {
    Fabric::WovenPatchGeometry g;
    g.n_warp = g.n_weft = 3;
    g.clamp_warp_ends   = false;
    dealii::Triangulation<3> mesh;
    Fabric::WovenPatch(g).create_mesh(mesh);
    // The nodes of the clamped end sections, by position.
    std::set<std::array<double, 3>> clamped;
    for (const auto &X :
         Fabric::make_contact_surface(mesh, density, {Fabric::BoundaryIds::end})
           .reference)
      clamped.insert({{X[0], X[1], X[2]}});
    std::printf("(a) 3 x 3 patch, warp ends free, weft ends clamped (%zu "
                "nodes on their end sections)\n",
                clamped.size());
    for (const bool with_free_ends : {true, false})
      {
        const auto s = surface(mesh, with_free_ends);
        std::printf("  %s: %zu faces\n",
                    with_free_ends ? "yarn_contact_boundary_ids()"
                                   : "lateral faces only",
                    s.faces.size());
        bool warp_closed = true, weft_rims_clamped = true;
        unsigned int warp_open = 0;
        for (const auto &[yarn, open] : open_edges(s))
          if (along_x(s, yarn))
            {
              warp_closed = warp_closed && open.first == 0;
              warp_open += open.first;
            }
          else
            for (const unsigned int i : open.second)
              weft_rims_clamped =
                weft_rims_clamped && clamped.count({{s.reference[i][0],
                                                     s.reference[i][1],
                                                     s.reference[i][2]}}) == 1;
        std::printf("    warp yarns (free ends): edges not closed %u; "
                    "closed: %s\n",
                    warp_open,
                    yes_no[warp_closed]);
        std::printf("    weft yarns (clamped): open only at the clamped "
                    "sections: %s\n",
                    yes_no[weft_rims_clamped]);
      }
  }

  // (b) A free end pressed on a lateral face.
  {
    const double a = 1e-3, w = 0.5e-3, h = 0.2e-3, d = 1e-6;
    Fabric::YarnContactParameters prm;
    prm.penalty    = 5e13;
    prm.friction   = 0.2;
    const double N = prm.penalty * d * a * w;
    dealii::Triangulation<3> both;
    two_blocks(both, a, h, w, d, {4, 1, 3}, {4, 1, 3});
    // Yarn 1 stands along y: its section y = 0 is a free end, y = h a
    // clamped end; every other boundary face is lateral.
    unsigned int clamped_faces = 0, boundary_faces = 0;
    for (const auto &cell : both.active_cell_iterators())
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          {
            ++boundary_faces;
            unsigned int id = Fabric::BoundaryIds::lateral;
            if (cell->material_id() == 1 && std::abs(face->center()[1]) < 1e-9)
              id = Fabric::free_end_boundary_id;
            else if (cell->material_id() == 1 &&
                     std::abs(face->center()[1] - h) < 1e-9)
              {
                id = Fabric::BoundaryIds::end;
                ++clamped_faces;
              }
            face->set_boundary_id(id);
          }
    std::printf("(b) a free end section of %.1f x %.1f mm pressed by "
                "d = 1 um on a lateral face, p = 5e13 Pa/m: p d A = %.6f N\n",
                a * 1e3,
                w * 1e3,
                N);
    for (const bool with_free_ends : {true, false})
      {
        const auto s = surface(both, with_free_ends);
        std::vector<unsigned int> owned(s.n_nodes());
        std::iota(owned.begin(), owned.end(), 0);
        Fabric::YarnContact contact(prm, s, owned, MPI_COMM_SELF);
        std::vector<double> x(3 * s.n_nodes()), v(x.size(), 0.),
          f(x.size(), 0.);
        for (unsigned int i = 0; i < s.n_nodes(); ++i)
          for (unsigned int c = 0; c < 3; ++c)
            x[3 * i + c] = s.reference[i][c];
        // Pressed by d in the step (a contact's spring starts at the
        // depth its node had before the step).
        for (unsigned int i = 0; i < s.n_nodes(); ++i)
          if (s.node_yarn[i] == 1)
            v[3 * i + 1] = -d / 1e-9;
        contact.add_forces(x, v, 1e-9, f);
        double f0 = 0., f1 = 0.;
        for (unsigned int i = 0; i < s.n_nodes(); ++i)
          (s.node_yarn[i] == 0 ? f0 : f1) += f[3 * i + 1];
        std::printf("  %s: %zu of %u boundary faces; force on the lateral "
                    "face's yarn %.9f N, on the free end's %.9f N\n",
                    with_free_ends ? "yarn_contact_boundary_ids()"
                                   : "lateral faces only",
                    s.faces.size(),
                    boundary_faces,
                    f0,
                    f1);
        if (with_free_ends)
          std::printf(
            "    clamped section left out: %s; p d A within 1e-12 and "
            "opposite to 1e-14: %s\n",
            yes_no[s.faces.size() == boundary_faces - clamped_faces],
            yes_no[std::abs(-f0 - N) < 1e-12 * N &&
                   std::abs(f0 + f1) < 1e-14 * N]);
        else
          std::printf("    p d A: %s\n", yes_no[std::abs(-f0 - N) < 1e-3 * N]);
      }
  }
  return 0;
}
