#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/dem/parameters.h>

#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cmath>

namespace YarnImpact
{
  namespace DEM
  {
    using namespace dealii;

    void
    Parameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("DEM");
      prm.declare_entry(
        "Fibre layout",
        "hexagonal",
        Patterns::Selection("hexagonal|file"),
        "hexagonal: Yarn/Number of fibres centres of a hexagonal lattice of "
        "spacing Yarn/Fibre diameter inside the yarn's ellipse, enlarged "
        "just enough to hold them; file: the centres are read from DEM/Fibre "
        "file.");
      prm.declare_entry("Fibre file",
                        "",
                        Patterns::Anything(),
                        "File with one fibre centre 'y z' per line, in "
                        "metres (y: thickness, z: width); '#' starts a "
                        "comment. Used when Fibre layout = file.");
      prm.declare_entry(
        "Maximum packing scale",
        "1.1",
        Patterns::Double(),
        "Largest factor by which the yarn's ellipse may be enlarged so that "
        "the hexagonal packing holds exactly Yarn/Number of fibres fibres "
        "without overlap; beyond it the input is rejected [-].");
      prm.declare_entry("Sphere spacing",
                        "12e-6",
                        Patterns::Double(),
                        "Largest distance between two consecutive spheres "
                        "of a fibre; the yarn length is divided into an even "
                        "number of equal trusses no longer than this. It "
                        "must not exceed Yarn/Fibre diameter [m].");
      prm.declare_entry("Normal stiffness ratio",
                        "0.5",
                        Patterns::Double(),
                        "Fibre-fibre normal penalty stiffness divided by the "
                        "truss stiffness E A / L0 [-].");
      prm.declare_entry("Tangential stiffness ratio",
                        "0.2857142857142857",
                        Patterns::Double(),
                        "Tangential contact stiffness divided by the normal "
                        "one (both contact kinds) [-].");
      prm.declare_entry("Damping ratio",
                        "0.1",
                        Patterns::Double(),
                        "Viscous damping of fibre-fibre contacts as a "
                        "fraction of critical damping, in [0, 1) [-].");
      prm.declare_entry("Friction coefficient",
                        "0.2",
                        Patterns::Double(),
                        "Coulomb friction coefficient between fibres [-].");
      prm.declare_entry("Projectile stiffness ratio",
                        "0.5",
                        Patterns::Double(),
                        "Projectile-fibre normal penalty stiffness divided "
                        "by the truss stiffness E A / L0 [-].");
      prm.declare_entry("Projectile damping ratio",
                        "0.1",
                        Patterns::Double(),
                        "Viscous damping of projectile-fibre contacts as a "
                        "fraction of critical damping, in [0, 1) [-].");
      prm.declare_entry("Projectile friction coefficient",
                        "0.2",
                        Patterns::Double(),
                        "Coulomb friction coefficient between the projectile "
                        "and the fibres [-].");
      prm.declare_entry("Projectile contact law",
                        "Cundall-Strack",
                        Patterns::Selection(Contact::law_selection()),
                        "Law of the projectile-fibre contacts "
                        "(doc/architecture.md section 3): Cundall-Strack "
                        "(spring-dashpot, tangential spring, Coulomb's "
                        "limit; the fibre-fibre law) or Penalty-Coulomb "
                        "(damping that never pulls, explicit Coulomb "
                        "friction on the slip velocity; the FE's law).");
      prm.declare_entry("Skin",
                        "4e-6",
                        Patterns::Double(),
                        "Verlet skin: pairs closer than the fibre diameter "
                        "plus this distance are listed; the lists are rebuilt "
                        "only when the proven bound on relative motion "
                        "reaches it. Up to about 0.4 diameters it lists "
                        "hardly more pairs (the next neighbours in a packing, "
                        "one sphere along on the next fibre, are sqrt(2) "
                        "diameters away) [m].");
      prm.declare_entry(
        "Stable time step",
        "contacts",
        Patterns::Selection("contacts|coordination"),
        "How the impact model bounds its stable time step (doc/theory.md "
        "section 3.2). contacts: from the springs it has now (trusses, the "
        "fibre pairs in contact, the projectile near the spheres): twice the "
        "largest eigenvalue of each sphere's own stiffness over its mass, "
        "recomputed every Time/Time step update interval steps. "
        "coordination: one bound for the whole run, with Coordination "
        "number contacts per sphere all added up (the step of versions "
        "before the contacts bound).");
      prm.declare_entry("Coordination number",
                        "6",
                        Patterns::Integer(),
                        "Number of fibre-fibre contacts per sphere assumed by "
                        "the scalar stable time step estimate (the "
                        "elementary tests, and Stable time step = "
                        "coordination) [-].");
      prm.declare_entry("Ghost stations",
                        "4",
                        Patterns::Integer(),
                        "Cross-sections copied from each neighbouring MPI "
                        "rank every step at the start. The layer grows by "
                        "itself (up to the neighbour's whole slab) when "
                        "fibres slide along each other across a rank "
                        "boundary, e.g. when cut fibres recoil; this value "
                        "only sets where it starts [-].");
      prm.declare_entry("List block",
                        "32",
                        Patterns::Integer(),
                        "Cross-sections per neighbour-list block. Each block "
                        "of a rank's cross-sections keeps its own neighbour "
                        "list and rebuild criterion and is rebuilt on its "
                        "own, so that the fast spheres under the projectile "
                        "rebuild only the lists near the impact. The results "
                        "do not depend on it, only the speed [-].");
      prm.declare_entry("Impact slab share",
                        "0.92",
                        Patterns::Double(),
                        "With half or quarter symmetry on several MPI ranks: "
                        "the slab of the first rank, which holds the impact "
                        "point (the densest contacts and the most frequent "
                        "list rebuilds), as a fraction of an even share of "
                        "the cross-sections; the other ranks share the rest "
                        "evenly. 1 gives even slabs. Ignored with Symmetry = "
                        "none (the impact point is then in the middle of the "
                        "yarn) and on one rank. The motion does not depend "
                        "on it, only the speed (and the last digits of the "
                        "energy sums, which are added per rank) [-].");
      prm.declare_entry("Joint rebuild fraction",
                        "0.6",
                        Patterns::Double(),
                        "On several MPI ranks: when some rank must rebuild a "
                        "neighbour-list block, every rank also rebuilds, in "
                        "the same step, its blocks whose rebuild criterion "
                        "has used up this fraction of the skin. Such a block "
                        "would fail within a few steps anyway, and each "
                        "rank's rebuild would otherwise stall the others "
                        "(after fibres break, blocks fail every few steps). "
                        "1 rebuilds only the failing blocks. The results do "
                        "not depend on it, only the speed [-].");
      prm.declare_entry("Partial search fraction",
                        "0",
                        Patterns::Double(),
                        "When the rebuild criterion of a neighbour-list "
                        "block fails or its halo grows: if at most this "
                        "fraction of the block's spheres moved farther than "
                        "the partial search threshold since the block was "
                        "built, or joined its halo, only those spheres are "
                        "searched again for partners and the other pairs "
                        "are kept; otherwise the block is rebuilt whole. 0 "
                        "always rebuilds whole blocks. The results do not "
                        "depend on it, only the speed [-].");
      prm.declare_entry("Check lists",
                        "false",
                        Patterns::Bool(),
                        "Verify at every force evaluation, by a sweep over "
                        "the spheres sorted along the yarn that does not use "
                        "the neighbour lists, that every pair of spheres "
                        "closer than the fibre diameter, and every such "
                        "pair with a mirror image, is listed; a missing pair "
                        "stops the run with an error. For tests: the sweep "
                        "compares each sphere with every sphere less than a "
                        "diameter away along the yarn, so a run takes 3 "
                        "times as long with 40 fibres and 25 times with 400.");
      prm.declare_entry("Phase timing",
                        "false",
                        Patterns::Bool(),
                        "Time the parts of the DEM step (trusses, pair "
                        "contacts, projectile, list checks and rebuilds, "
                        "communication, integration, stable step) in the "
                        "four phases of an impact (before contact, to the "
                        "first broken truss, to the cut, after it) and "
                        "print them, with the rebuild counts, in the run "
                        "summary. The phases change at history rows. Only "
                        "the summary depends on it.");
      prm.declare_entry("List rebuilds",
                        "criterion",
                        Patterns::Selection("criterion|missed contact"),
                        "When a neighbour-list block is rebuilt. criterion: "
                        "when the bound on the relative displacements of its "
                        "spheres since the last build reaches the skin (doc/"
                        "dem.md section 4). missed contact: only when the "
                        "sweep of Check lists, run before every force "
                        "evaluation, finds a pair in contact that the block "
                        "does not list; the motion is the same, and the "
                        "number of rebuilds shows how many the contacts "
                        "really need. A diagnostic, as slow as Check "
                        "lists.");
      prm.leave_subsection();
    }

    void
    Parameters::parse_parameters(ParameterHandler &prm)
    {
      using YarnImpact::Parameters::get_positive_double;
      using YarnImpact::Parameters::get_positive_integer;
      using YarnImpact::Parameters::require;
      prm.enter_subsection("DEM");
      layout     = (prm.get("Fibre layout") == "file" ? FibreLayout::file
                                                      : FibreLayout::hexagonal);
      fibre_file = prm.get("Fibre file");
      require(layout != FibreLayout::file || !fibre_file.empty(),
              "DEM/Fibre file",
              "must name a file when DEM/Fibre layout = file");
      max_packing_scale =
        get_positive_double(prm, "DEM", "Maximum packing scale");
      require(max_packing_scale >= 1.,
              "DEM/Maximum packing scale",
              "must be at least 1");
      sphere_spacing = get_positive_double(prm, "DEM", "Sphere spacing");
      normal_stiffness_ratio =
        get_positive_double(prm, "DEM", "Normal stiffness ratio");
      tangential_stiffness_ratio = prm.get_double("Tangential stiffness ratio");
      require(tangential_stiffness_ratio >= 0.,
              "DEM/Tangential stiffness ratio",
              "must not be negative");
      damping_ratio = prm.get_double("Damping ratio");
      require(damping_ratio >= 0. && damping_ratio < 1.,
              "DEM/Damping ratio",
              "must be in [0, 1)");
      friction = prm.get_double("Friction coefficient");
      require(friction >= 0.,
              "DEM/Friction coefficient",
              "must not be negative");
      projectile_stiffness_ratio =
        get_positive_double(prm, "DEM", "Projectile stiffness ratio");
      projectile_damping_ratio = prm.get_double("Projectile damping ratio");
      require(projectile_damping_ratio >= 0. && projectile_damping_ratio < 1.,
              "DEM/Projectile damping ratio",
              "must be in [0, 1)");
      projectile_friction = prm.get_double("Projectile friction coefficient");
      require(projectile_friction >= 0.,
              "DEM/Projectile friction coefficient",
              "must not be negative");
      projectile_contact_law =
        Contact::law_type(prm.get("Projectile contact law"));
      skin         = get_positive_double(prm, "DEM", "Skin");
      stable_step  = prm.get("Stable time step") == "contacts"
                       ? StableStep::contacts
                       : StableStep::coordination;
      const long c = prm.get_integer("Coordination number");
      require(c >= 0, "DEM/Coordination number", "must not be negative");
      coordination      = static_cast<unsigned int>(c);
      ghost_stations    = get_positive_integer(prm, "DEM", "Ghost stations");
      list_block        = get_positive_integer(prm, "DEM", "List block");
      impact_slab_share = prm.get_double("Impact slab share");
      require(impact_slab_share >= 0.25 && impact_slab_share <= 2.,
              "DEM/Impact slab share",
              "must be in [0.25, 2]");
      joint_rebuild_fraction = prm.get_double("Joint rebuild fraction");
      require(joint_rebuild_fraction > 0. && joint_rebuild_fraction <= 1.,
              "DEM/Joint rebuild fraction",
              "must be in (0, 1]");
      partial_search_fraction = prm.get_double("Partial search fraction");
      require(partial_search_fraction >= 0. && partial_search_fraction <= 1.,
              "DEM/Partial search fraction",
              "must be in [0, 1]");
      check_lists   = prm.get_bool("Check lists");
      phase_timing  = prm.get_bool("Phase timing");
      list_rebuilds = (prm.get("List rebuilds") == "missed contact"
                         ? ListRebuilds::missed_contact
                         : ListRebuilds::criterion);
      prm.leave_subsection();
    }
    FibreCentres
    fibre_centres(const YarnImpact::Parameters::Shared &shared,
                  const Parameters &parameters,
                  const bool symmetric_z)
    {
      using YarnImpact::Parameters::require;
      const auto &y  = shared.yarn;
      const double d = y.fibre_diameter;
      require(parameters.sphere_spacing <= d * (1. + 1e-12),
              "DEM/Sphere spacing",
              "must not exceed Yarn/Fibre diameter: larger gaps would let "
              "fibres pass between the spheres of another fibre");
      FibreCentres centres =
        (parameters.layout == FibreLayout::file
           ? read_fibre_file(parameters.fibre_file,
                             y.n_fibres,
                             d,
                             y.thickness_semi_axis,
                             y.width_semi_axis,
                             parameters.max_packing_scale)
           : hexagonal_packing(y.n_fibres,
                               d,
                               y.thickness_semi_axis,
                               y.width_semi_axis,
                               parameters.max_packing_scale,
                               symmetric_z));
      if (symmetric_z)
        {
          // The layout must be its own mirror image in z = 0.
          const unsigned int n = centres.size();
          for (unsigned int a = 0; a < n; ++a)
            {
              bool mirrored = (centres.z[a] == 0.);
              for (unsigned int b = 0; b < n && !mirrored; ++b)
                mirrored = std::abs(centres.y[b] - centres.y[a]) < 1e-9 * d &&
                           std::abs(centres.z[b] + centres.z[a]) < 1e-9 * d;
              require(mirrored,
                      "Symmetry",
                      "= quarter needs fibre centres symmetric about z = 0, "
                      "but the layout is not (use Symmetry = half)");
            }
        }
      return centres;
    }


    void
    validate(const YarnImpact::Parameters::Shared &shared,
             const Parameters &parameters,
             const bool elementary_test)
    {
      fibre_centres(shared,
                    parameters,
                    !elementary_test &&
                      shared.general.symmetry ==
                        YarnImpact::Parameters::Symmetry::quarter);
    }


    MemoryEstimate
    memory_estimate(const YarnImpact::Parameters::Shared &shared,
                    const Parameters &parameters)
    {
      using YarnImpact::Parameters::Symmetry;
      const auto symmetry = shared.general.symmetry;
      const double modelled =
        parameters.clamp_part_begin >= 0.
          ? 0.5 * shared.yarn.length - parameters.clamp_part_begin
          : (symmetry == Symmetry::none ? 1. : 0.5) * shared.yarn.length;
      const double fibres =
        (symmetry == Symmetry::quarter ? 0.5 : 1.) * shared.yarn.n_fibres;
      MemoryEstimate e;
      e.n_elements   = fibres * (modelled / parameters.sphere_spacing + 1.);
      e.bytes        = 600. * e.n_elements;
      e.element_name = "spheres";
      const double f_fibres  = shared.yarn.n_fibres / 400.;
      const double f_length  = shared.yarn.length / 0.0254;
      const double f_spacing = 12e-6 / parameters.sphere_spacing;
      e.parameter =
        (f_fibres >= f_length && f_fibres >= f_spacing ? "Yarn/Number of fibres"
         : f_length >= f_spacing                       ? "Yarn/Length"
                                                       : "DEM/Sphere spacing");
      return e;
    }


    namespace
    {
      /** The constants of a contact of a sphere of (reduced) mass @p mass
       * [kg] with the ratios and friction of one contact kind: stiffness
       * @p stiffness_ratio times the truss stiffness @p truss_k [N/m],
       * damping @p damping_ratio of critical, friction @p friction. */
      Contact::ContactConstants
      contact_constants(const Parameters &prm,
                        const double stiffness_ratio,
                        const double damping_ratio,
                        const double friction,
                        const double truss_k,
                        const double mass)
      {
        Contact::ContactConstants c;
        c.stiffness = stiffness_ratio * truss_k;
        c.damping = Contact::critical_damping(damping_ratio, mass, c.stiffness);
        c.tangential_stiffness = prm.tangential_stiffness_ratio * c.stiffness;
        c.friction             = friction;
        c.mass                 = mass;
        return c;
      }
    } // namespace


    FibreContactLaw
    fibre_contact_law(const Parameters &prm,
                      const double truss_k,
                      const double sphere_mass)
    {
      // Two free spheres: the reduced mass m/2.
      return FibreContactLaw(contact_constants(prm,
                                               prm.normal_stiffness_ratio,
                                               prm.damping_ratio,
                                               prm.friction,
                                               truss_k,
                                               0.5 * sphere_mass));
    }


    Contact::ContactConstants
    projectile_contact_constants(const Parameters &prm,
                                 const double truss_k,
                                 const double sphere_mass)
    {
      // The projectile is much heavier than a sphere: m_eff = m.
      return contact_constants(prm,
                               prm.projectile_stiffness_ratio,
                               prm.projectile_damping_ratio,
                               prm.projectile_friction,
                               truss_k,
                               sphere_mass);
    }


    double
    critical_time_step(const Parameters &prm,
                       const double truss_k,
                       const double sphere_mass)
    {
      const FibreContactLaw fibre =
        fibre_contact_law(prm, truss_k, sphere_mass);
      const Contact::ContactConstants projectile =
        projectile_contact_constants(prm, truss_k, sphere_mass);
      const double omega2 =
        2. *
        (2. * truss_k + prm.coordination * fibre.k_n + projectile.stiffness) /
        sphere_mass;
      return 2. / std::sqrt(omega2) * damping_step_factor(prm);
    }


    double
    damping_step_factor(const Parameters &prm)
    {
      const double zeta =
        std::max(prm.damping_ratio, prm.projectile_damping_ratio);
      return std::sqrt(1. + zeta * zeta) - zeta;
    }
  } // namespace DEM
} // namespace YarnImpact
