#ifndef yarn_impact_dem_parameters_h
#define yarn_impact_dem_parameters_h

#include <yarn_impact/contact/contact_law.h>
#include <yarn_impact/core/memory_estimate.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/dem/packing.h>

#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace YarnImpact
{
  /** The microscopic discrete-element reference model (doc/dem.md). */
  namespace DEM
  {
    /**
     * The fibre-fibre contact law: always the spring-dashpot with a
     * tangential spring (the pair kernels keep its history), unlike the
     * projectile's, which is chosen by `Projectile contact law`.
     */
    using FibreContactLaw = Contact::CundallStrackLaw;

    /** How the impact model bounds its stable time step (`Stable time
     * step`, doc/theory.md section 3.2). */
    enum class StableStep
    {
      contacts,     ///< from the springs it has now, direction by direction
      coordination, ///< scalar Gershgorin bound with `Coordination number`
    };

    /** Where the fibre centres come from. */
    enum class FibreLayout
    {
      hexagonal, ///< hexagonal packing inside the (scaled) ellipse
      file,      ///< (y, z) centres read from a file
    };

    /**
     * Parameters of the DEM model (subsection `DEM`); doc/dem.md explains
     * every default.
     */
    struct Parameters
    {
      /** Fibre layout (`Fibre layout`). */
      FibreLayout layout = FibreLayout::hexagonal;
      /** File with one `y z` fibre centre per line [m] (`Fibre file`). */
      std::string fibre_file;
      /** Largest factor by which the ellipse may be enlarged so that the
       * hexagonal packing holds exactly N fibres [-]. */
      double max_packing_scale = 1.1;
      /** Largest distance between two spheres of a fibre [m]. */
      double sphere_spacing = 12e-6;
      /** Fibre-fibre normal penalty stiffness over the truss stiffness
       * \f$EA/L_0\f$ [-]. */
      double normal_stiffness_ratio = 0.5;
      /** Tangential over normal contact stiffness [-]. */
      double tangential_stiffness_ratio = 2. / 7.;
      /** Fibre-fibre normal damping, fraction of critical [-]. */
      double damping_ratio = 0.1;
      /** Fibre-fibre Coulomb friction coefficient [-]. */
      double friction = 0.2;
      /** Projectile-fibre normal stiffness over the truss stiffness [-]. */
      double projectile_stiffness_ratio = 0.5;
      /** Projectile-fibre normal damping, fraction of critical [-]. */
      double projectile_damping_ratio = 0.1;
      /** Projectile-fibre Coulomb friction coefficient [-]. */
      double projectile_friction = 0.2;
      /** Projectile-fibre contact law (`Projectile contact law`). */
      Contact::LawType projectile_contact_law =
        Contact::LawType::cundall_strack;
      /** Verlet skin of the neighbour lists [m]. */
      double skin = 4e-6;
      /** How the impact model bounds its stable step. */
      StableStep stable_step = StableStep::contacts;
      /** Contacts per sphere assumed by the scalar stable time step (the
       * elementary tests, and the impact model with `Stable time step =
       * coordination`) [-]. */
      unsigned int coordination = 6;
      /** Cross-sections copied from each neighbouring rank at the start;
       * the layer grows by itself when fibres slide across a rank
       * boundary [-]. */
      unsigned int ghost_stations = 4;
      /** Cross-sections per neighbour-list block: each block is rebuilt on
       * its own when its criterion fails (doc/dem.md section 4) [-]. */
      unsigned int list_block = 32;
      /** With half or quarter symmetry and several MPI ranks: the first
       * rank's slab (which holds the impact point, where contacts are
       * densest and lists are rebuilt most often) as a fraction of an even
       * share of the cross-sections; the other ranks share the rest
       * evenly. Only the speed depends on it [-]. */
      double impact_slab_share = 0.92;
      /** On several MPI ranks: when a rank must rebuild a list block, every
       * rank also rebuilds its blocks whose criterion has used this
       * fraction of the skin, in the same step (they would fail within a
       * few steps, each rank on its own, while the others wait); 1
       * rebuilds only failing blocks. Only the speed depends on it [-]. */
      double joint_rebuild_fraction = 0.6;
      /** When a list block's criterion fails or its halo grows: the
       * largest share of the block's spheres that may be fast (moved more
       * than the partial search threshold since the build, or joined the
       * halo) for only those to be searched again (doc/dem.md section 4,
       * "Partial searches"); with more, the block is rebuilt whole. 0 always
       * rebuilds whole blocks. Only the speed depends on it [-]. */
      double partial_search_fraction = 0.;
      /** Verify after every list update, by a sweep over the spheres sorted
       * along x that knows nothing of the lists, that every pair closer
       * than the diameter (and every such mirror image) is listed; a
       * missing pair stops the run. For tests: the sweep makes a run 3
       * (40 fibres) to 25 (400 fibres) times as long. */
      bool check_lists = false;
      /** Time the parts of the step in the four phases of an impact
       * (before contact, to the first break, to the cut, after it) and
       * print the table in the run summary (dem/phase_timer.h). Off by
       * default: the summary then holds no wall times. */
      bool phase_timing = false;
      /** When a neighbour-list block is rebuilt (doc/dem.md section 4). */
      enum class ListRebuilds
      {
        /** When its displacement bound reaches the skin (sound, cheap). */
        criterion,
        /** Only when the sweep of check_lists, run before every force
         * evaluation, finds a contact that the block does not list: how
         * few rebuilds the contacts need (a diagnostic, as slow as
         * check_lists). */
        missed_contact
      };
      ListRebuilds list_rebuilds = ListRebuilds::criterion;

      /**
       * Set by a coupling (`Model = hybrid`, coupling/hybrid_model.h), never
       * by a `.prm`: the particle weight of the bridging domain
       * (doc/hybrid.md) per modelled station (sphere masses, contacts,
       * kinetic and contact energies) and per truss after each station
       * (stiffness, strain energy). With them, the last station is the
       * end of the DEM part, tied to the continuum, not a clamp. Empty: the
       * DEM alone, every weight 1.
       */
      std::vector<double> station_weight, truss_weight;

      /**
       * Set by a coupling, never by a `.prm`: when not negative, the model
       * is the clamp part of a hybrid yarn (doc/hybrid.md section 3.1), the
       * fibres from x = clamp_part_begin [m] to the clamp at L/2 of the
       * yarn of its shared parameters, on the DEM's stations of the whole
       * yarn, with no symmetry plane in it: its first station is the end
       * tied to the continuum (with the weights above), its last the
       * clamp. Negative: the part around the impact point (or the whole
       * yarn).
       */
      double clamp_part_begin = -1.;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };

    /**
     * The fibre centres of the yarn described by @p shared and @p parameters
     * (hexagonal packing or fibre file), after the checks that need no MPI
     * ranks: the sphere spacing against the fibre diameter, a packing that
     * fits (or a fibre file that can be read, holds Yarn/Number of fibres
     * centres and no overlap) and, with @p symmetric_z (quarter symmetry), a
     * layout that is its own mirror image in z = 0. The impact model, the
     * elementary tests and validate() share it, so that each check is written
     * once and `--check` refuses what the run refuses.
     * @throw InputError naming the parameter or the file
     */
    FibreCentres
    fibre_centres(const YarnImpact::Parameters::Shared &shared,
                  const Parameters &parameters,
                  const bool symmetric_z);

    /**
     * Check the DEM set-up against the shared parameters before anything is
     * written (called while the parameters are parsed, so also by
     * `--check`): fibre_centres() for the impact model, with quarter
     * symmetry when Symmetry = quarter, or, with @p elementary_test, for the
     * periodic segment of the elementary tests, which ignores Symmetry.
     * Builds the fibre centres only (milliseconds), not the spheres. The
     * check that depends on the number of MPI ranks (ghost stations against
     * slabs) is left to the model.
     * @throw InputError naming the parameter or the file
     */
    void
    validate(const YarnImpact::Parameters::Shared &shared,
             const Parameters &parameters,
             const bool elementary_test = false);

    /**
     * Memory the DEM set-up will need (600 B per sphere: 300 B measured at
     * set-up between 33 600 and 134 000 spheres, doubled for the lists and
     * ghosts that grow during the impact), and the parameter that makes it
     * large.
     */
    MemoryEstimate
    memory_estimate(const YarnImpact::Parameters::Shared &shared,
                    const Parameters &parameters);

    /**
     * The fibre-fibre contact law of @p prm between spheres of mass
     * @p sphere_mass [kg] whose trusses have the stiffness @p truss_k
     * [N/m]: normal penalty and damping (c = 2 zeta sqrt(m_eff k), m_eff =
     * m/2), tangential spring and Coulomb friction (doc/dem.md section 2).
     * The impact model and the elementary tests use this one law.
     */
    FibreContactLaw
    fibre_contact_law(const Parameters &prm,
                      const double truss_k,
                      const double sphere_mass);

    /** The constants of the projectile-fibre contact of @p prm, as
     * fibre_contact_law() (m_eff = m, the sphere's mass, which is also the
     * mass of ContactConstants); the law `projectile_contact_law` of @p prm
     * is built from them, and the elementary tests' rigid walls use their
     * normal part. */
    Contact::ContactConstants
    projectile_contact_constants(const Parameters &prm,
                                 const double truss_k,
                                 const double sphere_mass);

    /**
     * Largest stable step of a sphere of mass @p sphere_mass [kg] with two
     * trusses of stiffness @p truss_k [N/m], DEM/Coordination fibre
     * contacts and one projectile (or wall) contact: the Gershgorin bound
     * of doc/theory.md section 3.2, reduced for the contact damping, before
     * the safety factor [s].
     */
    double
    critical_time_step(const Parameters &prm,
                       const double truss_k,
                       const double sphere_mass);

    /**
     * The factor sqrt(1 + zeta^2) - zeta [-] by which viscous contact
     * damping of ratio zeta (the larger of the fibre and the projectile
     * contacts' of @p prm) lowers the stable step of an undamped bound
     * (doc/theory.md section 3.2).
     */
    double
    damping_step_factor(const Parameters &prm);

  } // namespace DEM
} // namespace YarnImpact

#endif
