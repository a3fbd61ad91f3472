#ifndef yarn_impact_fe_failure_law_h
#define yarn_impact_fe_failure_law_h

#include <yarn_impact/core/parameters.h>

#include <algorithm>
#include <cmath>

namespace dealii
{
  class ParameterHandler;
}

namespace YarnImpact
{
  namespace FE
  {
    /**
     * How an FE cell fails: the FE's own failure parameters. Their entries
     * sit in subsection `Yarn`, beside `Failure` and `Failure strain`, which
     * both models share (core/parameters.h); the DEM's trusses always break
     * at once at the failure strain.
     */
    struct FailureParameters
    {
      /** The FE failure model (entry `Yarn/Failure model`). */
      enum class Model
      {
        /** The paper's criterion: a cell whose largest Gauss-point
         * ln(lambda_f) passes ln(1 + failure strain) drops all its stress
         * in one step. */
        sudden,
        /** Crack-band softening of the fibre term between the onset at
         * damage_onset_strain and a final strain set by fracture_energy and
         * the cell's length along the fibre (doc/theory.md section 5). */
        progressive
      };
      /** The FE failure model. */
      Model model = Model::progressive;
      /** Largest Gauss-point fibre strain of a cell at which its
       * progressive fibre damage starts [-] (the sudden model and the DEM
       * use the failure strain). */
      double damage_onset_strain = 0.0347;
      /** Progressive model: relative growth of the damage onset strain
       * across the thickness [-]: a cell's onset is damage_onset_strain
       * (1 + spread depth), depth 0 at the face the projectile strikes and
       * 1 at the opposite face (doc/theory.md section 5.4). 0: the same
       * onset in every cell. */
      double damage_onset_spread = 0.243;
      /** Energy dissipated per unit area of a crack across the yarn by the
       * progressive model, G_f [J/m^2]. */
      double fracture_energy = 5.41e4;
      /** Progressive model: the fibre stress at the kink of a bilinear
       * softening envelope, as a fraction of the onset stress [-]; 0: the
       * linear envelope (doc/theory.md section 5.5). */
      double softening_tail_stress = 0.;
      /** Progressive model: the part of fracture_energy that the tail of
       * the bilinear envelope dissipates [J/m^2]. */
      double softening_tail_energy = 0.;

      /** Declare the entries (subsection `Yarn`). */
      static void
      declare_parameters(dealii::ParameterHandler &prm);
      /** Parse and check them; throws InputError naming the entry. */
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };

    /**
     * The fibre-failure law of the force loop (doc/theory.md section 5).
     *
     * - sudden: the paper's criterion. A cell whose largest Gauss-point
     *   ln(lambda_f) passes onset_log_stretch breaks: it carries no
     *   force from then on and its strain energy is counted as dissipated.
     * - progressive: crack-band softening of the fibre term
     *   1/2 k_e I_e^2 of the energy. The history variable kappa is the
     *   largest ln(lambda_f) a cell's Gauss points have reached; above
     *   the onset I_0 the fibre Kirchhoff stress follows the linear
     *   envelope k_e I_0 (I_u - kappa)/(I_u - I_0) down to zero at
     *   I_u = 2 G_f / (h k_e I_0), h the cell's reference length along
     *   the fibre, so that a band one cell long dissipates G_f per unit
     *   area whatever h. With a tail (tail_stress_ratio beta > 0) the
     *   envelope is bilinear: from k_e I_0 down to beta k_e I_0 at the
     *   kink I_k, then down to zero at I_u, the tail dissipating G_t of
     *   G_f (doc/theory.md section 5.5). The damage d = 1 - envelope/(k_e
     * kappa) scales the fibre term only (the law's energy must separate it:
     *   Law::separable_fibre_term); the compaction and distortion terms
     *   stay, because the broken fibres still fill the section and are
     *   still pressed by the projectile (doc/fe-model.md section 4).
     *
     * Both erode cells crushed below J = 0.2, inverted or with a
     * non-finite energy (CellState::eroded); the progressive law also
     * erodes a fully damaged cell whose fibre stretch passes 2
     * (parted_log_stretch).
     */
    struct FailureLaw
    {
      /** Which law, none for a yarn that does not fail (nor erode);
       * erosion for a yarn whose fibres do not fail but whose crushed,
       * inverted or non-finite cells are eroded (the FE part of a hybrid
       * yarn: its fibres break in the coupled model, and its cells among
       * their broken ends are crushed as the FE yarn's are). */
      enum class Kind
      {
        none,
        erosion,
        sudden,
        progressive
      };
      Kind kind = Kind::none;
      /** ln 2 [-]: a fully damaged cell (progressive) whose largest
       * Gauss-point fibre stretch passes 2 is eroded: its broken fibres'
       * ends have parted by a whole cell and cannot fill the section
       * (doc/fe-model.md section 4). */
      static constexpr double parted_log_stretch = 0.69314718055994531;
      /** I_0 = ln(1 + failure strain) [-]; for the progressive law, the
       * onset of the cells at the face that the projectile strikes. */
      double onset_log_stretch = 0.;
      /** Progressive law: relative growth s [-] of the onset strain across
       * the thickness, from expm1(onset_log_stretch) at the struck face to
       * (1 + s) times it at the opposite face (onset_log_stretch_at()). */
      double onset_spread = 0.;
      /** G_f, energy per unit crack area [J/m^2] (progressive). */
      double fracture_energy = 0.;
      /** beta [-]: the fibre stress at the kink of a bilinear envelope, as
       * a fraction of the onset stress k_e I_0 (progressive). 0: the linear
       * envelope. */
      double tail_stress_ratio = 0.;
      /** G_t [J/m^2]: the part of G_f that the tail of the bilinear
       * envelope dissipates, from the kink to complete failure
       * (progressive, with tail_stress_ratio > 0). */
      double tail_energy = 0.;
      /** k_e of the separable fibre term 1/2 k_e I_e^2 [Pa] (progressive).
       */
      double fibre_modulus = 0.;

      /** The onset I_0 [-] of a cell whose shallowest point lies at the
       * normalised depth @p depth [-] below the struck face (CellData::depth, 0
       * at the face the projectile strikes, 1 at the opposite one): the onset
       * strain grows linearly with the depth, eps_0 (1 + s depth). The
       * fibres nearest the nose are the most stretched of a section and
       * break first, those at the back last (doc/theory.md section 5.4);
       * a cell averages them, and the spread gives each cell the onset of
       * the fibres it holds. */
      double
      onset_log_stretch_at(const double depth) const
      {
        if (onset_spread == 0.)
          return onset_log_stretch;
        return std::log1p(std::expm1(onset_log_stretch) *
                          (1. + onset_spread * depth));
      }

      /** The ln(lambda_f) [-] at which the fibre stress of a cell @p h [m]
       * long along the fibre with onset @p I_0 [-] is gone: I_u = 2 G_f /
       * (h k_e I_0) for the linear envelope, 2 G_t / (h k_e beta I_0) with
       * a tail (the tail's area beta k_e I_0 I_u / 2 per unit volume is
       * G_t / h). */
      double
      final_log_stretch(const double h, const double I_0) const
      {
        if (tail_stress_ratio == 0.)
          return 2. * fracture_energy / (h * fibre_modulus * I_0);
        return 2. * tail_energy / (h * fibre_modulus * tail_stress_ratio * I_0);
      }

      /** The kink I_k [-] of the bilinear envelope of a cell @p h [m] long
       * with onset @p I_0 [-], where the fibre stress has fallen to
       * beta k_e I_0: the first branch dissipates G_f - G_t per unit area,
       * 1/2 k_e I_0 (I_k - beta I_0) h. Equal to final_log_stretch() for the
       * linear envelope. */
      double
      kink_log_stretch(const double h, const double I_0) const
      {
        if (tail_stress_ratio == 0.)
          return final_log_stretch(h, I_0);
        return tail_stress_ratio * I_0 +
               2. * (fracture_energy - tail_energy) / (h * fibre_modulus * I_0);
      }

      /** The envelope of the fibre Kirchhoff stress over k_e [-] at the
       * history variable @p kappa [-], for a cell @p h [m] long with onset
       * @p I_0 [-]: kappa up to the onset, then linear down to beta I_0 at
       * the kink and to zero at the final stretch. */
      double
      envelope(const double kappa, const double h, const double I_0) const
      {
        if (kappa <= I_0)
          return kappa;
        const double I_u = final_log_stretch(h, I_0);
        if (kappa >= I_u)
          return 0.;
        if (tail_stress_ratio == 0.)
          return I_0 * (I_u - kappa) / (I_u - I_0);
        const double I_k    = kink_log_stretch(h, I_0);
        const double tail_0 = tail_stress_ratio * I_0;
        if (kappa <= I_k)
          return I_0 - (I_0 - tail_0) * (kappa - I_0) / (I_k - I_0);
        return tail_0 * (I_u - kappa) / (I_u - I_k);
      }

      /** The damage [0, 1] of a cell @p h [m] long with onset @p I_0 [-]
       * at the history variable @p kappa (largest ln(lambda_f) reached)
       * [-]: 1 - envelope / kappa. */
      double
      damage(const double kappa, const double h, const double I_0) const
      {
        if (kappa <= I_0)
          return 0.;
        if (tail_stress_ratio != 0.)
          return 1. - envelope(kappa, h, I_0) / kappa;
        // The linear curve written out, as before the tail (the same bits).
        const double I_u = final_log_stretch(h, I_0);
        if (kappa >= I_u)
          return 1.;
        return 1. - I_0 * (I_u - kappa) / (kappa * (I_u - I_0));
      }
    };

    /**
     * The energy [J] that the progressive law dissipates in a cell whose
     * history variable grows from @p kappa_old to @p kappa_new [-], with
     * the undamaged fibre energy @p fibre_energy [J] at kappa_new, the
     * cell length @p h [m] along the fibre and the cell's onset @p I_0 [-].
     * Along the envelope the dissipation per unit volume is 1/2 k_e kappa^2 dd
     * = 1/2 k_e I_0 I_u / (I_u - I_0) dkappa, a constant rate (doc/theory.md
     * section 5.3; with a tail, one constant rate per branch, section 5.5),
     * so the increment is that rate times the part of [kappa_old,
     * kappa_new] inside [I_0, I_u], times the volume of the band. The volume is
     * fibre_energy / (1/2 k_e kappa_new^2): the whole cell when its strain is
     * uniform (then the crack dissipates G_f per unit area exactly, whatever
     * the step), less when its Gauss points are stretched less than the
     * largest, whose fibre energy the damage then removes in proportion, so
     * that the energy balance closes.
     */
    inline double
    dissipation_increment(const FailureLaw &law,
                          const double kappa_old,
                          const double kappa_new,
                          const double fibre_energy,
                          const double h,
                          const double I_0)
    {
      const double I_u = law.final_log_stretch(h, I_0);
      // The linear curve keeps its own expression: the general one below
      // gives the same number with other roundings.
      if (law.tail_stress_ratio == 0.)
        {
          const double lo = std::max(kappa_old, I_0);
          const double hi = std::min(kappa_new, I_u);
          if (hi <= lo)
            return 0.;
          return fibre_energy * I_0 * I_u * (hi - lo) /
                 ((I_u - I_0) * kappa_new * kappa_new);
        }
      // On a linear piece g = a + b kappa of the envelope the rate
      // 1/2 k_e (g - kappa g') = 1/2 k_e a is its intercept a: beta I_0
      // I_u / (I_u - I_k) on the tail, I_0 (I_k - beta I_0) / (I_k - I_0)
      // on the first branch.
      const double I_k    = law.kink_log_stretch(h, I_0);
      const double tail_0 = law.tail_stress_ratio * I_0;
      auto overlap        = [&](const double a, const double b) {
        return std::max(0., std::min(kappa_new, b) - std::max(kappa_old, a));
      };
      const double sum =
        I_0 * (I_k - tail_0) / (I_k - I_0) * overlap(I_0, I_k) +
        tail_0 * I_u / (I_u - I_k) * overlap(I_k, I_u);
      return fibre_energy * sum / (kappa_new * kappa_new);
    }

    /**
     * The failure law of a yarn @p yarn (`Failure`, `Failure strain`) with
     * the FE failure parameters @p failure, whose separable fibre term has
     * the modulus @p fibre_modulus [Pa] (the law's axial_modulus()): the one
     * place where a FailureLaw is built, for the force loop and for the
     * set-up checks alike.
     */
    FailureLaw
    make_failure_law(const YarnImpact::Parameters::Yarn &yarn,
                     const FailureParameters &failure,
                     const double fibre_modulus);
  } // namespace FE
} // namespace YarnImpact

#endif
