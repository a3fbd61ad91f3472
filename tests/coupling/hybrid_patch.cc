// The patch test of the hybrid yarn (doc/hybrid.md section 4.2): the
// paper's yarn as `Model = hybrid` (400 DEM fibres on |x| <= a, the FE part
// beyond, overlaps of 2, 4 and 8 FE cells; each also with a second DEM
// part at the clamp and its overlap) at rest under a uniform axial stretch
// of 1e-7. No degree of freedom of the coupled system may feel a
// force: the largest is held below 1e-4 of one fibre's tension. What
// remains is round-off in the DEM's truss elongations and the two laws'
// difference at second order in the strain, both of order 1e-5 here; the
// section quadrature of the FE part (hybrid_model.cc) is what removes the
// ghost force of the fibres' uneven spread over the section nodes, 0.33 of
// a fibre's tension with Gauss quadrature (4 overlap cells). With a far
// field of fibre bars (doc/hybrid.md section 3.4) each fibre's bars and
// spheres share the stretch cell layer by cell layer, weights summing to
// one, so the same bound holds. The whole yarn (Symmetry = none: a second
// FE part, overlap and bars on x < 0, the mirror images of those on
// x > 0) must hold it on both sides.
//
// A physics check, no recorded numbers: `output` holds the verdicts, the
// measured values go to stdout; a failed check exits non-zero.

#include <yarn_impact/coupling/hybrid_model.h>

#include <deal.II/base/mpi.h>

#include <cstdio>
#include <fstream>

using namespace YarnImpact;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool root =
    dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  std::ofstream verdicts;
  if (root)
    verdicts.open("output");
  Parameters::Shared shared;
  FE::Parameters fe;
  DEM::Parameters dem;
  Coupling::HybridParameters hybrid;
  bool passed = true;
  for (const double w : {0.5e-3, 1e-3, 2e-3})
    {
      // A DEM part at the clamp (a second overlap) only with the
      // continuum's far field; fibre bars reach the clamp. Variants 3 and
      // 4: the whole yarn with each far field.
      for (const int variant : {0, 1, 2, 3, 4})
        {
          const bool whole        = variant >= 3;
          const double clamp      = variant == 1 ? 1.5e-3 + w : 0.;
          hybrid.overlap_width    = w;
          hybrid.dem_half_length  = 2e-3 + w;
          hybrid.clamp_dem_length = clamp;
          hybrid.fibre_bars       = variant == 2 || variant == 4;
          shared.general.symmetry =
            whole ? Parameters::Symmetry::none : Parameters::Symmetry::half;
          const double ghost =
            Coupling::patch_test(shared, fe, dem, hybrid, 1e-7, MPI_COMM_WORLD);
          const bool ok = ghost <= 1e-4;
          passed        = passed && ok;
          if (root)
            {
              std::printf("overlap %.1f mm%s%s: largest force %.3e of a "
                          "fibre's tension\n",
                          w * 1e3,
                          whole ? ", whole yarn" : "",
                          clamp > 0.          ? ", DEM part at the clamp"
                          : hybrid.fibre_bars ? ", far field of fibre bars"
                                              : "",
                          ghost);
              verdicts << (ok ? "PASS" : "FAIL") << " patch test, overlap of "
                       << w * 1e3
                       << (whole ? " mm, whole yarn (an FE part and an overlap "
                                   "on each side"
                           : clamp > 0. ? " mm, DEM parts at the nose and the "
                                          "clamp (two overlaps)"
                           : hybrid.fibre_bars
                             ? " mm, far field of fibre bars (each sphere's "
                               "axial motion tied to its fibre's bars)"
                             : " mm")
                       << (whole ? (hybrid.fibre_bars ? ", fibre bars)" : ")")
                                 : "")
                       << ": largest force on a degree of freedom under a "
                          "uniform stretch of 1e-7 <= 1e-4 of a fibre's "
                          "tension\n";
            }
        }
    }
  return passed ? 0 : 1;
}
