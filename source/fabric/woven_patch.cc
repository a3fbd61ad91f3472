#include <yarn_impact/core/yarn_section.h>
#include <yarn_impact/fabric/woven_patch.h>

#include <deal.II/base/numbers.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace YarnImpact
{
  namespace Fabric
  {
    using namespace dealii;

    WovenPatch::WovenPatch(const WovenPatchGeometry &geometry)
      : g(geometry)
    {
      if (g.n_warp == 0 || g.n_weft == 0 || !(g.spacing > 0.) ||
          g.cells_per_spacing == 0)
        throw std::invalid_argument(
          "WovenPatch: the numbers of yarns and cells and the spacing must "
          "be positive");
      // At rest no two yarns may touch: a crossing's centrelines are 2 A
      // apart across the fabric, their meshed sections' vertices reach
      // meshed_thickness_semi_axis() from them; neighbouring parallel ones
      // are s apart in it.
      if (!(g.amplitude > meshed_thickness_semi_axis(g)))
        throw std::invalid_argument(
          "WovenPatch: the crimp amplitude must exceed the meshed section's "
          "thickness semi-axis, or the crossing yarns overlap");
      if (!(2. * g.width_semi_axis < g.spacing))
        throw std::invalid_argument(
          "WovenPatch: the spacing must exceed the yarn's width, or "
          "neighbouring parallel yarns overlap");
      // A ply's mesh spans its mid-plane +-ply_thickness() / 2.
      if (g.n_plies == 0 ||
          (g.n_plies > 1 && !(g.ply_spacing > ply_thickness(g))))
        throw std::invalid_argument(
          "WovenPatch: there must be a ply, and the ply spacing must exceed "
          "a ply's meshed thickness, or neighbouring plies overlap");
      // A mirror plane lies on a crossing yarn's centreline, and is a
      // layer of nodes of the yarns it cuts at mid-length.
      if ((g.mirror_x && g.n_weft % 2 == 0) ||
          (g.mirror_z && g.n_warp % 2 == 0) ||
          ((g.mirror_x || g.mirror_z) && g.cells_per_spacing % 2 == 1))
        throw std::invalid_argument(
          "WovenPatch: a symmetry plane needs an odd number of the yarns "
          "parallel to it and an even number of cells per spacing");
      if ((g.mirror_x || g.mirror_z) && g.n_plies > 1 &&
          (g.ply_offset_x != 0. || g.ply_offset_z != 0.))
        throw std::invalid_argument(
          "WovenPatch: plies shifted in the fabric's plane have no symmetry "
          "plane");
      const double k = numbers::PI / g.spacing;
      for (unsigned int id = 0; id < yarns_per_ply(); ++id)
        {
          const bool warp      = is_warp(id);
          const unsigned int n = warp ? g.n_weft : g.n_warp;
          const unsigned int i = warp ? id : id - g.n_warp;
          // The first crossing yarn's position along this one, and this
          // one's across the fabric.
          const double first = -0.5 * (n - 1.) * g.spacing;
          offset.push_back((i - 0.5 * ((warp ? g.n_warp : g.n_weft) - 1.)) *
                           g.spacing);
          CrimpedYarnGeometry y;
          y.amplitude  = g.amplitude;
          y.wavelength = 2. * g.spacing;
          // Warp: A cos(k (x - first) + i pi); weft: -A cos(k (z - first)
          // + j pi), as A sin(k x + phase).
          y.phase =
            (warp ? 0.5 : -0.5) * numbers::PI + i * numbers::PI - k * first;
          y.x_begin             = -0.5 * n * g.spacing;
          y.x_end               = 0.5 * n * g.spacing;
          y.thickness_semi_axis = g.thickness_semi_axis;
          y.width_semi_axis     = g.width_semi_axis;
          y.n_cells             = n * g.cells_per_spacing;
          y.section_refinements = g.section_refinements;
          // Cut at mid-length by the plane across it: the warp keeps
          // x <= 0, the weft its own x (the patch's z) >= 0. Cut
          // lengthwise by the plane along it: the half section z >= 0 of
          // its own frame, the patch's z >= 0 for the warp, x <= 0 for
          // the weft (to_yarn_frame()).
          if (warp ? g.mirror_x : g.mirror_z)
            {
              (warp ? y.x_end : y.x_begin) = 0.;
              y.n_cells /= 2;
            }
          y.half_section =
            (warp ? g.mirror_z : g.mirror_x) && offset.back() == 0.;
          yarns.emplace_back(y); // throws if it folds
        }
    }


    bool
    WovenPatch::meshed(const unsigned int id) const
    {
      return is_warp(id) ? !g.mirror_z || position(id) >= 0.
                         : !g.mirror_x || position(id) <= 0.;
    }


    unsigned int
    WovenPatch::copies(const unsigned int id) const
    {
      if (!meshed(id))
        return 0;
      const bool mirrored = is_warp(id) ? g.mirror_z : g.mirror_x;
      return mirrored && position(id) != 0. ? 2 : 1;
    }


    unsigned int
    WovenPatch::length_copies(const unsigned int id) const
    {
      const bool cut = is_warp(id) ? g.mirror_x : g.mirror_z;
      return (cut ? 2 : 1) * copies(id);
    }


    double
    WovenPatch::meshed_thickness_semi_axis(const WovenPatchGeometry &geometry)
    {
      Triangulation<2> section;
      create_yarn_section(section,
                          geometry.thickness_semi_axis,
                          geometry.width_semi_axis,
                          geometry.section_refinements,
                          false,
                          true);
      double extent = 0.;
      for (const Point<2> &v : section.get_vertices())
        extent = std::max(extent, std::abs(v[0]));
      return extent;
    }


    Point<3>
    WovenPatch::to_yarn_frame(const unsigned int id, const Point<3> &X) const
    {
      // Warp: shifted across by z_i. Weft: turned about y, its own x the
      // patch's z and its own z the patch's -x, shifted by x_j (a
      // rotation, so that the cells keep their orientation). Both
      // shifted up by their ply's depth and back along themselves by
      // their ply's shift in the plane (ply 0's coordinates untouched,
      // bit for bit: its shifts are +0; position() holds the shift
      // across).
      const unsigned int p = ply(id);
      const double y       = X[1] - ply_height(p);
      const double o       = position(id);
      return is_warp(id) ? Point<3>(X[0] - ply_shift(p, 0), y, X[2] - o)
                         : Point<3>(X[2] - ply_shift(p, 2), y, o - X[0]);
    }


    unsigned int
    WovenPatch::section_of(const unsigned int id, const Point<3> &X) const
    {
      const CrimpedYarn &y          = yarn(id);
      const CrimpedYarnGeometry &yg = y.geometry();
      const double s                = y.abscissa_of(to_yarn_frame(id, X));
      const double k =
        std::floor((s - yg.x_begin) / (yg.x_end - yg.x_begin) * yg.n_cells);
      return static_cast<unsigned int>(
        std::clamp(k, 0., static_cast<double>(yg.n_cells - 1)));
    }


    double
    WovenPatch::section_radius(const unsigned int id, const Point<3> &X) const
    {
      const CrimpedYarn &y          = yarn(id);
      const Point<3> P              = to_yarn_frame(id, X);
      const double s                = y.abscissa_of(P);
      const CrimpedYarnGeometry &yg = y.geometry();
      if (s < yg.x_begin - 1e-9 * g.spacing || s > yg.x_end + 1e-9 * g.spacing)
        return std::numeric_limits<double>::max();
      const double u = (P - y.centreline(s)) * y.normal(s);
      const double v = P[2];
      return u * u / (g.thickness_semi_axis * g.thickness_semi_axis) +
             v * v / (g.width_semi_axis * g.width_semi_axis);
    }


    unsigned int
    WovenPatch::yarn_of(const Point<3> &X) const
    {
      // The plies are more than their thickness apart: a point of a yarn
      // lies within half a spacing of its ply's mid-plane.
      const double p =
        g.n_plies == 1
          ? 0.
          : std::clamp(std::round(-X[1] / g.ply_spacing), 0., g.n_plies - 1.);
      const unsigned int first = static_cast<unsigned int>(p) * yarns_per_ply();
      // A bound first, from the warp yarn nearest in z and the weft yarn
      // nearest in x; then every yarn in id order as before, but that a
      // yarn whose radius cannot reach the bound is not evaluated: its
      // radius is at least its offset across the section, v^2 / a_z^2
      // (section_radius() adds u^2 / a_y^2 >= 0, the same rounding), so
      // that it could be neither the smallest nor a tie, and the answer
      // is the same yarn. Without it, locating the Gauss points of a
      // large patch (every yarn's Newton projection per point) dominated
      // its set-up.
      const auto nearest = [](const double offset, const unsigned int n) {
        return static_cast<unsigned int>(
          std::clamp(std::round(offset + 0.5 * (n - 1.)), 0., n - 1.));
      };
      const unsigned int q = static_cast<unsigned int>(p);
      const double x       = X[0] - ply_shift(q, 0);
      const double z       = X[2] - ply_shift(q, 2);
      const double a_z2    = g.width_semi_axis * g.width_semi_axis;
      const double bound   = std::min(
        section_radius(first + nearest(z / g.spacing, g.n_warp), X),
        section_radius(first + g.n_warp + nearest(x / g.spacing, g.n_weft), X));
      unsigned int best = first;
      double smallest   = std::numeric_limits<double>::max();
      for (unsigned int id = first; id < first + yarns_per_ply(); ++id)
        {
          const double v = to_yarn_frame(id, X)[2];
          if (v * v / a_z2 > bound)
            continue;
          const double r = section_radius(id, X);
          if (r < smallest)
            {
              smallest = r;
              best     = id;
            }
        }
      return best;
    }


    Tensor<1, 3>
    WovenPatch::fibre_direction(const Point<3> &X) const
    {
      const unsigned int id = yarn_of(X);
      const Tensor<1, 3> t  = yarn(id).fibre_direction(to_yarn_frame(id, X));
      if (is_warp(id))
        return t;
      Tensor<1, 3> T; // the weft's own x is the patch's z
      T[0] = -t[2];
      T[1] = t[1];
      T[2] = t[0];
      return T;
    }


    void
    WovenPatch::create_mesh(Triangulation<3, 3> &mesh) const
    {
      std::vector<Triangulation<3>> parts(n_yarns());
      std::vector<const Triangulation<3> *> pointers;
      for (unsigned int id = 0; id < n_yarns(); ++id)
        {
          if (!meshed(id))
            continue;
          yarn(id).create_mesh(parts[id]);
          const double o     = position(id);
          const bool warp    = is_warp(id);
          const bool shifted = ply(id) > 0;
          const double h     = ply_height(ply(id));
          // The ply's shift along the yarn (position() holds the one
          // across it).
          const double a = ply_shift(ply(id), warp ? 0 : 2);
          GridTools::transform(
            [o, warp, shifted, h, a](const Point<3> &p) {
              const double y = shifted ? p[1] + h : p[1];
              const double s = a != 0. ? p[0] + a : p[0];
              return warp ? Point<3>(s, y, p[2] + o) : Point<3>(o - p[2], y, s);
            },
            parts[id]);
          for (const auto &cell : parts[id].active_cell_iterators())
            cell->set_material_id(id);
          pointers.push_back(&parts[id]);
        }
      // No two yarns share a vertex (they do not touch): a tolerance far
      // below their gaps merges none. The merge drops the boundary ids:
      // the end sections are found again by their abscissa.
      GridGenerator::merge_triangulations(pointers,
                                          mesh,
                                          1e-9 * g.thickness_semi_axis);
      for (const auto &cell : mesh.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              const unsigned int id        = cell->material_id();
              const CrimpedYarnGeometry &y = yarn(id).geometry();
              const double s =
                yarn(id).abscissa_of(to_yarn_frame(id, face->center()));
              const double tol = 1e-6 * g.spacing / g.cells_per_spacing;
              // On a symmetry plane: a cut end, or a half section's cut
              // face (every other face of a yarn lies off it by at least
              // half a cell along or across the yarn).
              const Point<3> c = face->center();
              if ((g.mirror_x && std::abs(c[0]) < tol) ||
                  (g.mirror_z && std::abs(c[2]) < tol))
                {
                  face->set_boundary_id(symmetry_plane_boundary_id);
                  continue;
                }
              const bool clamped =
                is_warp(id) ? g.clamp_warp_ends : g.clamp_weft_ends;
              if (std::abs(s - y.x_begin) >= tol &&
                  std::abs(s - y.x_end) >= tol)
                face->set_boundary_id(BoundaryIds::lateral);
              else
                face->set_boundary_id(clamped ? BoundaryIds::end
                                              : free_end_boundary_id);
            }
    }
  } // namespace Fabric
} // namespace YarnImpact
