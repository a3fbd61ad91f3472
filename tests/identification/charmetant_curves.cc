// Curves of the FE code's Charmetant law along the paths of the DEM
// elementary tests, written as the CSVs the DEM writes: the identification
// script must recover the constants they were made with (test
// identification/synthetic_recovery).
#include <yarn_impact/fe/constitutive_law.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

using namespace YarnImpact;

namespace
{
  const char *header =
    "loading,confining_pressure,phase,time,imposed_strain,F_xx,F_yy,F_yz,"
    "F_zy,F_zz,I_e,I_tc,I_td,height,width,tau_xx,tau_yy,tau_zz,tau_yz,"
    "tau_yy_boundary,tau_zz_boundary,plate_gap,plate_load,wall_gap,"
    "wall_load,kinetic_energy,truss_energy,contact_energy,"
    "dissipated_energy,broken_fibres";

  /** One row: the law's Kirchhoff stress tau = P F^T at F. */
  void
  row(std::ofstream &out,
      const FE::CharmetantLaw &law,
      const std::string &loading,
      const double pressure,
      const double strain,
      const Mechanics::Matrix3 &F)
  {
    Mechanics::Matrix3 P;
    Mechanics::Invariants inv;
    law.stress(F, P, inv);
    double tau[9];
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        tau[3 * i + j] = P[3 * i] * F[3 * j] + P[3 * i + 1] * F[3 * j + 1] +
                         P[3 * i + 2] * F[3 * j + 2];
    out << loading << ',' << pressure << ",load,0," << strain << ',' << F[0]
        << ',' << F[4] << ',' << F[5] << ',' << F[7] << ',' << F[8] << ','
        << inv.elongation << ',' << inv.compaction << ',' << inv.distortion
        << ",0,0," << tau[0] << ',' << tau[4] << ',' << tau[8] << ',' << tau[5]
        << ",0,0,0,0,0,0,0,0,0,0,0\n";
  }
} // namespace

int
main(int argc, char **argv)
{
  if (argc != 5)
    {
      std::cerr << "usage: charmetant_curves k_e k_tc p k_td (Pa, -, Pa)\n";
      return 2;
    }
  FE::CharmetantParameters c;
  c.k_e  = std::atof(argv[1]);
  c.k_tc = std::atof(argv[2]);
  c.p    = std::atof(argv[3]);
  c.k_td = std::atof(argv[4]);
  const FE::CharmetantLaw law(c, 1267.);

  std::ofstream t("elementary_tension.csv");
  t.precision(17);
  t << header << '\n';
  for (unsigned int k = 0; k <= 40; ++k)
    {
      const double e             = 0.045 * k / 40.;
      const Mechanics::Matrix3 F = {1. + e, 0., 0., 0., 1., 0., 0., 0., 1.};
      row(t, law, "tension", 0., e, F);
    }

  // Compaction: the section thins and spreads, with a little shear.
  std::ofstream cp("elementary_compaction.csv");
  cp.precision(17);
  cp << header << '\n';
  for (unsigned int k = 0; k <= 40; ++k)
    {
      const double e  = 0.3 * k / 40.;
      const double ly = 1. - e, lz = std::pow(ly, -0.6);
      const Mechanics::Matrix3 F =
        {1., 0., 0., 0., ly, 0.02 * e, 0., -0.01 * e, lz};
      row(cp, law, "compaction", 0., e, F);
    }

  // Distortion at two confinements: nearly constant area.
  std::ofstream d("elementary_distortion.csv");
  d.precision(17);
  d << header << '\n';
  for (const double area : {0.97, 0.93})
    for (unsigned int k = 0; k <= 40; ++k)
      {
        const double e  = 0.3 * k / 40.;
        const double ly = area * (1. - e), lz = area / (1. - e);
        const Mechanics::Matrix3 F = {1., 0., 0., 0., ly, 0., 0., 0., lz};
        row(d, law, "distortion", area < 0.95 ? 5e7 : 1e7, e, F);
      }
  return 0;
}
