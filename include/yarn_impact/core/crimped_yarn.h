#ifndef yarn_impact_core_crimped_yarn_h
#define yarn_impact_core_crimped_yarn_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

namespace dealii
{
  template <int dim, int spacedim>
  class Triangulation;
}

namespace YarnImpact
{
  /**
   * The woven fabric's geometry: its crimped yarns (doc/fe-model.md
   * section 8). In core, beside the section it sweeps, because two models
   * build on it: the FE yarn meshes a crimped yarn with it (`FE/Crimp`),
   * and a woven fabric is made of them. What it builds is geometry, a
   * mesh and a fibre direction at every reference point, that the FE
   * model takes through FE::Parameters::fibre_direction.
   */
  namespace Fabric
  {
    /** Boundary ids of a crimped yarn's mesh. */
    namespace BoundaryIds
    {
      /** Lateral surface. */
      constexpr unsigned int lateral = 0;
      /** The two end sections x = x_begin and x = x_end of the centreline
       * (normal to its tangent there). */
      constexpr unsigned int end = 1;
      /** The plane z = 0 of a half section
       * (CrimpedYarnGeometry::half_section). */
      constexpr unsigned int symmetry_z = 2;
    } // namespace BoundaryIds

    /** What a crimped yarn is made of [m, -]. */
    struct CrimpedYarnGeometry
    {
      /** Crimp amplitude A [m]: the centreline's largest distance from the
       * fabric's mid-plane y = 0. 0: a straight yarn. */
      double amplitude = 0.1e-3;
      /** Crimp wavelength lambda [m]: twice the spacing of the crossing
       * yarns. */
      double wavelength = 2e-3;
      /** Phase phi [rad] of the centreline's height A sin(k x + phi):
       * pi/2 puts a crest at x = 0 (the FE yarn's impact point, and a
       * centreline mirror-symmetric about x = 0). */
      double phase = 0.;
      /** The centreline spans x in [x_begin, x_end] [m]. */
      double x_begin = -2e-3, x_end = 2e-3;
      /** Semi-axis of the section across the fabric (along the
       * centreline's normal in the x-y plane) [m]. */
      double thickness_semi_axis = 0.0575e-3;
      /** Semi-axis of the section in the fabric's plane (along z) [m]. */
      double width_semi_axis = 0.267e-3;
      /** Cells along the centreline [-], equal steps in x. */
      unsigned int n_cells = 64;
      /** Refinements of the 12-cell section [-] (create_yarn_section). */
      unsigned int section_refinements = 0;
      /** Scale the polygonal section to the ellipse's area. */
      bool preserve_section_area = true;
      /** Keep only the section's cells with z >= 0 (a model with the
       * symmetry plane z = 0; create_yarn_section's half section). */
      bool half_section = false;
    };

    /**
     * A yarn whose centreline undulates across the fabric's mid-plane,
     * c(x) = (x, A sin(2 pi x / lambda + phi), 0), with its elliptical section
     * kept normal to the centreline's tangent t(x): the section's
     * thickness semi-axis lies along the normal n = e_z x t in the x-y
     * plane, its width semi-axis along z. The fabric lies in the x-z plane
     * and the projectile strikes along y, as for the straight yarn, which
     * is the case A = 0 (vertex for vertex the mesh of
     * FE::create_yarn_mesh). The fibres follow the centreline: the fibre
     * direction at a reference point is the tangent t(x) at the centreline
     * point whose section holds it.
     *
     * Points of the tube X(x, u, v) = c(x) + u n(x) + v e_z stay distinct
     * as long as the thickness semi-axis is below the smallest radius of
     * curvature, lambda^2 / (4 pi^2 A): the constructor refuses a yarn
     * that would fold.
     */
    class CrimpedYarn
    {
    public:
      /** @param geometry the yarn; throws std::invalid_argument when it
       * is not a valid one (non-positive sizes, folding). */
      explicit CrimpedYarn(const CrimpedYarnGeometry &geometry);

      /** The geometry [m, -]. */
      const CrimpedYarnGeometry &
      geometry() const
      {
        return g;
      }

      /** Centreline point c(x) [m] at the abscissa @p x [m]. */
      dealii::Point<3>
      centreline(const double x) const;

      /** Unit tangent t(x) [-] of the centreline. */
      dealii::Tensor<1, 3>
      tangent(const double x) const;

      /** Unit normal n(x) = e_z x t(x) [-], in the x-y plane. */
      dealii::Tensor<1, 3>
      normal(const double x) const;

      /** Length of the centreline over [x_begin, x_end] [m], by
       * Gauss-Legendre quadrature (exact to round-off: the integrand is
       * analytic). */
      double
      centreline_length() const;

      /** Crimp [-]: centreline length over the span x_end - x_begin,
       * minus 1. */
      double
      crimp() const;

      /** The abscissa x [m] of the centreline point whose normal section
       * holds the reference point @p X [m]: the root of
       * (X - c(x)) . t(x) = 0 near X_x, by Newton's method. */
      double
      abscissa_of(const dealii::Point<3> &X) const;

      /** The fibre direction [-] at the reference point @p X [m]: the
       * centreline tangent at abscissa_of(X). */
      dealii::Tensor<1, 3>
      fibre_direction(const dealii::Point<3> &X) const;

      /** The same in the form of FE::Parameters::fibre_direction: @p X
       * (x, y, z) [m] in, the unit direction @p M [-] out. */
      void
      fibre_direction(const double *X, double *M) const;

      /**
       * The mesh: the section of create_yarn_section() swept along the
       * centreline in n_cells equal steps of x, each vertex of station x
       * at c(x) + u n(x) + v e_z for its section coordinates (u, v) =
       * (thickness, width); boundary ids of BoundaryIds. The cells are Q1
       * (straight edges between stations), so the mesh's volume
       * approaches the tube's, section area times centreline length, with
       * the square of the step.
       */
      void
      create_mesh(dealii::Triangulation<3, 3> &mesh) const;

    private:
      CrimpedYarnGeometry g;
      /** 2 pi / lambda [1/m]. */
      double k;
      /** Centreline height y(x) and its first two derivatives. */
      double
      height(const double x) const;
      double
      slope(const double x) const;
      double
      curvature_term(const double x) const;
    };
  } // namespace Fabric
} // namespace YarnImpact

#endif
