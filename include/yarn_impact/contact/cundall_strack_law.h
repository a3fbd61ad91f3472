#ifndef yarn_impact_contact_cundall_strack_law_h
#define yarn_impact_contact_cundall_strack_law_h

#include <yarn_impact/contact/contact_constants.h>

#include <cmath>

namespace YarnImpact
{
  namespace Contact
  {
    /**
     * Linear spring-dashpot contact with a tangential spring and Coulomb's
     * limit (Cundall-Strack): the DEM's law, of the fibre-fibre contacts,
     * the rigid walls of the elementary tests and, by default, the
     * projectile. It keeps a tangential history (the spring's elongation)
     * per contact, and its normal force may pull while the bodies separate
     * fast (the damping is not clipped). Fulfils the contract of
     * contact_law.h.
     */
    struct CundallStrackLaw
    {
      /** Doubles of tangential history per contact: the elongation
       * \f$\xi\f$ of the tangential spring [m]. */
      static constexpr unsigned int history_size = 3;

      /** Normal stiffness \f$k_n\f$ [N/m]. */
      double k_n = 0.;
      /** Normal damping \f$c_n = 2\zeta\sqrt{m_{eff} k_n}\f$ [N s/m]. */
      double c_n = 0.;
      /** Tangential stiffness \f$k_t\f$ [N/m]. */
      double k_t = 0.;
      /** Coulomb friction coefficient \f$\mu\f$ [-]. */
      double mu = 0.;

      /** A law without stiffness (set the members). */
      CundallStrackLaw() = default;

      /** The law of @p constants: stiffness, damping, tangential stiffness
       * and friction (not the mass). */
      explicit CundallStrackLaw(const ContactConstants &constants)
        : k_n(constants.stiffness)
        , c_n(constants.damping)
        , k_t(constants.tangential_stiffness)
        , mu(constants.friction)
      {}

      /**
       * Normal force [N], \f$F_n = k_n\delta - c_n v_n\f$, at the overlap
       * @p delta [m] and the normal relative velocity @p v_n [m/s]
       * (negative while approaching); not clipped, so that the rebound
       * follows the linear spring-dashpot exactly and the restitution is
       * \f$e = \exp(-\pi\zeta/\sqrt{1-\zeta^2})\f$. The damping work
       * \f$c_n v_n^2 dt\f$ over the step @p dt [s] is added to
       * @p dissipated [J].
       */
      inline double
      normal_force(const double delta,
                   const double v_n,
                   const double dt,
                   double &dissipated) const
      {
        const double fn = k_n * delta - c_n * v_n;
        dissipated += c_n * v_n * v_n * dt;
        return fn;
      }

      /** Coulomb's bound on the tangential force at the normal force
       * @p f_n [N]: \f$\mu\max(F_n, 0)\f$ [N]. */
      inline double
      friction_limit(const double f_n) const
      {
        return mu * (f_n > 0. ? f_n : 0.);
      }

      /**
       * Tangential force @p f_t [N] of the contact with unit normal @p n
       * and relative velocity @p v_rel [m/s] (normal part @p v_n), at the
       * normal force @p f_n [N]: the history @p xi [m] is first rotated onto
       * the current tangent plane (magnitude kept), then incremented by the
       * tangential relative velocity times @p dt [s];
       * \f$F_t = -k_t\xi\f$, limited to friction_limit() by shortening
       * \f$\xi\f$ (slip). The slip work, the limit force times the slip
       * length, is added to @p dissipated [J].
       */
      inline void
      tangential_force(const double *n,
                       const double *v_rel,
                       const double v_n,
                       const double f_n,
                       const double dt,
                       double *xi,
                       double *f_t,
                       double &dissipated) const
      {
        // Rotate the history onto the tangent plane, keeping its length.
        const double xn  = xi[0] * n[0] + xi[1] * n[1] + xi[2] * n[2];
        const double xx0 = xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2];
        double t[3] = {xi[0] - xn * n[0], xi[1] - xn * n[1], xi[2] - xn * n[2]};
        const double tt   = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
        const double keep = (tt > 0. ? std::sqrt(xx0 / tt) : 0.);
        for (unsigned int d = 0; d < 3; ++d)
          xi[d] = keep * t[d] + dt * (v_rel[d] - v_n * n[d]);

        for (unsigned int d = 0; d < 3; ++d)
          f_t[d] = -k_t * xi[d];
        const double ft2 = f_t[0] * f_t[0] + f_t[1] * f_t[1] + f_t[2] * f_t[2];
        const double limit = friction_limit(f_n);
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
                f_t[d] *= s;
              }
          }
      }

      /** Energy stored in the contact at the overlap @p delta [m] with the
       * history @p xi [m]: \f$\tfrac12 k_n\delta^2 + \tfrac12 k_t|\xi|^2\f$
       * [J]. */
      inline double
      energy(const double delta, const double *xi) const
      {
        return 0.5 * k_n * delta * delta +
               0.5 * k_t * (xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
      }
    };
  } // namespace Contact
} // namespace YarnImpact

#endif
