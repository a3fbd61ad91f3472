#ifndef yarn_impact_fe_yarn_mesh_h
#define yarn_impact_fe_yarn_mesh_h

#include <yarn_impact/core/crimped_yarn.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/fe/parameters.h>

namespace dealii
{
  template <int dim, int spacedim>
  class Triangulation;
}

namespace YarnImpact
{
  namespace FE
  {
    /** Boundary ids of the yarn mesh. */
    namespace BoundaryIds
    {
      /** Lateral surface, where the projectile can touch. */
      constexpr unsigned int lateral = 0;
      /** Clamped end x = +-L/2. */
      constexpr unsigned int clamp = 1;
      /** Symmetry plane x = 0. */
      constexpr unsigned int symmetry_x = 2;
      /** Symmetry plane z = 0. */
      constexpr unsigned int symmetry_z = 3;
      /** The end x = x_begin of a part of the yarn (create_yarn_part_mesh):
       * free, moved by a coupling. */
      constexpr unsigned int coupled_end = 4;
    } // namespace BoundaryIds

    /**
     * The yarn: the section of create_yarn_section() (core/yarn_section.h)
     * in the (y, z) plane, y along the thickness semi-axis a_y and z along
     * the width semi-axis a_z (for quarter symmetry only the cells with
     * z >= 0), extruded along x over [-L/2, L/2] (symmetry
     * none) or [0, L/2] (half, quarter) with @p n_axial_cells over the whole
     * length, boundary ids of BoundaryIds set by position.
     */
    void
    create_yarn_mesh(dealii::Triangulation<3, 3> &mesh,
                     const YarnImpact::Parameters::Yarn &yarn,
                     const YarnImpact::Parameters::Symmetry symmetry,
                     const unsigned int n_axial_cells,
                     const unsigned int section_refinements,
                     const bool preserve_section_area);

    /**
     * The crimped yarn of `FE/Crimp` (@p crimp) as a Fabric::CrimpedYarn:
     * the centreline A cos(2 pi x / lambda) (phase pi/2, a crest at x = 0)
     * over [-L/2, L/2] (symmetry none) or [0, L/2] (half, quarter, and
     * then only the section's cells with z >= 0 for quarter) in
     * @p n_axial_cells over the whole length, the section of the yarn
     * @p yarn [m] refined @p section_refinements times. Does not check
     * it: FE::validate() does, and the CrimpedYarn throws.
     */
    Fabric::CrimpedYarnGeometry
    crimped_yarn_geometry(const YarnImpact::Parameters::Yarn &yarn,
                          const YarnImpact::Parameters::Symmetry symmetry,
                          const unsigned int n_axial_cells,
                          const unsigned int section_refinements,
                          const bool preserve_section_area,
                          const CrimpParameters &crimp);

    /**
     * The mesh of the crimped yarn @p crimped (CrimpedYarn::create_mesh)
     * with the boundary ids of BoundaryIds: its end sections the clamps
     * (or, at abscissa 0 of a half or quarter model, where the section at
     * the crest is the plane x = 0, the symmetry plane), its half
     * section's plane z = 0 the symmetry plane z = 0.
     */
    void
    create_crimped_yarn_mesh(dealii::Triangulation<3, 3> &mesh,
                             const Fabric::CrimpedYarn &crimped);

    /**
     * A part of the yarn (half or quarter symmetry, @p symmetry): the
     * section (its half z >= 0 with quarter symmetry) extruded along x over
     * [@p x_begin, @p x_end] [m] in @p n_cells equal layers; the face
     * x = x_begin, and x = x_end unless it is the clamp L/2, have the
     * boundary id BoundaryIds::coupled_end, the others as in
     * create_yarn_mesh().
     */
    void
    create_yarn_part_mesh(dealii::Triangulation<3, 3> &mesh,
                          const YarnImpact::Parameters::Yarn &yarn,
                          const YarnImpact::Parameters::Symmetry symmetry,
                          const double x_begin,
                          const double x_end,
                          const unsigned int n_cells,
                          const unsigned int section_refinements,
                          const bool preserve_section_area);
  } // namespace FE
} // namespace YarnImpact

#endif
