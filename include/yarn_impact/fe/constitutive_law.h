#ifndef yarn_impact_fe_constitutive_law_h
#define yarn_impact_fe_constitutive_law_h

#include <yarn_impact/fe/charmetant_law.h>
#include <yarn_impact/fe/linear_transversely_isotropic_law.h>
#include <yarn_impact/fe/parameters.h>
#include <yarn_impact/mechanics/kinematics.h>

#include <stdexcept>
#include <type_traits>
#include <utility>

namespace YarnImpact
{
  namespace FE
  {
    /**
     * @page fe_law_contract The constitutive-law contract
     *
     * The FE model (YarnModel) and its force loop (cell_kernel.h) are
     * templates on the law, so that the law's stress inlines into the loop
     * over Gauss points; a law is therefore a concept, not a virtual
     * interface. A class `Law` is a constitutive law when a `const Law`
     * provides
     *
     * - `double stress(const Matrix3 &F, Matrix3 &P, Invariants &inv)`
     *   (Matrix3 and Invariants of mechanics/kinematics.h):
     *   the first Piola-Kirchhoff stress P [Pa] (row-major) at the
     *   deformation gradient F (row-major, fibre direction x: a law is
     *   written in its fibre frame, and oriented_stress() turns it to any
     *   fibre direction), returning
     *   the strain-energy density W [J/m^3]. It must fill
     *   `inv.elongation` = ln(lambda_f), which the failure test and the
     *   strain outputs use; `inv.compaction` feeds transverse_modulus().
     * - `double axial_modulus()`: the P-wave modulus along the fibres [Pa]
     *   (stable time step, Smith's theory).
     * - `double transverse_modulus(const Invariants &inv)`: the P-wave
     *   modulus across the fibres at the compaction `inv.compaction` [Pa]
     *   (stable time step).
     * - `double uniaxial_nominal_stress(double strain)`: the nominal
     *   stress of a free bar at an axial strain [Pa] (Smith's theory).
     * - `double density`: the density [kg/m^3] (lumped mass).
     * - `static constexpr bool vectorised`: true when the law also has
     *   `template <typename V> V stress_kernel(const V (&F)[9],
     *   V (&P)[9], V &Ie, V &Itc, V &Itd)` for V = internal::Double4,
     *   four Gauss points at once (the same body as stress() is best, so
     *   that the scalar tests cover it); false and the force loop calls
     *   stress() one Gauss point at a time.
     * - `static constexpr bool separable_fibre_term`: true when the
     *   energy is 1/2 axial_modulus() I_e^2 plus terms that do not depend
     *   on I_e, and the stress's fibre part is therefore
     *   (axial_modulus() I_e / I4) F M (x) M: the progressive failure law
     *   (FailureLaw in cell_kernel.h) then damages that part alone,
     *   outside the law. False and `Yarn/Failure model = progressive` is
     *   refused with this law.
     *
     * The law must be copyable (axial_properties() keeps a copy).
     * check_law_contract() states this at compile time.
     *
     * A new law: its own header beside charmetant_law.h (and a source
     * file for what is not inline), its parameters in fe/parameters.h
     * and `FE/Constitutive law`, and one entry in
     * YARN_IMPACT_FE_FOR_EACH_LAW below.
     */

    /**
     * The laws, one entry X(law type, class, member of Parameters with
     * its parameters) each: with_law() selects from it, and the force loop
     * (cell_kernel.cc) and the model's members in fe_observables.cc are
     * instantiated from it.
     */
#define YARN_IMPACT_FE_FOR_EACH_LAW(X)     \
  X(charmetant, CharmetantLaw, charmetant) \
  X(linear_transversely_isotropic, LinearTransverselyIsotropicLaw, linear)

    /** Compile-time check that @p Law provides what the constitutive-law
     * contract asks for (see the page above). */
    template <class Law>
    constexpr bool
    check_law_contract()
    {
      const Law *law = nullptr;
      static_assert(std::is_same_v<decltype(law->stress(
                                     std::declval<const Mechanics::Matrix3 &>(),
                                     std::declval<Mechanics::Matrix3 &>(),
                                     std::declval<Mechanics::Invariants &>())),
                                   double>,
                    "a law needs double stress(F, P, inv) const");
      static_assert(
        std::is_convertible_v<decltype(law->axial_modulus()), double>,
        "a law needs double axial_modulus() const");
      static_assert(
        std::is_convertible_v<decltype(law->transverse_modulus(
                                std::declval<Mechanics::Invariants>())),
                              double>,
        "a law needs double transverse_modulus(inv) const");
      static_assert(
        std::is_convertible_v<decltype(law->uniaxial_nominal_stress(0.)),
                              double>,
        "a law needs double uniaxial_nominal_stress(strain) const");
      static_assert(std::is_convertible_v<decltype(law->density), double>,
                    "a law needs a density [kg/m^3]");
      static_assert(std::is_same_v<decltype(Law::vectorised), const bool>,
                    "a law says whether it has a Double4 stress_kernel");
      static_assert(
        std::is_same_v<decltype(Law::separable_fibre_term), const bool>,
        "a law says whether its fibre term 1/2 k_e I_e^2 is separable");
      static_assert(std::is_copy_constructible_v<Law>,
                    "a law must be copyable");
      return true;
    }

    /**
     * The stress of @p law with its fibres along the first axis of the
     * fibre frame @p R (Mechanics::fibre_frame()) at the deformation
     * gradient @p F (row-major): the law evaluated in its frame at F R,
     * turned back, P = P'(F R) R^T [Pa] (doc/theory.md section 1.8).
     * Returns W [J/m^3] and fills @p inv as the law's stress() does. The
     * scalar path for a fibre direction at any angle; the force loop
     * does the same with the shape gradients stored in the frames
     * (CellData::frames).
     */
    template <class Law>
    double
    oriented_stress(const Law &law,
                    const Mechanics::Matrix3 &F,
                    const Mechanics::FibreFrame &R,
                    Mechanics::Matrix3 &P,
                    Mechanics::Invariants &inv)
    {
      Mechanics::Matrix3 F_frame, P_frame;
      Mechanics::to_fibre_frame(F, R, F_frame);
      const double W = law.stress(F_frame, P_frame, inv);
      Mechanics::from_fibre_frame(P_frame, R, P);
      return W;
    }

    /**
     * The law chosen by `parameters.law`, built from its parameters and
     * @p density [kg/m^3] and handed to @p visitor; returns what the
     * visitor returns (the same type for every law).
     */
    template <class Visitor>
    auto
    with_law(const Parameters &parameters,
             const double density,
             Visitor &&visitor)
    {
      switch (parameters.law)
        {
#define YARN_IMPACT_FE_SELECT_LAW(type, Law, member) \
  case LawType::type:                                \
    static_assert(check_law_contract<Law>());        \
    return visitor(Law(parameters.member, density));
          YARN_IMPACT_FE_FOR_EACH_LAW(YARN_IMPACT_FE_SELECT_LAW)
#undef YARN_IMPACT_FE_SELECT_LAW
        }
      throw std::logic_error("FE: a constitutive law without a selector entry");
    }
  } // namespace FE
} // namespace YarnImpact

#endif
