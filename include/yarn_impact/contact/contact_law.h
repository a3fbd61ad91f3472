#ifndef yarn_impact_contact_contact_law_h
#define yarn_impact_contact_contact_law_h

#include <yarn_impact/contact/contact_constants.h>
#include <yarn_impact/contact/cundall_strack_law.h>
#include <yarn_impact/contact/penalty_coulomb_law.h>

#include <stdexcept>
#include <string>
#include <type_traits>

namespace YarnImpact
{
  namespace Contact
  {
    /**
     * @page contact_law_contract The contact-law contract
     *
     * A contact law gives the force between a body and what it touches
     * (the projectile, another fibre, a wall) from the overlap and the
     * relative velocity of one contact point. The models' force loops are
     * templates on the law, so that the law inlines into the loop over
     * contacts; a law is a concept, not a virtual interface. A class `Law`
     * is a contact law when it is built from ContactConstants and a
     * `const Law` provides
     *
     * - `static constexpr unsigned int history_size`: the doubles of
     *   tangential history the caller keeps per contact (at most 3), zeroed
     *   when a contact starts; 0 for none.
     * - `double normal_force(double delta, double v_n, double dt,
     *   double &dissipated)`: the normal force [N] (positive pushes the
     *   bodies apart) at the overlap `delta` > 0 [m] and the normal
     *   relative velocity `v_n` [m/s] (the overlap rate is -v_n); the
     *   energy the normal damping takes over the step `dt` [s] is added to
     *   `dissipated` [J].
     * - `double friction_limit(double f_n)`: Coulomb's bound on the
     *   tangential force at the normal force `f_n` [N].
     * - `void tangential_force(const double *n, const double *v_rel,
     *   double v_n, double f_n, double dt, double *history, double *f_t,
     *   double &dissipated)`: the tangential (friction) force `f_t` [N],
     *   never above friction_limit(f_n), of the contact with unit normal
     *   `n` (towards the body that feels the force) and relative velocity
     *   `v_rel` [m/s]; it updates `history` and adds its slip work to
     *   `dissipated` [J].
     * - `double energy(double delta, const double *history)`: the energy
     *   stored in the contact [J].
     *
     * contact_force() puts the two parts together; check_contact_law_contract()
     * states the contract at compile time. Both models' stable steps assume a
     * linear normal spring of stiffness ContactConstants::stiffness with
     * viscous damping (fe/contact.cc, DEM::critical_time_step); a law that
     * is stiffer than that must shorten them too.
     *
     * A new law: its own header beside cundall_strack_law.h, and one entry
     * in YARN_IMPACT_CONTACT_FOR_EACH_LAW below; the models' projectile
     * contacts (`FE/Contact/Law`, `DEM/Projectile contact law`) then offer
     * it, and their force loops and energies are instantiated for it.
     */

    /**
     * The laws, one entry X(law type, class, parameter value) each: the
     * selection of the parameters, law_type() and with_contact_law() are
     * made from it.
     */
#define YARN_IMPACT_CONTACT_FOR_EACH_LAW(X)             \
  X(cundall_strack, CundallStrackLaw, "Cundall-Strack") \
  X(penalty_coulomb, PenaltyCoulombLaw, "Penalty-Coulomb")

    /** Which contact law (one value an entry of
     * YARN_IMPACT_CONTACT_FOR_EACH_LAW). */
    enum class LawType
    {
#define YARN_IMPACT_CONTACT_LAW_VALUE(type, Law, name) type,
      YARN_IMPACT_CONTACT_FOR_EACH_LAW(YARN_IMPACT_CONTACT_LAW_VALUE)
#undef YARN_IMPACT_CONTACT_LAW_VALUE
    };


    /** The parameter values of the laws, "A|B|...", for a
     * dealii::Patterns::Selection. */
    inline std::string
    law_selection()
    {
      std::string names;
#define YARN_IMPACT_CONTACT_LAW_NAME(type, Law, name) \
  names += (names.empty() ? "" : "|") + std::string(name);
      YARN_IMPACT_CONTACT_FOR_EACH_LAW(YARN_IMPACT_CONTACT_LAW_NAME)
#undef YARN_IMPACT_CONTACT_LAW_NAME
      return names;
    }


    /** The law of the parameter value @p name (one of law_selection()). */
    inline LawType
    law_type(const std::string &name)
    {
#define YARN_IMPACT_CONTACT_LAW_PARSE(type, Law, value) \
  if (name == value)                                    \
    return LawType::type;
      YARN_IMPACT_CONTACT_FOR_EACH_LAW(YARN_IMPACT_CONTACT_LAW_PARSE)
#undef YARN_IMPACT_CONTACT_LAW_PARSE
      throw std::invalid_argument("unknown contact law '" + name + "'");
    }


    /** Compile-time check that @p Law provides what the contact-law
     * contract asks for (see the page above). */
    template <class Law>
    constexpr bool
    check_contact_law_contract()
    {
      const Law *law  = nullptr;
      double *pointer = nullptr;
      double value    = 0.;
      static_assert(std::is_constructible_v<Law, const ContactConstants &>,
                    "a law is built from ContactConstants");
      static_assert(
        std::is_same_v<decltype(Law::history_size), const unsigned int> &&
          Law::history_size <= 3,
        "a law says how much history it keeps (at most 3)");
      static_assert(
        std::is_same_v<decltype(law->normal_force(0., 0., 0., value)), double>,
        "a law needs double normal_force(delta, v_n, dt, dissipated) const");
      static_assert(std::is_same_v<decltype(law->friction_limit(0.)), double>,
                    "a law needs double friction_limit(f_n) const");
      static_assert(std::is_void_v<decltype(law->tangential_force(pointer,
                                                                  pointer,
                                                                  0.,
                                                                  0.,
                                                                  0.,
                                                                  pointer,
                                                                  pointer,
                                                                  value))>,
                    "a law needs void tangential_force(n, v_rel, v_n, f_n, "
                    "dt, history, f_t, dissipated) const");
      static_assert(std::is_same_v<decltype(law->energy(0., pointer)), double>,
                    "a law needs double energy(delta, history) const");
      return true;
    }


    /**
     * The force @p f [N] of @p law on the body of a contact with the
     * overlap @p delta > 0 [m], the unit normal @p n (towards the body) and
     * the relative velocity @p v_rel [m/s] of the body, over the step
     * @p dt [s]: the normal force along @p n plus the tangential force.
     * The law's @p history is updated and the energy it dissipates in the
     * step is added to @p dissipated [J] (damping first, then slip).
     */
    template <class Law>
    inline void
    contact_force(const Law &law,
                  const double delta,
                  const double *n,
                  const double *v_rel,
                  const double dt,
                  double *history,
                  double *f,
                  double &dissipated)
    {
      const double v_n = v_rel[0] * n[0] + v_rel[1] * n[1] + v_rel[2] * n[2];
      const double f_n = law.normal_force(delta, v_n, dt, dissipated);
      double f_t[3];
      law.tangential_force(n, v_rel, v_n, f_n, dt, history, f_t, dissipated);
      for (unsigned int d = 0; d < 3; ++d)
        f[d] = f_n * n[d] + f_t[d];
    }


    /** The type @p Law, handed to the visitor of with_contact_law(). */
    template <class Law>
    struct LawTag
    {
      /** The law's class. */
      using type = Law;
    };


    /**
     * Calls @p visitor with LawTag<Law> of the law @p type and returns what
     * it returns (the same type for every law). The visitor builds the
     * law from its contacts' ContactConstants: one switch per force
     * evaluation, none per contact.
     */
    template <class Visitor>
    auto
    with_contact_law(const LawType type, Visitor &&visitor)
    {
      switch (type)
        {
#define YARN_IMPACT_CONTACT_SELECT_LAW(type, Law, name) \
  case LawType::type:                                   \
    static_assert(check_contact_law_contract<Law>());   \
    return visitor(LawTag<Law>());
          YARN_IMPACT_CONTACT_FOR_EACH_LAW(YARN_IMPACT_CONTACT_SELECT_LAW)
#undef YARN_IMPACT_CONTACT_SELECT_LAW
        }
      throw std::logic_error("a contact law without a selector entry");
    }
  } // namespace Contact
} // namespace YarnImpact

#endif
