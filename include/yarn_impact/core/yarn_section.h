#ifndef yarn_impact_core_yarn_section_h
#define yarn_impact_core_yarn_section_h

namespace dealii
{
  template <int dim, int spacedim>
  class Triangulation;
}

namespace YarnImpact
{
  /**
   * The elliptical section of a yarn, as a 2D mesh whose first coordinate
   * runs along the thickness semi-axis @p a_y [m] and the second along the
   * width semi-axis @p a_z [m]: `GridGenerator::hyper_ball_balanced` (12
   * cells), refined @p refinements times on the unit disk with its
   * manifolds, then scaled to the ellipse. With @p half_section only the
   * cells with a non-negative second coordinate are kept (quarter
   * symmetry). With @p preserve_area the mesh is then scaled about the
   * centre so that its area is exactly that of the (half) ellipse. The
   * straight FE yarn extrudes it along x (FE::create_yarn_mesh), the
   * fabric's crimped yarn sweeps it along a curved centreline
   * (Fabric::CrimpedYarn), the hybrid yarn places its fibres in it.
   */
  void
  create_yarn_section(dealii::Triangulation<2, 2> &section,
                      const double a_y,
                      const double a_z,
                      const unsigned int refinements,
                      const bool half_section,
                      const bool preserve_area);
} // namespace YarnImpact

#endif
