#include <yarn_impact/core/yarn_section.h>
#include <yarn_impact/fe/yarn_mesh.h>

#include <deal.II/base/numbers.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <cmath>

namespace YarnImpact
{
  namespace FE
  {
    using namespace dealii;

    void
    create_yarn_mesh(Triangulation<3, 3> &mesh,
                     const YarnImpact::Parameters::Yarn &yarn,
                     const YarnImpact::Parameters::Symmetry symmetry,
                     const unsigned int n_axial_cells,
                     const unsigned int section_refinements,
                     const bool preserve_section_area)
    {
      const bool reduced = symmetry != YarnImpact::Parameters::Symmetry::none;
      Triangulation<2> section;
      create_yarn_section(section,
                          yarn.thickness_semi_axis,
                          yarn.width_semi_axis,
                          section_refinements,
                          symmetry == YarnImpact::Parameters::Symmetry::quarter,
                          preserve_section_area);

      const unsigned int n_slices = reduced ? n_axial_cells / 2 : n_axial_cells;
      const double length         = reduced ? 0.5 * yarn.length : yarn.length;
      Triangulation<3> extruded;
      GridGenerator::extrude_triangulation(section,
                                           n_slices + 1,
                                           length,
                                           extruded);
      // Extrusion is along the third coordinate; a cyclic permutation (a
      // rotation, so cells keep their orientation) makes it the yarn axis x.
      const double x0 = reduced ? 0. : -0.5 * yarn.length;
      GridTools::transform(
        [x0](const Point<3> &p) { return Point<3>(p[2] + x0, p[0], p[1]); },
        extruded);

      const double tol = 1e-6 * yarn.length / n_axial_cells;
      for (const auto &cell : extruded.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              const Point<3> c = face->center();
              if (std::abs(std::abs(c[0]) - 0.5 * yarn.length) < tol)
                face->set_boundary_id(BoundaryIds::clamp);
              else if (reduced && std::abs(c[0]) < tol)
                face->set_boundary_id(BoundaryIds::symmetry_x);
              else if (symmetry == YarnImpact::Parameters::Symmetry::quarter &&
                       std::abs(c[2]) < 1e-9 * yarn.width_semi_axis)
                face->set_boundary_id(BoundaryIds::symmetry_z);
              else
                face->set_boundary_id(BoundaryIds::lateral);
            }
      mesh.copy_triangulation(extruded);
    }


    Fabric::CrimpedYarnGeometry
    crimped_yarn_geometry(const YarnImpact::Parameters::Yarn &yarn,
                          const YarnImpact::Parameters::Symmetry symmetry,
                          const unsigned int n_axial_cells,
                          const unsigned int section_refinements,
                          const bool preserve_section_area,
                          const CrimpParameters &crimp)
    {
      const bool reduced = symmetry != YarnImpact::Parameters::Symmetry::none;
      Fabric::CrimpedYarnGeometry g;
      g.amplitude  = crimp.amplitude;
      g.wavelength = crimp.wavelength;
      // A crest at x = 0: the projectile first touches the yarn there,
      // and the centreline is mirror-symmetric about the plane x = 0,
      // where the section at the crest lies: half and quarter models
      // keep their symmetry plane.
      g.phase                 = 0.5 * numbers::PI;
      g.x_begin               = reduced ? 0. : -0.5 * yarn.length;
      g.x_end                 = 0.5 * yarn.length;
      g.thickness_semi_axis   = yarn.thickness_semi_axis;
      g.width_semi_axis       = yarn.width_semi_axis;
      g.n_cells               = reduced ? n_axial_cells / 2 : n_axial_cells;
      g.section_refinements   = section_refinements;
      g.preserve_section_area = preserve_section_area;
      g.half_section = symmetry == YarnImpact::Parameters::Symmetry::quarter;
      return g;
    }


    void
    create_crimped_yarn_mesh(Triangulation<3, 3> &mesh,
                             const Fabric::CrimpedYarn &crimped)
    {
      crimped.create_mesh(mesh);
      const Fabric::CrimpedYarnGeometry &g = crimped.geometry();
      const double tol = 1e-6 * (g.x_end - g.x_begin) / g.n_cells;
      for (const auto &cell : mesh.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              if (face->boundary_id() == Fabric::BoundaryIds::lateral)
                face->set_boundary_id(BoundaryIds::lateral);
              else if (face->boundary_id() == Fabric::BoundaryIds::symmetry_z)
                face->set_boundary_id(BoundaryIds::symmetry_z);
              else
                face->set_boundary_id(
                  std::abs(crimped.abscissa_of(face->center())) < tol
                    ? BoundaryIds::symmetry_x
                    : BoundaryIds::clamp);
            }
    }


    void
    create_yarn_part_mesh(Triangulation<3, 3> &mesh,
                          const YarnImpact::Parameters::Yarn &yarn,
                          const YarnImpact::Parameters::Symmetry symmetry,
                          const double x_begin,
                          const double x_end,
                          const unsigned int n_cells,
                          const unsigned int section_refinements,
                          const bool preserve_section_area)
    {
      const bool quarter =
        symmetry == YarnImpact::Parameters::Symmetry::quarter;
      Triangulation<2> section;
      create_yarn_section(section,
                          yarn.thickness_semi_axis,
                          yarn.width_semi_axis,
                          section_refinements,
                          quarter,
                          preserve_section_area);
      const double length = x_end - x_begin;
      Triangulation<3> extruded;
      GridGenerator::extrude_triangulation(section,
                                           n_cells + 1,
                                           length,
                                           extruded);
      GridTools::transform(
        [x_begin](const Point<3> &p) {
          return Point<3>(p[2] + x_begin, p[0], p[1]);
        },
        extruded);
      const double tol = 1e-6 * length / n_cells;
      for (const auto &cell : extruded.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              const Point<3> c = face->center();
              if (std::abs(c[0] - 0.5 * yarn.length) < tol)
                face->set_boundary_id(BoundaryIds::clamp);
              else if (std::abs(c[0] - x_begin) < tol ||
                       std::abs(c[0] - x_end) < tol)
                face->set_boundary_id(BoundaryIds::coupled_end);
              else if (quarter && std::abs(c[2]) < 1e-9 * yarn.width_semi_axis)
                face->set_boundary_id(BoundaryIds::symmetry_z);
              else
                face->set_boundary_id(BoundaryIds::lateral);
            }
      mesh.copy_triangulation(extruded);
    }
  } // namespace FE
} // namespace YarnImpact
