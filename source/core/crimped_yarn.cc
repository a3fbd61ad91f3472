#include <yarn_impact/core/crimped_yarn.h>
#include <yarn_impact/core/yarn_section.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <cmath>
#include <stdexcept>

namespace YarnImpact
{
  namespace Fabric
  {
    using namespace dealii;

    CrimpedYarn::CrimpedYarn(const CrimpedYarnGeometry &geometry)
      : g(geometry)
      , k(2. * numbers::PI / geometry.wavelength)
    {
      if (!(g.wavelength > 0.) || !(g.amplitude >= 0.) ||
          !(g.x_end > g.x_begin) || !(g.thickness_semi_axis > 0.) ||
          !(g.width_semi_axis > 0.) || g.n_cells == 0)
        throw std::invalid_argument(
          "CrimpedYarn: the wavelength, span, semi-axes and number of cells "
          "must be positive and the amplitude not negative");
      // The smallest radius of curvature of A sin(k x), 1/(A k^2), at the
      // crests: a section reaching past it would fold the tube there.
      if (g.amplitude * k * k * g.thickness_semi_axis >= 1.)
        throw std::invalid_argument(
          "CrimpedYarn: the thickness semi-axis reaches past the "
          "centreline's radius of curvature lambda^2/(4 pi^2 A): the yarn "
          "would fold");
    }


    double
    CrimpedYarn::height(const double x) const
    {
      return g.amplitude * std::sin(k * x + g.phase);
    }


    double
    CrimpedYarn::slope(const double x) const
    {
      return g.amplitude * k * std::cos(k * x + g.phase);
    }


    double
    CrimpedYarn::curvature_term(const double x) const
    {
      return -g.amplitude * k * k * std::sin(k * x + g.phase);
    }


    Point<3>
    CrimpedYarn::centreline(const double x) const
    {
      return Point<3>(x, height(x), 0.);
    }


    Tensor<1, 3>
    CrimpedYarn::tangent(const double x) const
    {
      const double s = slope(x);
      const double n = std::sqrt(1. + s * s);
      Tensor<1, 3> t;
      t[0] = 1. / n;
      t[1] = s / n;
      return t;
    }


    Tensor<1, 3>
    CrimpedYarn::normal(const double x) const
    {
      const double s = slope(x);
      const double n = std::sqrt(1. + s * s);
      Tensor<1, 3> m;
      m[0] = -s / n;
      m[1] = 1. / n;
      return m;
    }


    double
    CrimpedYarn::centreline_length() const
    {
      // 10 Gauss points on each eighth of a wavelength: the integrand
      // sqrt(1 + y'^2) is analytic, and the rule is exact to round-off.
      const QGauss<1> rule(10);
      const double span = g.x_end - g.x_begin;
      const unsigned int n_pieces =
        static_cast<unsigned int>(std::ceil(8. * span / g.wavelength));
      const double h = span / n_pieces;
      double length  = 0.;
      for (unsigned int i = 0; i < n_pieces; ++i)
        for (unsigned int q = 0; q < rule.size(); ++q)
          {
            const double x = g.x_begin + h * (i + rule.point(q)[0]);
            const double s = slope(x);
            length += h * rule.weight(q) * std::sqrt(1. + s * s);
          }
      return length;
    }


    double
    CrimpedYarn::crimp() const
    {
      return centreline_length() / (g.x_end - g.x_begin) - 1.;
    }


    double
    CrimpedYarn::abscissa_of(const Point<3> &X) const
    {
      // f(x) = (X - c(x)) . (1, y'(x)) = 0: the section through c(x) is
      // normal to the tangent. f' = -(1 + y'^2) + (X_y - y) y'' < 0 inside
      // the tube (|X_y - y| below the radius of curvature), so Newton's
      // method from X_x converges, quadratically, in a few steps.
      double x = X[0];
      for (unsigned int it = 0; it < 50; ++it)
        {
          const double s  = slope(x);
          const double d  = X[1] - height(x);
          const double f  = (X[0] - x) + d * s;
          const double df = -(1. + s * s) + d * curvature_term(x);
          const double dx = -f / df;
          x += dx;
          if (std::abs(dx) <= 1e-15 * (std::abs(x) + g.wavelength))
            break;
        }
      return x;
    }


    Tensor<1, 3>
    CrimpedYarn::fibre_direction(const Point<3> &X) const
    {
      return tangent(abscissa_of(X));
    }


    void
    CrimpedYarn::fibre_direction(const double *X, double *M) const
    {
      const Tensor<1, 3> t = fibre_direction(Point<3>(X[0], X[1], X[2]));
      for (unsigned int d = 0; d < 3; ++d)
        M[d] = t[d];
    }


    void
    CrimpedYarn::create_mesh(Triangulation<3, 3> &mesh) const
    {
      Triangulation<2> section;
      create_yarn_section(section,
                          g.thickness_semi_axis,
                          g.width_semi_axis,
                          g.section_refinements,
                          g.half_section,
                          g.preserve_section_area);
      const double span = g.x_end - g.x_begin;
      Triangulation<3> swept;
      GridGenerator::extrude_triangulation(section, g.n_cells + 1, span, swept);
      // The ends are the faces at the first and last station, and the
      // half section's symmetry plane the faces at v = 0; found before the
      // sweep, where they are the planes w = 0, w = span and v = 0.
      const double tol = 1e-6 * span / g.n_cells;
      for (const auto &cell : swept.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            face->set_boundary_id(std::abs(face->center()[2]) < tol ||
                                      std::abs(face->center()[2] - span) < tol
                                    ? BoundaryIds::end
                                  : g.half_section &&
                                      std::abs(face->center()[1]) <
                                        1e-9 * g.width_semi_axis
                                    ? BoundaryIds::symmetry_z
                                    : BoundaryIds::lateral);
      // The extrusion's (u, v, w) = (thickness, width, distance along x) to
      // c(x) + u n(x) + v e_z, x = x_begin + w. At A = 0 this is the
      // straight yarn's cyclic permutation (w + x_begin, u, v), which
      // keeps the cells' orientation; the crimp turns each section about
      // e_z, which keeps it too.
      GridTools::transform(
        [this](const Point<3> &p) {
          const double x       = p[2] + g.x_begin;
          const Point<3> c     = centreline(x);
          const Tensor<1, 3> n = normal(x);
          return Point<3>(c[0] + p[0] * n[0], c[1] + p[0] * n[1], p[1]);
        },
        swept);
      mesh.copy_triangulation(swept);
    }
  } // namespace Fabric
} // namespace YarnImpact
