// Smith theory (doc/theory.md section 2.3) for the DEM fibre data (linear
// law) and for the FE continuum (P = k_e ln(1+e)/(1+e)), at 120 m/s.

#include <yarn_impact/analysis/smith_theory.h>

#include <cmath>
#include <cstdio>

using namespace YarnImpact;

namespace
{
  void
  print(const char *name,
        const double value,
        const double reference,
        const double tolerance)
  {
    const bool ok =
      std::abs(value - reference) <= tolerance * std::abs(reference);
    std::printf("  %-30s %12.5f  reference %12.5f  %s\n",
                name,
                value,
                reference,
                ok ? "OK" : "WRONG");
  }
} // namespace

int
main()
{
  const double mass = 9.91e-6, V = 120.;

  AxialProperties dem;
  dem.area           = 400. * M_PI * 36e-12;
  dem.density        = 1440.;
  dem.modulus        = 84.62e9;
  dem.nominal_stress = [](const double e) { return 84.62e9 * e; };
  const auto s       = Analysis::smith_solution(dem, V, mass);
  std::printf("DEM fibre data, linear law\n");
  print("wave speed [m/s]", s.wave_speed, 7665.8, 1e-4);
  print("strain [%]", 100. * s.strain, 0.2507, 1e-3);
  print("inflow velocity [m/s]", s.inflow_velocity, 19.22, 1e-3);
  print("material-frame speed [m/s]", s.material_speed, 383.3, 1e-3);
  print("lab-frame speed [m/s]", s.lab_speed, 365.1, 1e-3);
  print("angle [deg]", s.angle * 180. / M_PI, 18.20, 1e-3);
  print("tension [N]", s.tension, 9.596, 1e-3);
  print("force [N]", s.force, 5.993, 1e-3);
  print("deceleration [1e5 m/s^2]", 1e-5 * s.deceleration, 6.05, 2e-3);
  print("critical velocity [m/s]",
        Analysis::critical_velocity(dem, 0.0452),
        1017.,
        1e-3);
  // Closed-form linear Smith: V = c sqrt(2 e sqrt(e(1+e)) - e^2).
  const double e = s.strain, c = s.wave_speed;
  print("V from closed form [m/s]",
        c * std::sqrt(2. * e * std::sqrt(e * (1. + e)) - e * e),
        V,
        1e-9);

  AxialProperties fe;
  fe.area           = M_PI * 0.0575e-3 * 0.267e-3;
  fe.density        = 1267.;
  fe.modulus        = 80077.19e6;
  fe.nominal_stress = [](const double e) {
    return 80077.19e6 * std::log1p(e) / (1. + e);
  };
  const auto f = Analysis::smith_solution(fe, V, mass);
  std::printf("FE continuum, P = k_e ln(1+e)/(1+e)\n");
  print("wave speed [m/s]", f.wave_speed, 7950.0, 1e-4);
  print("strain [%]", 100. * f.strain, 0.2393, 1e-3);
  print("inflow velocity [m/s]", f.inflow_velocity, 18.99, 1e-3);
  print("material-frame speed [m/s]", f.material_speed, 387.7, 1e-3);
  print("lab-frame speed [m/s]", f.lab_speed, 369.7, 1e-3);
  print("tension [N]", f.tension, 9.209, 1e-3);
  print("force [N]", f.force, 5.687, 1e-3);
  print("deceleration [1e5 m/s^2]", 1e-5 * f.deceleration, 5.74, 2e-3);
  print("critical velocity [m/s]",
        Analysis::critical_velocity(fe, 0.0452),
        1020.,
        2e-3);
}
