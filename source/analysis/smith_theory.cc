#include <yarn_impact/analysis/smith_theory.h>

#include <cmath>
#include <stdexcept>

namespace YarnImpact
{
  namespace Analysis
  {
    namespace
    {
      /** Wave speed c(e) = sqrt(P'(e)/rho), P' by a central difference. */
      double
      wave_speed(const AxialProperties &axial, const double e)
      {
        const double h  = 1e-7;
        const double dp = (axial.nominal_stress(e + h) -
                           axial.nominal_stress(std::max(e - h, -h))) /
                          (e + h - std::max(e - h, -h));
        return std::sqrt(std::max(dp, 0.) / axial.density);
      }

      /** w(eps) = int_0^eps c(e) de by composite Gauss-Legendre (3 points on
       * 64 intervals): exact to round-off for the smooth laws used here. */
      double
      inflow_velocity(const AxialProperties &axial, const double eps)
      {
        const unsigned int n = 64;
        const double h       = eps / n;
        const double g       = std::sqrt(0.6);
        const double xg[3]   = {-g, 0., g};
        const double wg[3]   = {5. / 9., 8. / 9., 5. / 9.};
        double sum           = 0.;
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int q = 0; q < 3; ++q)
            sum += wg[q] * 0.5 * h *
                   wave_speed(axial, (i + 0.5) * h + 0.5 * h * xg[q]);
        return sum;
      }

      /** Impact speed that produces the strain eps. */
      double
      impact_speed_for_strain(const AxialProperties &axial, const double eps)
      {
        const double w = inflow_velocity(axial, eps);
        const double U =
          std::sqrt(axial.nominal_stress(eps) / (axial.density * (1. + eps)));
        return std::sqrt(std::max(w * (2. * (1. + eps) * U - w), 0.));
      }
    } // namespace

    SmithSolution
    smith_solution(const AxialProperties &axial,
                   const double impact_speed,
                   const double projectile_mass)
    {
      if (!(impact_speed > 0.) || !axial.nominal_stress)
        throw std::invalid_argument("Smith theory needs a positive speed");
      // V(eps) is increasing: bisection on [0, 0.5].
      double lo = 0., hi = 0.5;
      for (unsigned int it = 0; it < 200 && hi - lo > 1e-15; ++it)
        {
          const double mid = 0.5 * (lo + hi);
          (impact_speed_for_strain(axial, mid) < impact_speed ? lo : hi) = mid;
        }
      SmithSolution s;
      s.strain          = 0.5 * (lo + hi);
      s.wave_speed      = wave_speed(axial, 0.);
      s.inflow_velocity = inflow_velocity(axial, s.strain);
      s.material_speed  = std::sqrt(axial.nominal_stress(s.strain) /
                                   (axial.density * (1. + s.strain)));
      s.lab_speed    = (1. + s.strain) * s.material_speed - s.inflow_velocity;
      s.angle        = std::atan2(impact_speed, s.lab_speed);
      s.tension      = axial.nominal_stress(s.strain) * axial.area;
      s.force        = 2. * s.tension * std::sin(s.angle);
      s.deceleration = s.force / projectile_mass;
      return s;
    }

    double
    critical_velocity(const AxialProperties &axial, const double failure_strain)
    {
      return impact_speed_for_strain(axial, failure_strain);
    }
  } // namespace Analysis
} // namespace YarnImpact
