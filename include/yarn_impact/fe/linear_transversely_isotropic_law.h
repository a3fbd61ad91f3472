#ifndef yarn_impact_fe_linear_transversely_isotropic_law_h
#define yarn_impact_fe_linear_transversely_isotropic_law_h

#include <yarn_impact/fe/parameters.h>
#include <yarn_impact/mechanics/kinematics.h>

namespace YarnImpact
{
  namespace FE
  {
    /**
     * The classical linear transversely isotropic yarn law, fibre direction
     * x, in St. Venant-Kirchhoff form: \f$S = \mathbb{C} : E\f$ with the
     * Green-Lagrange strain E. With the default null Poisson ratios the
     * section does not react to axial strain: the paper's point.
     */
    class LinearTransverselyIsotropicLaw
    {
    public:
      /** Scalar only: the force loop calls stress() one Gauss point at a
       * time (the constitutive-law contract, constitutive_law.h). */
      static constexpr bool vectorised = false;
      /** The fibre strain is coupled to the others through C : E (and
       * shear G_LT): no separable fibre term, so the progressive failure
       * law is refused with this law (FE::validate()). */
      static constexpr bool separable_fibre_term = false;

      /** @param parameters the moduli @param density [kg/m^3] */
      LinearTransverselyIsotropicLaw(const LinearParameters &parameters,
                                     const double density);

      /** First Piola-Kirchhoff stress and energy density, as
       * CharmetantLaw::stress(); the invariants are filled too. */
      double
      stress(const Mechanics::Matrix3 &F,
             Mechanics::Matrix3 &P,
             Mechanics::Invariants &inv) const;

      /** Axial P-wave modulus \f$\mathbb{C}_{1111}\f$ [Pa]. */
      double
      axial_modulus() const
      {
        return C11;
      }

      /** Transverse P-wave modulus \f$\mathbb{C}_{2222}\f$ [Pa]. */
      double
      transverse_modulus(const Mechanics::Invariants &) const
      {
        return C22;
      }

      /** Uniaxial nominal stress of the SVK bar under free lateral
       * contraction, \f$P = E_L (\varepsilon + \varepsilon^2/2)
       * (1+\varepsilon)\f$ [Pa] (exact for null Poisson ratios). */
      double
      uniaxial_nominal_stress(const double strain) const
      {
        return E_L * (strain + 0.5 * strain * strain) * (1. + strain);
      }

      /** Density [kg/m^3]. */
      double density;

    private:
      double E_L;
      /** Stiffness in Voigt form (x = 1, y = 2, z = 3). */
      double C11, C12, C22, C23, G12, G23;
    };
  } // namespace FE
} // namespace YarnImpact

#endif
