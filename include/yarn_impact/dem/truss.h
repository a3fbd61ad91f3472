#ifndef yarn_impact_dem_truss_h
#define yarn_impact_dem_truss_h

#include <cmath>

namespace YarnImpact
{
  namespace DEM
  {
    /**
     * Axial force of a truss, geometrically exact: \f$T = k(l - L_0)\f$
     * along the current direction, with the stiffness @p k [N/m] and the
     * rest length @p L0 [m].
     * @return the engineering strain \f$l/L_0 - 1\f$ [-]
     * @param e current vector from the first to the second end [m]
     * @param[out] f force on the first end (the second gets -f) [N]
     */
    inline double
    truss_force(const double *e, const double k, const double L0, double *f)
    {
      const double l = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
      const double s = k * (l - L0) / l;
      f[0]           = s * e[0];
      f[1]           = s * e[1];
      f[2]           = s * e[2];
      return l / L0 - 1.;
    }
  } // namespace DEM
} // namespace YarnImpact

#endif
