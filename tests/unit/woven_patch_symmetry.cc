// The symmetry planes of the plain-woven patch (Fabric::WovenPatch,
// WovenPatchGeometry::mirror_x and mirror_z; doc/fabric.md section 10), a
// geometry test on 3 x 3 yarns of the paper's section (s = 1 mm, A =
// 0.1 mm, 8 cells per spacing):
// - the whole patch is its own mirror image in x = 0 and in z = 0 (every
//   vertex has an image within 1e-15 m), while the 4 x 4 patch, whose
//   planes x = 0 and z = 0 lie between two yarns, is not (over and under
//   swap: vertices without an image);
// - the half (x <= 0) and quarter (x <= 0, z >= 0) meshes hold 1/2 and 1/4
//   of the cells, their volume and their lateral area times 2 and 4 are
//   the whole's within 1e-12, every vertex of theirs is a vertex of the
//   whole mesh within 1e-15 m on the kept side, and the whole mesh's
//   vertices strictly inside the kept side are all theirs;
// - the faces with the symmetry plane's boundary id lie on the planes, and
//   no lateral face does;
// - the yarns each meshed yarn stands for (copies) add up to the whole
//   patch's yarns;
// - an even number of yarns parallel to a plane is refused.

#include <yarn_impact/fabric/woven_patch.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/tria.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

using namespace YarnImpact;
using dealii::Point;

namespace
{
  /** The vertices of a mesh, binned by 0.1 nm for a search within 1e-15 m
   * (neighbouring bins included). */
  struct Vertices
  {
    std::map<std::array<long, 3>, std::vector<Point<3>>> bins;

    explicit Vertices(const dealii::Triangulation<3> &mesh)
    {
      for (const Point<3> &v : mesh.get_vertices())
        bins[key(v)].push_back(v);
    }
    static std::array<long, 3>
    key(const Point<3> &X)
    {
      return {{std::lround(X[0] / 1e-10),
               std::lround(X[1] / 1e-10),
               std::lround(X[2] / 1e-10)}};
    }
    bool
    has(const Point<3> &X) const
    {
      const auto k = key(X);
      for (long i = -1; i <= 1; ++i)
        for (long j = -1; j <= 1; ++j)
          for (long l = -1; l <= 1; ++l)
            {
              const auto it = bins.find({{k[0] + i, k[1] + j, k[2] + l}});
              if (it != bins.end())
                for (const Point<3> &v : it->second)
                  if (v.distance(X) < 1e-15)
                    return true;
            }
      return false;
    }
  };

  /** Cells, volume [m^3] and lateral area [m^2] of a mesh. */
  std::array<double, 3>
  measures(const dealii::Triangulation<3> &mesh)
  {
    dealii::FE_Q<3> fe(1);
    dealii::QGauss<3> quadrature(2);
    dealii::FEValues<3> values(fe, quadrature, dealii::update_JxW_values);
    double volume = 0., area = 0.;
    for (const auto &cell : mesh.active_cell_iterators())
      {
        values.reinit(cell);
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          volume += values.JxW(q);
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() &&
              face->boundary_id() == Fabric::BoundaryIds::lateral)
            area += face->measure();
      }
    return {{double(mesh.n_active_cells()), volume, area}};
  }

  /** Vertices of @p mesh without a mirror image in the plane normal to
   * coordinate @p d [-]. */
  unsigned int
  without_image(const dealii::Triangulation<3> &mesh, const unsigned int d)
  {
    const Vertices all(mesh);
    unsigned int n = 0;
    for (Point<3> v : mesh.get_vertices())
      {
        v[d] = -v[d];
        n += !all.has(v);
      }
    return n;
  }
} // namespace

int
main()
{
  Fabric::WovenPatchGeometry g;
  g.n_warp = g.n_weft = 3;
  dealii::Triangulation<3> whole_mesh;
  Fabric::WovenPatch(g).create_mesh(whole_mesh);
  const auto whole = measures(whole_mesh);
  std::printf("whole 3 x 3 patch: %.0f cells; vertices without a mirror "
              "image in x = 0: %u, in z = 0: %u (0)\n",
              whole[0],
              without_image(whole_mesh, 0),
              without_image(whole_mesh, 2));
  Fabric::WovenPatchGeometry even = g;
  even.n_warp = even.n_weft = 4;
  dealii::Triangulation<3> even_mesh;
  Fabric::WovenPatch(even).create_mesh(even_mesh);
  const unsigned int even_x = without_image(even_mesh, 0),
                     even_z = without_image(even_mesh, 2);
  std::printf("whole 4 x 4 patch: vertices without a mirror image in "
              "x = 0: %s, in z = 0: %s (some)\n",
              even_x > 0 ? "some" : "NONE",
              even_z > 0 ? "some" : "NONE");

  const Vertices whole_vertices(whole_mesh);
  const double on = 1e-15;
  for (const bool quarter : {false, true})
    {
      Fabric::WovenPatchGeometry r = g;
      r.mirror_x                   = true;
      r.mirror_z                   = quarter;
      const Fabric::WovenPatch patch(r);
      dealii::Triangulation<3> mesh;
      patch.create_mesh(mesh);
      const auto m        = measures(mesh);
      const double factor = quarter ? 4. : 2.;
      // Its vertices are the whole's on the kept side; the whole's inside
      // the kept side are its own.
      unsigned int foreign = 0, missing = 0;
      for (const Point<3> &v : mesh.get_vertices())
        foreign +=
          !whole_vertices.has(v) || v[0] > on || (quarter && v[2] < -on);
      const Vertices own(mesh);
      for (const Point<3> &v : whole_mesh.get_vertices())
        if (v[0] < -on && (!quarter || v[2] > on))
          missing += !own.has(v);
      // The plane's faces on the planes, no lateral face on them.
      unsigned int plane_faces = 0, off_plane = 0, lateral_on = 0;
      for (const auto &cell : mesh.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              bool on_x = true, on_z = true;
              for (const unsigned int k : face->vertex_indices())
                {
                  on_x = on_x && std::abs(face->vertex(k)[0]) < on;
                  on_z = on_z && std::abs(face->vertex(k)[2]) < on;
                }
              const bool on_plane = on_x || (quarter && on_z);
              if (face->boundary_id() == Fabric::symmetry_plane_boundary_id)
                {
                  ++plane_faces;
                  off_plane += !on_plane;
                }
              else if (face->boundary_id() == Fabric::BoundaryIds::lateral)
                lateral_on += on_plane;
            }
      unsigned int copies = 0;
      for (unsigned int id = 0; id < patch.n_yarns(); ++id)
        copies += patch.copies(id);
      const bool ok_measures =
        m[0] * factor == whole[0] &&
        std::abs(m[1] * factor / whole[1] - 1.) < 1e-12 &&
        std::abs(m[2] * factor / whole[2] - 1.) < 1e-12;
      std::printf("%s: %.0f cells (%.0f), volume and lateral area x %.0f "
                  "the whole's within 1e-12: %s; vertices not the whole's "
                  "or off the kept side: %u, the whole's inside it "
                  "missing: %u (0, 0); %u faces on the planes, off them "
                  "%u, lateral faces on them %u (0, 0); copies of the "
                  "yarns %u (6)\n",
                  quarter ? "quarter" : "half",
                  m[0],
                  whole[0] / factor,
                  factor,
                  ok_measures ? "OK" : "WRONG",
                  foreign,
                  missing,
                  plane_faces,
                  off_plane,
                  lateral_on,
                  copies);
    }

  // Between two yarns no mirror plane holds: refused.
  for (const bool quarter : {false, true})
    {
      Fabric::WovenPatchGeometry r    = g;
      (quarter ? r.n_warp : r.n_weft) = 4;
      r.mirror_x                      = true;
      r.mirror_z                      = quarter;
      bool refused                    = false;
      try
        {
          Fabric::WovenPatch patch(r);
        }
      catch (const std::invalid_argument &)
        {
          refused = true;
        }
      std::printf("refused: %s with 4 %s yarns %s\n",
                  quarter ? "quarter" : "half",
                  quarter ? "warp" : "weft",
                  refused ? "OK" : "WRONG");
    }
}
