#ifndef yarn_impact_contact_penalty_coulomb_law_h
#define yarn_impact_contact_penalty_coulomb_law_h

#include <yarn_impact/contact/contact_constants.h>

#include <algorithm>
#include <cmath>

namespace YarnImpact
{
  namespace Contact
  {
    /**
     * Penalty contact with viscous damping that never pulls, and explicit
     * Coulomb friction on the tangential relative velocity (no tangential
     * spring, no history): the FE's law by default, as explicit impact
     * codes apply to surface nodes. Fulfils the contract of contact_law.h.
     */
    struct PenaltyCoulombLaw
    {
      /** No tangential history: the friction acts on the velocity. */
      static constexpr unsigned int history_size = 0;

      /** Normal (penalty) stiffness \f$k_n\f$ [N/m]. */
      double k_n = 0.;
      /** Normal damping \f$c_n\f$ [N s/m]; 0: none. */
      double c_n = 0.;
      /** Coulomb friction coefficient \f$\mu\f$ [-]; 0: none. */
      double mu = 0.;
      /** Mass of the body in contact [kg], which bounds the friction. */
      double mass = 0.;

      /** The law of @p constants: stiffness, damping, friction and mass
       * (not the tangential stiffness). */
      explicit PenaltyCoulombLaw(const ContactConstants &constants)
        : k_n(constants.stiffness)
        , c_n(constants.damping)
        , mu(constants.friction)
        , mass(constants.mass)
      {}

      /**
       * Normal force [N] at the overlap @p delta [m] and the normal
       * relative velocity @p v_n [m/s] (negative while approaching):
       * \f$F_n = k_n\delta + \max(-c_n v_n, -k_n\delta)\f$, so that the
       * damping never makes the contact pull. The damping work over the
       * step @p dt [s] is added to @p dissipated [J].
       */
      inline double
      normal_force(const double delta,
                   const double v_n,
                   const double dt,
                   double &dissipated) const
      {
        double fn = k_n * delta;
        if (c_n > 0.)
          {
            const double fd = std::max(-c_n * v_n, -fn);
            fn += fd;
            dissipated += -fd * v_n * dt;
          }
        return fn;
      }

      /** Coulomb's bound on the friction force at the normal force @p f_n
       * [N], \f$\mu F_n\f$ [N] (normal_force() is never negative). */
      inline double
      friction_limit(const double f_n) const
      {
        return mu * f_n;
      }

      /**
       * Friction force @p f_t [N] against the tangential relative velocity
       * \f$v_t\f$ of the contact with unit normal @p n and relative velocity
       * @p v_rel [m/s] (normal part @p v_n), at the normal force @p f_n [N]:
       * \f$F_t = -\min(\mu F_n, m|v_t|/dt)\, v_t/|v_t|\f$ over the step
       * @p dt [s]. Explicit Coulomb: the force never exceeds the one that
       * stops the slip within the step, so that sticking bodies do not
       * chatter. Its work is added to @p dissipated [J]; @p history is not
       * used.
       */
      inline void
      tangential_force(const double *n,
                       const double *v_rel,
                       const double v_n,
                       const double f_n,
                       const double dt,
                       double * /*history*/,
                       double *f_t,
                       double &dissipated) const
      {
        f_t[0] = f_t[1] = f_t[2] = 0.;
        if (!(mu > 0.))
          return;
        const double vt[3] = {v_rel[0] - v_n * n[0],
                              v_rel[1] - v_n * n[1],
                              v_rel[2] - v_n * n[2]};
        const double speed =
          std::sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
        const double stop = mass * speed / dt;
        const double scale =
          speed > 0. ? -std::min(friction_limit(f_n), stop) / speed : 0.;
        for (unsigned int d = 0; d < 3; ++d)
          f_t[d] = scale * vt[d];
        dissipated += -(f_t[0] * vt[0] + f_t[1] * vt[1] + f_t[2] * vt[2]) * dt;
      }

      /** Energy stored in the penalty spring at the overlap @p delta [m],
       * \f$\tfrac12 k_n\delta^2\f$ [J]; @p history is not used. */
      inline double
      energy(const double delta, const double * /*history*/) const
      {
        return 0.5 * k_n * delta * delta;
      }
    };
  } // namespace Contact
} // namespace YarnImpact

#endif
