#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/fe/parameters.h>

#include <deal.II/base/parameter_handler.h>

namespace YarnImpact
{
  namespace FE
  {
    using namespace dealii;
    using YarnImpact::Parameters::get_positive_double;
    using YarnImpact::Parameters::require;

    void
    Parameters::declare_parameters(ParameterHandler &prm)
    {
      FailureParameters::declare_parameters(prm);
      prm.enter_subsection("FE");
      prm.declare_entry(
        "Constitutive law",
        "Charmetant",
        Patterns::Selection("Charmetant|Linear transversely isotropic"),
        "Charmetant: the paper's hyperelastic transversely isotropic law in "
        "three invariants (elongation, compaction, distortion); Linear "
        "transversely isotropic: the classical yarn law (St. Venant-Kirchhoff "
        "form) that the paper argues against.");
      prm.declare_entry("Density",
                        "1267",
                        Patterns::Double(),
                        "Density of the continuum yarn: fibre density times "
                        "the volume fraction [kg/m^3].");
      prm.declare_entry(
        "Density from fibres",
        "false",
        Patterns::Bool(),
        "When true, the density is Yarn/Fibre density x fibre area / section "
        "area, so that the FE yarn has the DEM yarn's mass per length "
        "(Density is then ignored).");
      prm.declare_entry(
        "Axial modulus from fibres",
        "false",
        Patterns::Bool(),
        "When true, the law's axial modulus (Charmetant/k_e, Linear "
        "transversely isotropic/E_L) is Yarn/Fibre Young modulus x fibre "
        "area / section area, so that the FE yarn has the DEM yarn's axial "
        "stiffness EA (the law's own entry is then ignored). With Density "
        "from fibres, both models carry the same yarn (doc/hybrid.md "
        "section 3).");
      prm.declare_entry("Cells along the axis",
                        "100",
                        Patterns::Integer(),
                        "Number of cells along the whole yarn length; half "
                        "and quarter models keep the half of them on x >= 0 "
                        "(the number must then be even) [-].");
      prm.declare_entry("Section refinements",
                        "0",
                        Patterns::Integer(0, 6),
                        "Number of refinements of the 12-cell elliptical "
                        "section (each multiplies its cells by 4) [-].");
      prm.declare_entry(
        "Preserve section area",
        "true",
        Patterns::Bool(),
        "When true, the polygonal section mesh (its boundary vertices on "
        "the ellipse) is scaled about its centre so that its area equals "
        "the ellipse's: the 12-cell section would otherwise have 10 % less "
        "area, mass per length and axial stiffness than the ellipse. The "
        "projectile always starts touching the top of the meshed yarn.");
      prm.declare_entry("Global refinements",
                        "0",
                        Patterns::Integer(0, 4),
                        "Number of refinements of the 3D mesh in all "
                        "directions (each multiplies the cells by 8) [-].");

      prm.enter_subsection("Charmetant");
      prm.declare_entry("k_e",
                        "80077.19e6",
                        Patterns::Double(),
                        "Elongation modulus k_e of f(I_e) = k_e I_e^2 / 2 "
                        "[Pa].");
      prm.declare_entry("k_tc",
                        "1055.82e6",
                        Patterns::Double(),
                        "Compaction modulus k_tc of g(I_tc) = k_tc |I_tc|^p "
                        "[Pa].");
      prm.declare_entry("p",
                        "2.205",
                        Patterns::Double(),
                        "Compaction exponent p, larger than 1 [-].");
      prm.declare_entry("k_td",
                        "649.75e6",
                        Patterns::Double(),
                        "Distortion modulus k_td of h(I_td) = k_td I_td^2 / "
                        "2 [Pa].");
      prm.leave_subsection();

      prm.enter_subsection("Linear transversely isotropic");
      prm.declare_entry("E_L",
                        "80077.19e6",
                        Patterns::Double(),
                        "Longitudinal Young modulus [Pa].");
      prm.declare_entry("E_T",
                        "650e6",
                        Patterns::Double(),
                        "Transverse Young modulus [Pa].");
      prm.declare_entry("G_LT",
                        "650e6",
                        Patterns::Double(),
                        "Longitudinal (axial) shear modulus [Pa].");
      prm.declare_entry("nu_LT",
                        "0",
                        Patterns::Double(),
                        "Major Poisson ratio (null in the classical yarn "
                        "model) [-].");
      prm.declare_entry("nu_TT",
                        "0",
                        Patterns::Double(),
                        "Transverse Poisson ratio (null in the classical "
                        "yarn model) [-].");
      prm.leave_subsection();

      prm.enter_subsection("Contact");
      prm.declare_entry("Law",
                        "Penalty-Coulomb",
                        Patterns::Selection(Contact::law_selection()),
                        "Contact law of a surface node "
                        "(doc/architecture.md section 3): Penalty-Coulomb "
                        "(damping that never pulls, explicit Coulomb "
                        "friction on the slip velocity) or Cundall-Strack "
                        "(spring-dashpot, tangential spring with Coulomb's "
                        "limit; the DEM's law).");
      prm.declare_entry("Penalty",
                        "5e13",
                        Patterns::Double(),
                        "Contact pressure per unit penetration of the yarn "
                        "surface into the projectile [Pa/m]; the force on a "
                        "node is Penalty x nodal surface area x penetration, "
                        "so the contact does not depend on the mesh.");
      prm.declare_entry("Friction coefficient",
                        "0.2",
                        Patterns::Double(),
                        "Coulomb friction coefficient between the projectile "
                        "and the yarn [-]; the default is the DEM's (DEM/"
                        "Projectile friction coefficient), so that both "
                        "models of Model = both see the same contact.");
      prm.declare_entry("Damping ratio",
                        "0",
                        Patterns::Double(),
                        "Viscous damping of the contact as a fraction of the "
                        "critical damping of a surface node on its penalty "
                        "spring [-].");
      prm.declare_entry("Tangential stiffness ratio",
                        "0.2857142857142857",
                        Patterns::Double(),
                        "Tangential stiffness of a surface node's contact "
                        "divided by its normal (penalty) stiffness, for the "
                        "Cundall-Strack law, in [0, 1] [-].");
      prm.leave_subsection();

      prm.enter_subsection("Crimp");
      prm.declare_entry(
        "Amplitude",
        "0",
        Patterns::Double(),
        "Crimp amplitude A: the yarn's centreline is (x, A cos(2 pi x / "
        "Wavelength), 0) over the span x in [-L/2, L/2], a crest under the "
        "projectile at x = 0, with the section normal to the centreline and "
        "the fibres along its tangent; 0: the straight yarn. The "
        "centreline's smallest radius of curvature, Wavelength^2 / (4 pi^2 "
        "Amplitude), must exceed Yarn/Thickness semi-axis [m].");
      prm.declare_entry("Wavelength",
                        "2e-3",
                        Patterns::Double(),
                        "Crimp wavelength lambda along x: twice the spacing "
                        "of the crossing yarns (used only with a positive "
                        "Amplitude; at least 8 cells of Cells along the "
                        "axis per wavelength) [m].");
      prm.leave_subsection();
      prm.leave_subsection();
    }

    void
    Parameters::parse_parameters(ParameterHandler &prm)
    {
      failure.parse_parameters(prm);
      prm.enter_subsection("FE");
      law                       = (prm.get("Constitutive law") == "Charmetant"
                                     ? LawType::charmetant
                                     : LawType::linear_transversely_isotropic);
      density                   = get_positive_double(prm, "FE", "Density");
      density_from_fibres       = prm.get_bool("Density from fibres");
      axial_modulus_from_fibres = prm.get_bool("Axial modulus from fibres");
      n_axial_cells =
        YarnImpact::Parameters::get_positive_integer(prm,
                                                     "FE",
                                                     "Cells along the axis");
      section_refinements   = prm.get_integer("Section refinements");
      global_refinements    = prm.get_integer("Global refinements");
      preserve_section_area = prm.get_bool("Preserve section area");

      prm.enter_subsection("Charmetant");
      charmetant.k_e  = get_positive_double(prm, "FE/Charmetant", "k_e");
      charmetant.k_tc = get_positive_double(prm, "FE/Charmetant", "k_tc");
      charmetant.p    = get_positive_double(prm, "FE/Charmetant", "p");
      require(charmetant.p > 1.,
              "FE/Charmetant/p",
              "must be larger than 1 (the compaction stress must vanish "
              "continuously at the reference state)");
      charmetant.k_td = get_positive_double(prm, "FE/Charmetant", "k_td");
      prm.leave_subsection();

      prm.enter_subsection("Linear transversely isotropic");
      const std::string lin = "FE/Linear transversely isotropic";
      linear.E_L            = get_positive_double(prm, lin, "E_L");
      linear.E_T            = get_positive_double(prm, lin, "E_T");
      linear.G_LT           = get_positive_double(prm, lin, "G_LT");
      linear.nu_LT          = prm.get_double("nu_LT");
      linear.nu_TT          = prm.get_double("nu_TT");
      require(linear.nu_TT > -1. && linear.nu_TT < 1.,
              lin + "/nu_TT",
              "must lie in (-1, 1)");
      // Positive definiteness of the compliance of a transversely
      // isotropic solid.
      const double nu_TL = linear.nu_LT * linear.E_T / linear.E_L;
      require(1. - linear.nu_TT - 2. * linear.nu_LT * nu_TL > 0.,
              lin + "/nu_LT",
              "gives a stiffness that is not positive definite");
      prm.leave_subsection();

      prm.enter_subsection("Contact");
      contact.law      = Contact::law_type(prm.get("Law"));
      contact.penalty  = get_positive_double(prm, "FE/Contact", "Penalty");
      contact.friction = prm.get_double("Friction coefficient");
      require(contact.friction >= 0.,
              "FE/Contact/Friction coefficient",
              "must not be negative");
      contact.damping_ratio = prm.get_double("Damping ratio");
      require(contact.damping_ratio >= 0. && contact.damping_ratio < 1.,
              "FE/Contact/Damping ratio",
              "must lie in [0, 1)");
      contact.tangential_stiffness_ratio =
        prm.get_double("Tangential stiffness ratio");
      // The contact's stable step is that of the normal spring.
      require(contact.tangential_stiffness_ratio >= 0. &&
                contact.tangential_stiffness_ratio <= 1.,
              "FE/Contact/Tangential stiffness ratio",
              "must lie in [0, 1]");
      prm.leave_subsection();

      prm.enter_subsection("Crimp");
      crimp.amplitude = prm.get_double("Amplitude");
      require(crimp.amplitude >= 0.,
              "FE/Crimp/Amplitude",
              "must not be negative (0: the straight yarn)");
      crimp.wavelength = get_positive_double(prm, "FE/Crimp", "Wavelength");
      prm.leave_subsection();
      prm.leave_subsection();
    }
  } // namespace FE
} // namespace YarnImpact
