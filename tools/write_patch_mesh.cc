// write-patch-mesh: the generated woven patch (Fabric::WovenPatch) written
// as a Gmsh mesh and an orientation file for `Fabric/Mesh file` and
// `Fabric/Orientation file` (doc/fabric.md section 8), and the largest
// angle between a mesh's estimated fibre directions and an orientation
// file's.
//
//   write-patch-mesh WARP WEFT CELLS_PER_SPACING STEM [--per-cell]
//                    [--no-surfaces]
//     STEM.msh: the patch of the shipped example's yarns (s = 1 mm,
//     A = 0.1 mm, a_y = 0.0575 mm, a_z = 0.267 mm, the four edges
//     clamped), Gmsh format 2.2, 17 digits; physical group yarn + 1 per
//     hexahedron, physical surfaces 1 (lateral), 2 (clamped end) unless
//     --no-surfaces. STEM.orientation: per cell the patch's fibre
//     directions at its 8 Gauss points (24 numbers, those the FE model
//     would take from the patch; the cell's Gauss points in the vertex
//     order GridIn gives it), or their normalised mean (3 numbers) with
//     --per-cell.
//   write-patch-mesh --compare MESH ORIENTATION
//     prints the largest angle [degrees] between the directions
//     estimated from MESH and the cells' mean directions of ORIENTATION.

#include <yarn_impact/core/crimped_yarn.h>
#include <yarn_impact/fabric/mesh_file.h>
#include <yarn_impact/fabric/woven_patch.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

using namespace dealii;
using namespace YarnImpact::Fabric;

namespace
{
  int
  compare(const std::string &mesh, const std::string &orientation)
  {
    const MeshFile estimated(mesh, "", true, true);
    const MeshFile read(mesh, orientation, true, true);
    double largest = 0.;
    for (unsigned int c = 0; c < read.n_cells(); ++c)
      {
        const double cosine = std::min(1.,
                                       std::abs(estimated.cell_direction(c) *
                                                read.cell_direction(c)));
        largest = std::max(largest, std::acos(cosine) * 180. / M_PI);
      }
    std::printf("cells %u, yarns %u, sections per yarn %u (estimated), %u "
                "(read); largest angle between the estimated and the read "
                "directions %.4f degrees\n",
                read.n_cells(),
                read.n_yarns(),
                estimated.sections_per_yarn(),
                read.sections_per_yarn(),
                largest);
    return 0;
  }
} // namespace

int
main(int argc, char **argv)
{
  try
    {
      const std::vector<std::string> args(argv + 1, argv + argc);
      if (args.size() == 3 && args[0] == "--compare")
        return compare(args[1], args[2]);
      if (args.size() < 4)
        {
          std::cerr << "usage: write-patch-mesh WARP WEFT CELLS_PER_SPACING "
                       "STEM [--per-cell] [--no-surfaces] | --compare MESH "
                       "ORIENTATION\n";
          return 1;
        }
      const bool per_cell = std::count(args.begin(), args.end(), "--per-cell");
      const bool surfaces =
        !std::count(args.begin(), args.end(), "--no-surfaces");
      WovenPatchGeometry g;
      g.n_warp            = std::stoi(args[0]);
      g.n_weft            = std::stoi(args[1]);
      g.cells_per_spacing = std::stoi(args[2]);
      const WovenPatch patch(g);
      Triangulation<3> mesh;
      patch.create_mesh(mesh);

      FILE *out = std::fopen((args[3] + ".msh").c_str(), "w");
      std::fprintf(out,
                   "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%u\n",
                   mesh.n_vertices());
      for (unsigned int v = 0; v < mesh.n_vertices(); ++v)
        std::fprintf(out,
                     "%u %.17g %.17g %.17g\n",
                     v + 1,
                     mesh.get_vertices()[v][0],
                     mesh.get_vertices()[v][1],
                     mesh.get_vertices()[v][2]);
      std::vector<std::string> faces;
      for (const auto &cell : mesh.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (surfaces && face->at_boundary())
            {
              const unsigned int id = face->boundary_id();
              const unsigned int tag =
                id == BoundaryIds::end       ? MeshFileTags::clamped_end
                : id == BoundaryIds::lateral ? MeshFileTags::lateral
                                             : MeshFileTags::free_end;
              // Gmsh's quadrilateral goes round its vertices.
              char line[200];
              std::snprintf(line,
                            sizeof(line),
                            "3 2 %u %u %u %u %u %u",
                            tag,
                            tag,
                            face->vertex_index(0) + 1,
                            face->vertex_index(1) + 1,
                            face->vertex_index(3) + 1,
                            face->vertex_index(2) + 1);
              faces.push_back(line);
            }
      std::fprintf(out,
                   "$EndNodes\n$Elements\n%zu\n",
                   mesh.n_active_cells() + faces.size());
      unsigned int element = 0;
      for (const auto &cell : mesh.active_cell_iterators())
        {
          // Gmsh's hexahedron goes round each face z = 0 and z = 1.
          std::fprintf(out,
                       "%u 5 2 %u %u",
                       ++element,
                       cell->material_id() + 1,
                       cell->material_id() + 1);
          for (const unsigned int v : {0, 1, 3, 2, 4, 5, 7, 6})
            std::fprintf(out, " %u", cell->vertex_index(v) + 1);
          std::fprintf(out, "\n");
        }
      for (const std::string &f : faces)
        std::fprintf(out, "%u %s\n", ++element, f.c_str());
      std::fprintf(out, "$EndElements\n");
      std::fclose(out);

      // The directions at the Gauss points the FE model uses (QGauss<3>(2),
      // the default mapping), as the patch gives them, on the mesh as
      // GridIn reads it back: GridIn may turn a cell's vertex order, and
      // with it the order of its Gauss points.
      Triangulation<3> read;
      {
        GridIn<3> grid_in;
        grid_in.attach_triangulation(read);
        std::ifstream in(args[3] + ".msh");
        grid_in.read_msh(in);
      }
      FE_Q<3> fe(1);
      QGauss<3> quadrature(2);
      FEValues<3> values(fe, quadrature, update_quadrature_points);
      out = std::fopen((args[3] + ".orientation").c_str(), "w");
      std::fprintf(out,
                   "# fibre directions of the %u cells of %s.msh, %s\n",
                   mesh.n_active_cells(),
                   args[3].c_str(),
                   per_cell ? "one per cell" : "one per Gauss point");
      for (const auto &cell : read.active_cell_iterators())
        {
          values.reinit(cell);
          Tensor<1, 3> mean;
          std::string line;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const Tensor<1, 3> t =
                patch.fibre_direction(values.quadrature_point(q));
              mean += t;
              char word[80];
              for (unsigned int d = 0; d < 3; ++d)
                {
                  std::snprintf(word, sizeof(word), " %.17g", t[d]);
                  line += word;
                }
            }
          if (per_cell)
            {
              mean /= mean.norm();
              std::fprintf(out,
                           "%.17g %.17g %.17g\n",
                           mean[0],
                           mean[1],
                           mean[2]);
            }
          else
            std::fprintf(out, "%s\n", line.c_str() + 1);
        }
      std::fclose(out);
      return 0;
    }
  catch (const std::exception &e)
    {
      std::cerr << "write-patch-mesh: " << e.what() << "\n";
      return 1;
    }
}
