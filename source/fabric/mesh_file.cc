// A fabric's mesh read from a Gmsh file (`Fabric/Mesh file`,
// doc/fabric.md section 8): the yarns, fibre directions, clamps and
// sections that the generated patch (WovenPatch) gives from its geometry,
// found here from the file and the mesh.

#include <yarn_impact/core/crimped_yarn.h>
#include <yarn_impact/fabric/mesh_file.h>
#include <yarn_impact/fabric/woven_patch.h>

#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/reference_cell.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace YarnImpact
{
  namespace Fabric
  {
    using namespace dealii;

    namespace
    {
      const char *const mesh_entry        = "Fabric/Mesh file";
      const char *const orientation_entry = "Fabric/Orientation file";

      /** The gist of deal.II's message @p text in one line: its
       * "Additional information" (the reader's reason), else its first
       * line. */
      std::string
      first_line(const std::string &text)
      {
        std::istringstream in(text);
        std::string line, gist, first;
        bool additional = false;
        while (std::getline(in, line))
          {
            const auto b = line.find_first_not_of(" \t-");
            if (b == std::string::npos)
              {
                if (!gist.empty())
                  break;
                continue;
              }
            line = line.substr(b);
            if (first.empty())
              first = line;
            if (line.rfind("Additional information:", 0) == 0)
              additional = true;
            else if (additional)
              gist += (gist.empty() ? "" : " ") + line;
          }
        std::string result = !gist.empty()    ? gist
                             : !first.empty() ? first
                                              : "unknown error";
        // The caller's message ends with its own full stop.
        while (!result.empty() && result.back() == '.')
          result.pop_back();
        return result;
      }

      /** The unit normal [-] of a quadrilateral face from its vertices
       * (deal.II's lexicographic order): the cross product of its
       * diagonals. */
      Tensor<1, 3>
      face_normal(const Triangulation<3>::face_iterator &face)
      {
        const Tensor<1, 3> n =
          cross_product_3d(face->vertex(3) - face->vertex(0),
                           face->vertex(2) - face->vertex(1));
        return n / n.norm();
      }
    } // namespace


    MeshFile::MeshFile(const std::string &mesh_file,
                       const std::string &orientation_file,
                       const bool clamp_warp_ends,
                       const bool clamp_weft_ends)
    {
      read_mesh(mesh_file);
      if (orientation_file.empty())
        {
          for (const Tensor<1, 3> &t : estimate_directions(tria))
            directions.push_back({t});
        }
      else
        read_orientation(orientation_file);
      for (const auto &d : directions)
        {
          Tensor<1, 3> m;
          for (const Tensor<1, 3> &t : d)
            m += t;
          mean_direction.push_back(m / m.norm());
        }
      make_bins();
      find_sections();
      classify_faces(clamp_warp_ends, clamp_weft_ends);
    }


    void
    MeshFile::read_mesh(const std::string &file)
    {
      file_name              = file;
      const std::string name = "'" + file + "'";
      std::ifstream in(file);
      if (!in)
        throw MeshFileError(mesh_entry, "cannot read " + name);
      const auto dot = file.rfind('.');
      if (dot == std::string::npos || file.substr(dot) != ".msh")
        throw MeshFileError(mesh_entry,
                            name + " is not a Gmsh mesh (.msh), the one "
                                   "format read");
      try
        {
          GridIn<3> grid_in;
          grid_in.attach_triangulation(tria);
          grid_in.read_msh(in);
        }
      catch (const std::exception &e)
        {
          throw MeshFileError(mesh_entry,
                              name + " is not a mesh deal.II's GridIn reads: " +
                                first_line(e.what()));
        }
      if (tria.n_active_cells() == 0)
        throw MeshFileError(mesh_entry, name + " holds no cells");
      unsigned int not_hex = 0, no_group = 0;
      for (const auto &cell : tria.active_cell_iterators())
        {
          not_hex += cell->reference_cell() != ReferenceCells::Hexahedron;
          // Gmsh's physical groups count from 1: 0 is a cell in none.
          no_group += cell->material_id() == 0;
          cell_yarn.push_back(cell->material_id() - 1);
          yarns = std::max(yarns, cell->material_id() + 0u);
        }
      if (not_hex > 0)
        throw MeshFileError(mesh_entry,
                            name + ": " + std::to_string(not_hex) + " of its " +
                              std::to_string(tria.n_active_cells()) +
                              " cells are not hexahedra");
      if (no_group > 0)
        throw MeshFileError(
          mesh_entry,
          name + ": " + std::to_string(no_group) +
            " cells are in no physical group (the group g >= 1 makes a "
            "cell one of yarn g - 1)");
      // The yarns' contact needs each yarn's own surface.
      for (const auto &cell : tria.active_cell_iterators())
        for (unsigned int f = 0; f < 6; ++f)
          if (!cell->at_boundary(f) &&
              cell->neighbor(f)->material_id() != cell->material_id())
            throw MeshFileError(
              mesh_entry,
              name + ": cells of physical groups " +
                std::to_string(cell->material_id()) + " and " +
                std::to_string(cell->neighbor(f)->material_id()) +
                " share a face; each yarn must be meshed apart, with its own "
                "surface");
    }


    void
    MeshFile::read_orientation(const std::string &file)
    {
      const std::string name = "'" + file + "'";
      std::ifstream in(file);
      if (!in)
        throw MeshFileError(orientation_entry, "cannot read " + name);
      std::string line;
      unsigned int line_number = 0;
      while (std::getline(in, line))
        {
          ++line_number;
          const auto hash = line.find('#');
          if (hash != std::string::npos)
            line.erase(hash);
          std::istringstream s(line);
          std::vector<double> v;
          std::string word;
          while (s >> word)
            {
              char *end      = nullptr;
              const double x = std::strtod(word.c_str(), &end);
              if (end == word.c_str() || *end != '\0' || !std::isfinite(x))
                throw MeshFileError(orientation_entry,
                                    name + " line " +
                                      std::to_string(line_number) + ": '" +
                                      word + "' is not a finite number");
              v.push_back(x);
            }
          if (v.empty())
            continue;
          const std::string at = name + " line " + std::to_string(line_number);
          if (v.size() != 3 && v.size() != 24)
            throw MeshFileError(
              orientation_entry,
              at + ": " + std::to_string(v.size()) +
                " numbers; a line holds 3 (the cell's unit direction) or 24 "
                "(one per Gauss point)");
          if (!directions.empty() && directions[0].size() * 3 != v.size())
            throw MeshFileError(orientation_entry,
                                at + ": every line must hold as many numbers "
                                     "as the first");
          std::vector<Tensor<1, 3>> d(v.size() / 3);
          for (unsigned int k = 0; k < d.size(); ++k)
            {
              for (unsigned int i = 0; i < 3; ++i)
                d[k][i] = v[3 * k + i];
              if (std::abs(d[k].norm() - 1.) > 1e-6)
                throw MeshFileError(orientation_entry,
                                    at + ": a direction of length " +
                                      std::to_string(d[k].norm()) +
                                      ", not 1 within 1e-6");
            }
          directions.push_back(d);
        }
      if (directions.size() != n_cells())
        throw MeshFileError(orientation_entry,
                            name + " gives " +
                              std::to_string(directions.size()) +
                              " cells' directions for the " +
                              std::to_string(n_cells()) +
                              " cells of Fabric/Mesh file");
      read_directions = true;
    }


    std::vector<Tensor<1, 3>>
    MeshFile::estimate_directions(const Triangulation<3, 3> &mesh)
    {
      std::vector<Tensor<1, 3>> result(mesh.n_active_cells());
      // The cells reached through face f and on through the opposite
      // faces, within the same material id; -1 if the walk comes back to
      // the start (a ring of cells round the section: a yarn's fibres run
      // open from end to end).
      const auto chain = [&mesh](const Triangulation<3>::cell_iterator start,
                                 unsigned int f) {
        int n     = 0;
        auto cell = start;
        while (!cell->at_boundary(f))
          {
            const auto next = cell->neighbor(f);
            if (next->material_id() != cell->material_id())
              break;
            if (next == start)
              return -1;
            const unsigned int back = cell->neighbor_of_neighbor(f);
            cell                    = next;
            f                       = back ^ 1u;
            if (++n > static_cast<int>(mesh.n_active_cells()))
              return -1;
          }
        return n;
      };
      for (const auto &cell : mesh.active_cell_iterators())
        {
          unsigned int best  = 0;
          int best_chain     = -2;
          double best_length = 0.;
          for (unsigned int d = 0; d < 3; ++d)
            {
              const int forward = chain(cell, 2 * d);
              const int n =
                forward < 0 ? -1
                            : 1 + forward + std::max(0, chain(cell, 2 * d + 1));
              const double length =
                (cell->face(2 * d + 1)->center() - cell->face(2 * d)->center())
                  .norm();
              if (n > best_chain || (n == best_chain && length > best_length))
                {
                  best        = d;
                  best_chain  = n;
                  best_length = length;
                }
            }
          const Tensor<1, 3> t =
            cell->face(2 * best + 1)->center() - cell->face(2 * best)->center();
          result[cell->active_cell_index()] = t / t.norm();
        }
      return result;
    }


    void
    MeshFile::make_bins()
    {
      BoundingBox<3> all(tria.get_vertices());
      double extent = 0.;
      for (const auto &cell : tria.active_cell_iterators())
        for (unsigned int d = 0; d < 3; ++d)
          extent += cell->bounding_box().side_length(d);
      bin_width  = std::max(extent / (3. * n_cells()), 1e-300);
      bin_origin = all.get_boundary_points().first;
      for (unsigned int d = 0; d < 3; ++d)
        n_bins[d] = std::clamp<unsigned int>(
          static_cast<unsigned int>(all.side_length(d) / bin_width) + 1,
          1,
          256);
      bins.assign(n_bins[0] * n_bins[1] * n_bins[2], {});
      const auto bin = [this](const double x, const unsigned int d) {
        return std::clamp<long>(static_cast<long>(
                                  std::floor((x - bin_origin[d]) / bin_width)),
                                0,
                                n_bins[d] - 1);
      };
      for (const auto &cell : tria.active_cell_iterators())
        {
          const auto box = cell->bounding_box().get_boundary_points();
          for (long i = bin(box.first[0], 0); i <= bin(box.second[0], 0); ++i)
            for (long j = bin(box.first[1], 1); j <= bin(box.second[1], 1); ++j)
              for (long k = bin(box.first[2], 2); k <= bin(box.second[2], 2);
                   ++k)
                bins[(k * n_bins[1] + j) * n_bins[0] + i].push_back(
                  cell->active_cell_index());
        }
    }


    unsigned int
    MeshFile::locate(const Point<3> &X, Point<3> &unit) const
    {
      static const MappingQ<3> mapping(1);
      unsigned int b = 0;
      for (int d = 2; d >= 0; --d)
        b = b * n_bins[d] +
            std::clamp<long>(static_cast<long>(
                               std::floor((X[d] - bin_origin[d]) / bin_width)),
                             0,
                             n_bins[d] - 1);
      double best_depth = -std::numeric_limits<double>::max();
      unsigned int best = 0;
      for (const unsigned int c : bins[b])
        {
          const Triangulation<3>::active_cell_iterator cell(&tria, 0, c);
          BoundingBox<3> box = cell->bounding_box();
          box.extend(1e-9 * bin_width);
          if (!box.point_inside(X))
            continue;
          try
            {
              const Point<3> p = mapping.transform_real_to_unit_cell(cell, X);
              double depth     = std::numeric_limits<double>::max();
              for (unsigned int d = 0; d < 3; ++d)
                depth = std::min({depth, p[d], 1. - p[d]});
              if (depth > best_depth)
                {
                  best_depth = depth;
                  best       = c;
                  unit       = p;
                }
            }
          catch (const std::exception &)
            {
              // The Newton iteration fails only far outside the cell.
            }
        }
      if (best_depth < -1e-6)
        throw std::runtime_error(
          "Fabric mesh file: a point in no cell of the mesh");
      return best;
    }


    unsigned int
    MeshFile::locate(const Point<3> &X) const
    {
      Point<3> unit;
      return locate(X, unit);
    }


    Tensor<1, 3>
    MeshFile::fibre_direction(const Point<3> &X) const
    {
      Point<3> p;
      const unsigned int c = locate(X, p);
      if (directions[c].size() == 1)
        return directions[c][0];
      // QGauss<3>(2)'s points, x fastest.
      const unsigned int q = (p[0] > 0.5) + 2 * (p[1] > 0.5) + 4 * (p[2] > 0.5);
      return directions[c][q];
    }


    double
    MeshFile::section_height(const Point<3> &X) const
    {
      const unsigned int c   = locate(X);
      const Tensor<1, 3> &M  = mean_direction[c];
      Tensor<1, 3> n         = Point<3>(0., 1., 0.) - M[1] * M;
      const double magnitude = n.norm();
      n =
        magnitude > 1e-12 ? n / magnitude : Tensor<1, 3>(Point<3>(1., 0., 0.));
      return (X - section_centre[c]) * n;
    }


    void
    MeshFile::find_sections()
    {
      // Each yarn's mean axis: its cells' directions turned to one side.
      std::vector<Tensor<1, 3>> axis(yarns);
      std::vector<std::vector<unsigned int>> cells(yarns);
      for (unsigned int c = 0; c < n_cells(); ++c)
        {
          Tensor<1, 3> &a       = axis[cell_yarn[c]];
          const Tensor<1, 3> &M = mean_direction[c];
          a += (a * M < 0. ? -1. : 1.) * M;
          cells[cell_yarn[c]].push_back(c);
        }
      cell_section.assign(n_cells(), 0);
      section_centre.assign(n_cells(), Point<3>());
      warp.assign(yarns, true);
      span.assign(yarns, 0.);
      for (unsigned int id = 0; id < yarns; ++id)
        {
          if (cells[id].empty())
            continue;
          const Tensor<1, 3> a = axis[id] / axis[id].norm();
          warp[id]             = std::abs(a[0]) >= std::abs(a[2]);
          // Each cell's position along the axis and length along its own
          // direction; a gap above half the median length starts a
          // section.
          std::vector<std::pair<double, unsigned int>> along;
          std::vector<double> lengths;
          double lo = std::numeric_limits<double>::max(), hi = -lo;
          for (const unsigned int c : cells[id])
            {
              const Triangulation<3>::active_cell_iterator cell(&tria, 0, c);
              along.emplace_back(cell->center() * a, c);
              double l0 = std::numeric_limits<double>::max(), l1 = -l0;
              for (unsigned int v = 0; v < 8; ++v)
                {
                  const double t = cell->vertex(v) * mean_direction[c];
                  l0             = std::min(l0, t);
                  l1             = std::max(l1, t);
                  lo             = std::min(lo, cell->vertex(v) * a);
                  hi             = std::max(hi, cell->vertex(v) * a);
                }
              lengths.push_back(l1 - l0);
            }
          span[id] = hi - lo;
          std::sort(along.begin(), along.end());
          std::nth_element(lengths.begin(),
                           lengths.begin() + lengths.size() / 2,
                           lengths.end());
          const double gap = 0.5 * lengths[lengths.size() / 2];
          unsigned int k = 0, first = 0;
          for (unsigned int i = 0; i <= along.size(); ++i)
            {
              if (i == along.size() ||
                  (i > 0 && along[i].first - along[i - 1].first > gap))
                {
                  // Close the section of along[first, i).
                  Point<3> centre;
                  for (unsigned int j = first; j < i; ++j)
                    centre +=
                      Triangulation<3>::active_cell_iterator(&tria,
                                                             0,
                                                             along[j].second)
                        ->center();
                  centre /= (i - first);
                  for (unsigned int j = first; j < i; ++j)
                    section_centre[along[j].second] = centre;
                  if (i == along.size())
                    break;
                  ++k;
                  first = i;
                }
              cell_section[along[i].second] = k;
            }
          max_sections = std::max(max_sections, k + 1);
        }
    }


    void
    MeshFile::classify_faces(const bool clamp_warp_ends,
                             const bool clamp_weft_ends)
    {
      // An end face's normal lies along its cell's fibres, a lateral
      // face's across them: cos 45 degrees between the two.
      const double end_cosine = std::sqrt(0.5);
      for (const auto &cell : tria.active_cell_iterators())
        for (unsigned int f = 0; f < 6; ++f)
          if (cell->at_boundary(f))
            {
              const auto face = cell->face(f);
              std::array<unsigned int, 4> key;
              for (unsigned int v = 0; v < 4; ++v)
                key[v] = face->vertex_index(v);
              std::sort(key.begin(), key.end());
              const unsigned int c   = cell->active_cell_index();
              const unsigned int tag = face->boundary_id();
              const bool clamped =
                warp[cell_yarn[c]] ? clamp_warp_ends : clamp_weft_ends;
              const unsigned int ended =
                clamped ? BoundaryIds::end : free_end_boundary_id;
              unsigned int id = BoundaryIds::lateral;
              if (tag == 0)
                id =
                  std::abs(face_normal(face) * mean_direction[c]) > end_cosine
                    ? ended
                    : BoundaryIds::lateral;
              else if (tag == MeshFileTags::clamped_end)
                id = BoundaryIds::end;
              else if (tag == MeshFileTags::free_end)
                id = free_end_boundary_id;
              else if (tag != MeshFileTags::lateral)
                throw MeshFileError(
                  mesh_entry,
                  "'" + file_name + "': a boundary face has the physical tag " +
                    std::to_string(tag) +
                    ", none of 1 (lateral), 2 (clamped end), 3 (free end)");
              face_ids[key] = id;
            }
    }


    void
    MeshFile::create_mesh(Triangulation<3, 3> &mesh) const
    {
      std::vector<CellData<3>> cells(n_cells());
      for (const auto &cell : tria.active_cell_iterators())
        {
          CellData<3> &data = cells[cell->active_cell_index()];
          for (unsigned int v = 0; v < 8; ++v)
            data.vertices[v] = cell->vertex_index(v);
          data.material_id = cell_yarn[cell->active_cell_index()];
        }
      mesh.create_triangulation(tria.get_vertices(), cells, SubCellData());
      for (const auto &cell : mesh.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              std::array<unsigned int, 4> key;
              for (unsigned int v = 0; v < 4; ++v)
                key[v] = face->vertex_index(v);
              std::sort(key.begin(), key.end());
              face->set_boundary_id(face_ids.at(key));
            }
    }
  } // namespace Fabric
} // namespace YarnImpact
