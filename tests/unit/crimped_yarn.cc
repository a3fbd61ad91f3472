// The crimped yarn of the woven fabric (Fabric::CrimpedYarn) against closed
// forms: its centreline length and crimp against the complete elliptic
// integral of the second kind (by the arithmetic-geometric mean, itself
// checked by fine numerical quadrature), the mesh's volume against the
// section area times the centreline length (converging with the square of
// the step along the centreline), every cell's Jacobian positive at its
// vertices and Gauss points, the fibre direction at every Gauss point and
// vertex equal to the centreline tangent at the point's section (found
// here by bisection), and the straight limit A = 0 equal to the FE yarn
// mesh vertex for vertex.

#include <yarn_impact/core/crimped_yarn.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/fe/yarn_mesh.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace YarnImpact;
using dealii::Point;
using dealii::Tensor;

namespace
{
  /** Complete elliptic integral of the second kind E(m), m = k^2, by the
   * arithmetic-geometric mean: E = K (1 - sum_n 2^(n-1) c_n^2) with
   * K = pi / (2 AGM(1, sqrt(1 - m))). */
  double
  elliptic_E(const double m)
  {
    double a = 1., b = std::sqrt(1. - m), c = std::sqrt(m);
    double sum = 0.5 * c * c, power = 0.5;
    for (unsigned int n = 0; n < 40 && c > 1e-18; ++n)
      {
        c                   = 0.5 * (a - b);
        const double a_next = 0.5 * (a + b);
        b                   = std::sqrt(a * b);
        a                   = a_next;
        power *= 2.;
        sum += power * c * c;
      }
    return M_PI / (2. * a) * (1. - sum);
  }

  /** The length of A sin(k x) over whole wavelengths [m]: per wavelength
   * lambda/(2 pi) int_0^2pi sqrt(1 + m^2 cos^2) = lambda/(2 pi) 4
   * sqrt(1 + m^2) E(m^2 / (1 + m^2)), m = A k. */
  double
  closed_form_length(const double A,
                     const double lambda,
                     const double n_wavelengths)
  {
    const double m = A * 2. * M_PI / lambda;
    return n_wavelengths * lambda / (2. * M_PI) * 4. * std::sqrt(1. + m * m) *
           elliptic_E(m * m / (1. + m * m));
  }

  /** The same by composite Simpson on 2 10^5 intervals. */
  double
  simpson_length(const double A, const double lambda, const double span)
  {
    const unsigned int n = 200000;
    const double k = 2. * M_PI / lambda, h = span / n;
    double sum = 0.;
    for (unsigned int i = 0; i <= n; ++i)
      {
        const double s = A * k * std::cos(k * (-0.5 * span + i * h));
        const double f = std::sqrt(1. + s * s);
        sum += (i == 0 || i == n ? 1. : (i % 2 ? 4. : 2.)) * f;
      }
    return sum * h / 3.;
  }

  /** The abscissa of the section through X, found by bisection of
   * (X - c(x)) . t(x) on [X_x - lambda/8, X_x + lambda/8]: independent of
   * the generator's Newton iteration. */
  double
  bisect_abscissa(const Fabric::CrimpedYarn &yarn, const Point<3> &X)
  {
    const double w = yarn.geometry().wavelength / 8.;
    double lo = X[0] - w, hi = X[0] + w;
    const auto f = [&](const double x) {
      return (X - yarn.centreline(x)) * yarn.tangent(x);
    };
    const double f_lo = f(lo);
    for (unsigned int it = 0; it < 200 && hi - lo > 1e-17; ++it)
      {
        const double mid = 0.5 * (lo + hi);
        if ((f(mid) > 0.) == (f_lo > 0.))
          lo = mid;
        else
          hi = mid;
      }
    return 0.5 * (lo + hi);
  }
} // namespace

int
main()
{
  Fabric::CrimpedYarnGeometry g; // A = 0.1 mm, lambda = 2 mm, 2 wavelengths
  const double span = g.x_end - g.x_begin;

  std::printf("centreline of A sin(2 pi x / lambda), A = %.2f mm, lambda = "
              "%.1f mm, %.0f wavelengths\n",
              g.amplitude * 1e3,
              g.wavelength * 1e3,
              span / g.wavelength);
  {
    const Fabric::CrimpedYarn yarn(g);
    const double exact  = closed_form_length(g.amplitude, g.wavelength, 2.);
    const double simple = simpson_length(g.amplitude, g.wavelength, span);
    const double length = yarn.centreline_length();
    std::printf("  length, elliptic integral   %.9f mm\n", exact * 1e3);
    std::printf("  elliptic integral against Simpson (2e5 intervals): %s\n",
                std::abs(simple / exact - 1.) < 1e-12 ? "OK" : "WRONG");
    std::printf("  generator's length against the closed form: %s\n",
                std::abs(length / exact - 1.) < 1e-12 ? "OK" : "WRONG");
    std::printf("  crimp %.6f %%, closed form %.6f %% %s\n",
                100. * yarn.crimp(),
                100. * (exact / span - 1.),
                std::abs(yarn.crimp() - (exact / span - 1.)) < 1e-12 ? "OK"
                                                                     : "WRONG");
  }

  std::printf("swept volume against section area x centreline length "
              "(area-preserving section)\n");
  double previous_error = 0.;
  for (const unsigned int n_cells : {16u, 32u, 64u, 128u})
    {
      g.n_cells = n_cells;
      const Fabric::CrimpedYarn yarn(g);
      dealii::Triangulation<3> mesh;
      yarn.create_mesh(mesh);
      const double tube = M_PI * g.thickness_semi_axis * g.width_semi_axis *
                          yarn.centreline_length();
      const double error = dealii::GridTools::volume(mesh) / tube - 1.;
      std::printf("  %3u cells along: volume / tube - 1 = %.3e",
                  n_cells,
                  error);
      if (previous_error != 0.)
        std::printf(", error ratio %.2f %s",
                    previous_error / error,
                    std::abs(previous_error / error - 4.) < 0.2
                      ? "(second order)"
                      : "NOT CONVERGING");
      std::printf("\n");
      previous_error = error;
    }

  std::printf("Jacobians and fibre directions, 64 cells along, one section "
              "refinement\n");
  {
    g.n_cells             = 64;
    g.section_refinements = 1;
    const Fabric::CrimpedYarn yarn(g);
    dealii::Triangulation<3> mesh;
    yarn.create_mesh(mesh);
    dealii::FE_Q<3> fe(1);
    const dealii::MappingQ1<3> mapping;
    double min_det = 1e300, max_det = 0., worst_M = 0., worst_unit = 0.,
           largest_angle = 0.;
    // The Gauss points (where the laws take M) and the vertices (where a
    // trilinear cell's Jacobian is smallest).
    for (const dealii::Quadrature<3> &rule :
         {dealii::Quadrature<3>(dealii::QGauss<3>(2)),
          dealii::Quadrature<3>(dealii::QTrapezoid<1>())})
      {
        dealii::FEValues<3> values(mapping,
                                   fe,
                                   rule,
                                   dealii::update_JxW_values |
                                     dealii::update_quadrature_points);
        for (const auto &cell : mesh.active_cell_iterators())
          {
            values.reinit(cell);
            for (unsigned int q = 0; q < rule.size(); ++q)
              {
                const double det     = values.JxW(q) / rule.weight(q);
                min_det              = std::min(min_det, det);
                max_det              = std::max(max_det, det);
                const Point<3> &X    = values.quadrature_point(q);
                const Tensor<1, 3> M = yarn.fibre_direction(X);
                const Tensor<1, 3> t = yarn.tangent(bisect_abscissa(yarn, X));
                worst_M              = std::max(worst_M, (M - t).norm());
                worst_unit    = std::max(worst_unit, std::abs(M.norm() - 1.));
                largest_angle = std::max(largest_angle, std::acos(M[0]));
              }
          }
      }
    std::printf("  %u cells, smallest / largest det J %.4f: %s\n",
                mesh.n_active_cells(),
                min_det / max_det,
                min_det > 0. ? "all positive" : "NOT ALL POSITIVE");
    std::printf("  M = centreline tangent at the point's section: %s\n",
                worst_M < 1e-12 ? "OK" : "WRONG");
    std::printf("  |M| = 1: %s\n", worst_unit < 1e-14 ? "OK" : "WRONG");
    std::printf("  largest angle of M to x %.4f deg, atan(A k) %.4f deg\n",
                largest_angle * 180. / M_PI,
                std::atan(g.amplitude * 2. * M_PI / g.wavelength) * 180. /
                  M_PI);
  }

  std::printf("straight limit A = 0 against FE::create_yarn_mesh\n");
  {
    g.amplitude           = 0.;
    g.n_cells             = 20;
    g.section_refinements = 0;
    g.x_begin             = -0.5 * 0.0254;
    g.x_end               = 0.5 * 0.0254;
    dealii::Triangulation<3> crimped, straight;
    Fabric::CrimpedYarn(g).create_mesh(crimped);
    Parameters::Yarn yarn;
    yarn.length              = 0.0254;
    yarn.thickness_semi_axis = g.thickness_semi_axis;
    yarn.width_semi_axis     = g.width_semi_axis;
    FE::create_yarn_mesh(straight,
                         yarn,
                         Parameters::Symmetry::none,
                         20,
                         0,
                         true);
    bool same = crimped.n_vertices() == straight.n_vertices();
    for (unsigned int v = 0; same && v < crimped.n_vertices(); ++v)
      same = crimped.get_vertices()[v] == straight.get_vertices()[v];
    std::printf("  the same vertices, bit for bit: %s\n",
                same ? "OK" : "WRONG");
  }
}
