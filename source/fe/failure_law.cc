#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/fe/failure_law.h>

#include <deal.II/base/parameter_handler.h>

#include <cmath>

namespace YarnImpact
{
  namespace FE
  {
    using namespace dealii;
    using YarnImpact::Parameters::get_positive_double;
    using YarnImpact::Parameters::require;

    void
    FailureParameters::declare_parameters(ParameterHandler &prm)
    {
      // In subsection Yarn, where the failure strain is: the entries' paths
      // are those of every parameter file.
      prm.enter_subsection("Yarn");
      prm.declare_entry(
        "Failure model",
        "progressive",
        Patterns::Selection("sudden|progressive"),
        "How an FE cell fails (the DEM's trusses always break at once at "
        "the failure strain). progressive, the default, with its onset, "
        "spread and fracture energy identified from the DEM, follows the "
        "DEM's projectile best after the first breaks (doc/validation.md "
        "section 6); sudden is the paper's criterion "
        "(prm/km2_120ms_compare.prm, prm/km2_120ms_fe.prm). sudden: a cell "
        "whose "
        "largest Gauss-point fibre strain passes the failure strain loses "
        "all its stress in one step. progressive: from Damage onset strain "
        "on (grown across the thickness by Damage onset spread), the fibre "
        "stress of the cell softens with its fibre strain down to zero, "
        "linearly or with the tail of Softening tail stress, the slope set "
        "by Fracture energy and the cell's length along the fibre (crack "
        "band), and the released energy is counted as dissipated.");
      prm.declare_entry(
        "Damage onset strain",
        "0.0347",
        Patterns::Double(),
        "Progressive failure model: the largest Gauss-point fibre strain of "
        "an FE cell at which its fibre damage starts [-]. A cell averages "
        "some 30 fibres over 0.254 mm and does not resolve the strain peak "
        "of the fibres on the nose, so its fibres start breaking below the "
        "fibre failure strain; calibrated at 120 m/s against the DEM's "
        "first break by scripts/identify_fibre_failure.py "
        "(doc/identification.md section 8).");
      prm.declare_entry(
        "Damage onset spread",
        "0.243",
        Patterns::Double(),
        "Progressive failure model: relative growth s of the damage onset "
        "strain across the yarn's thickness [-]. A cell whose shallowest "
        "reference point lies at the depth z below the face the projectile "
        "strikes (z = 0 there, 1 at the opposite face) starts its damage at "
        "Damage onset strain x (1 + s z): the fibres against the nose are "
        "taken to be the most stretched of the section, breaking first, and "
        "those at the back last (doc/theory.md section 5.4). 0: one onset "
        "for every cell. "
        "Identified from the DEM impact by scripts/identify_fibre_failure.py "
        "(doc/identification.md section 8).");
      prm.declare_entry(
        "Fracture energy",
        "5.41e4",
        Patterns::Double(),
        "Energy dissipated per unit area of a crack across the yarn by the "
        "progressive failure model, G_f [J/m^2]; identified from the DEM "
        "by scripts/identify_fibre_failure.py (doc/identification.md "
        "section 8). Must exceed the elastic energy per unit area of the "
        "longest cell at the largest damage onset strain.");
      prm.declare_entry(
        "Softening tail stress",
        "0",
        Patterns::Double(),
        "Progressive failure model: the fibre stress at the kink of a "
        "bilinear softening curve, as a fraction beta of the stress at the "
        "damage onset [-]. From the onset the fibre stress falls linearly "
        "to beta times the onset stress, then along a tail down to zero. "
        "The DEM's yarn, once most fibres are broken, holds a small load "
        "over a long opening while the last fibres go (doc/theory.md "
        "section 5.5). 0: the linear softening curve. Identified from the "
        "DEM impact by scripts/identify_fibre_failure.py "
        "(doc/identification.md section 8).");
      prm.declare_entry(
        "Softening tail energy",
        "0",
        Patterns::Double(),
        "Progressive failure model with Softening tail stress > 0: the part "
        "of Fracture energy that the tail dissipates, G_t [J/m^2]; the "
        "first branch dissipates the rest. Identified from the DEM impact "
        "by scripts/identify_fibre_failure.py (doc/identification.md "
        "section 8).");
      prm.leave_subsection();
    }


    void
    FailureParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Yarn");
      model = prm.get("Failure model") == "progressive" ? Model::progressive
                                                        : Model::sudden;
      fracture_energy = get_positive_double(prm, "Yarn", "Fracture energy");
      damage_onset_strain =
        get_positive_double(prm, "Yarn", "Damage onset strain");
      damage_onset_spread = prm.get_double("Damage onset spread");
      require(damage_onset_spread >= 0. && std::isfinite(damage_onset_spread),
              "Yarn/Damage onset spread",
              "must be zero or positive: the fibres against the nose break "
              "first");
      softening_tail_stress = prm.get_double("Softening tail stress");
      require(softening_tail_stress >= 0. && softening_tail_stress < 1.,
              "Yarn/Softening tail stress",
              "must lie in [0, 1): a fraction of the fibre stress at the "
              "damage onset (0: linear softening)");
      softening_tail_energy = prm.get_double("Softening tail energy");
      require(std::isfinite(softening_tail_energy) &&
                (softening_tail_stress == 0.
                   ? softening_tail_energy == 0.
                   : softening_tail_energy > 0. &&
                       softening_tail_energy < fracture_energy),
              "Yarn/Softening tail energy",
              softening_tail_stress == 0.
                ? "must be 0 when Softening tail stress is 0 (the linear "
                  "softening curve has no tail)"
                : "must lie between 0 and Fracture energy (exclusive): the "
                  "part of it that the tail dissipates [J/m^2]");
      prm.leave_subsection();
    }


    FailureLaw
    make_failure_law(const YarnImpact::Parameters::Yarn &yarn,
                     const FailureParameters &failure,
                     const double fibre_modulus)
    {
      const bool progressive =
        failure.model == FailureParameters::Model::progressive;
      FailureLaw law;
      law.onset_log_stretch = std::log1p(
        progressive ? failure.damage_onset_strain : yarn.failure_strain);
      law.onset_spread      = progressive ? failure.damage_onset_spread : 0.;
      law.fracture_energy   = failure.fracture_energy;
      law.tail_stress_ratio = progressive ? failure.softening_tail_stress : 0.;
      law.tail_energy       = progressive ? failure.softening_tail_energy : 0.;
      law.fibre_modulus     = fibre_modulus;
      law.kind              = !yarn.failure ? FailureLaw::Kind::none
                              : progressive ? FailureLaw::Kind::progressive
                                            : FailureLaw::Kind::sudden;
      return law;
    }
  } // namespace FE
} // namespace YarnImpact
