#ifndef yarn_impact_analysis_smith_theory_h
#define yarn_impact_analysis_smith_theory_h

#include <yarn_impact/core/impact_model.h>

namespace YarnImpact
{
  namespace Analysis
  {
    /**
     * Smith's solution for a long yarn hit transversely at constant speed
     * \f$V\f$ (doc/theory.md section 2.1), generalised to a nonlinear nominal
     * stress \f$P(\varepsilon)\f$:
     * \f[
     *   c(\varepsilon) = \sqrt{P'(\varepsilon)/\rho},\quad
     *   w = \int_0^\varepsilon c(e)\,de,\quad
     *   U = \sqrt{P(\varepsilon)/(\rho(1+\varepsilon))},\quad
     *   V^2 = w\,(2(1+\varepsilon)U - w),
     * \f]
     * which reduces to Smith's formula for \f$P = E\varepsilon\f$.
     */
    struct SmithSolution
    {
      /** Small-strain longitudinal wave speed \f$c(0)\f$ [m/s]. */
      double wave_speed = 0.;
      /** Strain behind the longitudinal front [-]. */
      double strain = 0.;
      /** Inflow velocity of the material towards the impact point [m/s]. */
      double inflow_velocity = 0.;
      /** Transverse wave speed in the material frame [m/s]. */
      double material_speed = 0.;
      /** Transverse wave speed in the laboratory frame [m/s]. */
      double lab_speed = 0.;
      /** Deflection angle of the yarn arms [rad]. */
      double angle = 0.;
      /** Yarn tension [N]. */
      double tension = 0.;
      /** Force of the two arms on the projectile [N]. */
      double force = 0.;
      /** Deceleration of the projectile, force / mass [m/s^2]. */
      double deceleration = 0.;
    };

    /**
     * Solve Smith's relations for the yarn @p axial hit at @p impact_speed
     * [m/s] by a projectile of mass @p projectile_mass [kg].
     */
    SmithSolution
    smith_solution(const AxialProperties &axial,
                   const double impact_speed,
                   const double projectile_mass);

    /** Impact speed that gives the strain @p failure_strain behind the
     * longitudinal front: Smith's critical velocity [m/s]. */
    double
    critical_velocity(const AxialProperties &axial,
                      const double failure_strain);
  } // namespace Analysis
} // namespace YarnImpact

#endif
