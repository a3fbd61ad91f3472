#ifndef yarn_impact_contact_contact_constants_h
#define yarn_impact_contact_contact_constants_h

#include <cmath>

namespace YarnImpact
{
  /**
   * Contact laws shared by the models (doc/architecture.md section 3): the
   * contract a law fulfils and the law list are in contact_law.h, one law a
   * header beside it, the projectile's geometry in projectile_contact.h.
   * This folder includes nothing from the models.
   */
  namespace Contact
  {
    /**
     * The constants of one contact, from which every law is built: each
     * model derives them from its own parameters (the FE per surface node
     * from the penalty per area, the DEM per sphere from the truss
     * stiffness), so that a law does not know which model uses it. A law
     * uses the ones it needs and says which.
     */
    struct ContactConstants
    {
      /** Normal stiffness \f$k_n\f$ [N/m]. */
      double stiffness = 0.;
      /** Normal viscous damping \f$c_n\f$ [N s/m] (critical_damping()). */
      double damping = 0.;
      /** Tangential stiffness \f$k_t\f$ [N/m]. */
      double tangential_stiffness = 0.;
      /** Coulomb friction coefficient \f$\mu\f$ [-]. */
      double friction = 0.;
      /** Mass of the body in contact [kg] (a law may bound its friction
       * force by what stops this mass within a step). */
      double mass = 0.;
    };


    /**
     * The viscous damping \f$c = 2\zeta\sqrt{m k}\f$ [N s/m] that is the
     * fraction @p damping_ratio \f$\zeta\f$ [-] of the critical damping of
     * a mass @p mass [kg] on a spring of stiffness @p stiffness [N/m] (for a
     * contact of two equal free bodies, @p mass is the reduced mass).
     */
    inline double
    critical_damping(const double damping_ratio,
                     const double mass,
                     const double stiffness)
    {
      return 2. * damping_ratio * std::sqrt(mass * stiffness);
    }
  } // namespace Contact
} // namespace YarnImpact

#endif
