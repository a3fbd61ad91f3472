#ifndef yarn_impact_dem_contact_law_h
#define yarn_impact_dem_contact_law_h

#include <cmath>

namespace YarnImpact
{
  namespace DEM
  {
    /**
     * Constants of one kind of contact (fibre-fibre, projectile-fibre):
     * linear normal penalty spring with viscous damping, linear tangential
     * spring with Coulomb's limit (Cundall-Strack).
     */
    struct ContactLaw
    {
      /** Normal stiffness \f$k_n\f$ [N/m]. */
      double k_n = 0.;
      /** Normal damping \f$c_n = 2\zeta\sqrt{m_{eff} k_n}\f$ [N s/m]. */
      double c_n = 0.;
      /** Tangential stiffness \f$k_t\f$ [N/m]. */
      double k_t = 0.;
      /** Coulomb friction coefficient \f$\mu\f$ [-]. */
      double mu = 0.;

      /**
       * Force on body i of a contact with overlap @p delta > 0.
       *
       * Normal: \f$F_n = k_n\delta - c_n v_n\f$ along @p n (unit, pointing
       * from j to i), with \f$v_n = (v_i - v_j)\cdot n\f$; it is not clipped,
       * so the rebound follows the linear spring-dashpot exactly and
       * \f$e = \exp(-\pi\zeta/\sqrt{1-\zeta^2})\f$.
       *
       * Tangential: the history (spring elongation) @p xi is first rotated
       * onto the current tangent plane (magnitude kept), then incremented by
       * the tangential relative velocity times @p dt; \f$F_t = -k_t\xi\f$,
       * limited to \f$\mu\max(F_n,0)\f$ by shortening \f$\xi\f$ (slip).
       * Dissipated: the damping work \f$c_n v_n^2 dt\f$ and the slip work
       * \f$\mu F_n\f$ times the slip length.
       *
       * @param[in,out] xi tangential history [m]
       * @param[out] f force on i [N]
       * @param[in,out] dissipated energy lost by damping and slip in the step
       * is added [J]
       */
      inline void
      force(const double delta,
            const double *n,
            const double *v_rel,
            const double dt,
            double *xi,
            double *f,
            double &dissipated) const
      {
        const double vn = v_rel[0] * n[0] + v_rel[1] * n[1] + v_rel[2] * n[2];
        const double fn = k_n * delta - c_n * vn;
        dissipated += c_n * vn * vn * dt;

        // Rotate the history onto the tangent plane, keeping its length.
        const double xn  = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2];
        const double xx0 = xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2];
        double t[3] = {xi[0] - xn * n[0], xi[1] - xn * n[1], xi[2] - xn * n[2]};
        const double tt   = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
        const double keep = (tt > 0. ? std::sqrt(xx0 / tt) : 0.);
        for (unsigned int d = 0; d < 3; ++d)
          xi[d] = keep * t[d] + dt * (v_rel[d] - vn * n[d]);

        double ft[3]       = {-k_t * xi[0], -k_t * xi[1], -k_t * xi[2]};
        const double ft2   = ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2];
        const double limit = mu * (fn > 0. ? fn : 0.);
        if (ft2 > limit * limit)
          {
            // Slip: the work of the limit force over the slip length
            // |xi| (1 - s). (The drop of the spring energy from the trial
            // state, 0.5 k_t |xi|^2 (1 - s^2), counts 0.5 k_t |slip|^2 too
            // much per step, which the bodies never lost: it made the
            // balance drift by several per cent once cut fibres slid fast
            // along light contacts.)
            const double xi_norm = std::sqrt(ft2) / k_t;
            const double s       = limit / std::sqrt(ft2);
            dissipated += limit * xi_norm * (1. - s);
            for (unsigned int d = 0; d < 3; ++d)
              {
                xi[d] *= s;
                ft[d] *= s;
              }
          }
        for (unsigned int d = 0; d < 3; ++d)
          f[d] = fn * n[d] + ft[d];
      }

      /** Energy stored in the contact: \f$\tfrac12 k_n\delta^2 +
       * \tfrac12 k_t|\xi|^2\f$ [J]. */
      inline double
      energy(const double delta, const double *xi) const
      {
        return 0.5 * k_n * delta * delta +
               0.5 * k_t * (xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
      }
    };

    /**
     * Axial force of a truss, geometrically exact: \f$T = k(l - L_0)\f$
     * along the current direction.
     * @return the engineering strain \f$l/L_0 - 1\f$
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
