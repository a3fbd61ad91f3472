#ifndef yarn_impact_core_observables_h
#define yarn_impact_core_observables_h

#include <mpi.h>

#include <vector>

namespace YarnImpact
{
  /**
   * The yarn seen station by station along its axis, the same way in both
   * models: a station is an FE node layer or a DEM cross-section of
   * spheres. Stations are ordered by increasing distance from the impact
   * point and cover one side of the yarn (x >= 0); values of the side
   * x < 0, when modelled, are folded onto it by taking the larger one.
   * A model fills it; analysis (wave_fronts.h) measures the fronts on it.
   */
  struct StationProfile
  {
    /** Current (laboratory-frame) distance |x| of the station from the
     * impact plane [m]. */
    std::vector<double> position;
    /** Longitudinal (fibre) strain, \f$\lambda_f - 1\f$, averaged over the
     * section at the station (area-weighted, so that it is the yarn's
     * tension over its axial stiffness) [-]. */
    std::vector<double> axial_strain;
    /** Deflection in the impact direction, \f$-u_y\f$, the largest over
     * the station [m]. */
    std::vector<double> deflection;
    /** Current width of the section (extent along z) [m]. */
    std::vector<double> width;
    /** Width of the section at t = 0 [m]. */
    std::vector<double> initial_width;
    /** Second-moment width of the section, \f$4\sqrt{\langle z^2
     * \rangle}\f$ about the plane z = 0, area-weighted (FE: lumped nodal
     * masses; DEM: one weight per fibre centre). It is the full width
     * 2 a_z of a uniformly filled ellipse, and means the same in both
     * models (doc/identification.md section 2.4) [m]. */
    std::vector<double> rms_width;

    /** Resize all arrays to @p n stations, filled with zeros. */
    void
    resize(const unsigned int n);

    /** Number of stations. */
    unsigned int
    size() const
    {
      return position.size();
    }
  };

  /** Wave fronts and section data measured on a StationProfile (by
   * Analysis::measure_wave_fronts); one per history row. */
  struct WaveFrontPositions
  {
    /** Longitudinal (strain) front: outermost station with axial strain
     * above the strain threshold [m]. */
    double longitudinal = 0.;
    /** Transverse front: outermost station deflected by more than the
     * deflection threshold [m]. */
    double transverse = 0.;
    /** Spreading front: outermost station whose width grew by more than
     * the spreading threshold [m]. */
    double spreading = 0.;
    /** Section width at the impact point (first station) [m]. */
    double width_at_impact = 0.;
    /** Second-moment width at the impact point (first station) [m]. */
    double rms_width_at_impact = 0.;
    /** Mean axial strain in the middle half of the region between the
     * transverse and the longitudinal fronts: Smith's strain behind the
     * longitudinal front [-]. */
    double plateau_strain = 0.;
  };

  /**
   * What a model observes of itself at one instant (ImpactModel::
   * observables()), defined the same way in both models (doc/user-guide.md,
   * "History columns"). All values are those of the whole yarn, whatever
   * the symmetry. Nothing here is measured by analysis: the fronts are
   * measured on @p profile by the layer above (HistoryRow::fronts).
   */
  /**
   * One fibre break of a model that follows its fibres one by one (a DEM
   * truss, a fibre bar of the hybrid's far field): when, which fibre, and
   * where along the yarn, so that one can see whether a part of size a
   * holds the breaks (doc/user-guide.md, "Fibre breaks").
   */
  struct FibreBreak
  {
    /** Time of the step at which it broke [s]. */
    double time = 0.;
    /** The part that broke: "dem" or "bars". */
    const char *part = "dem";
    /** Fibre index in the model's fibre layout [-]. */
    unsigned int fibre = 0;
    /** Reference (initial) x of the broken element's mid-point, from the
     * impact point [m]; the fibre's reference y and z in the section [m]. */
    double x = 0., y = 0., z = 0.;
  };


  /** Order of fibre breaks in their file: by time, then x, then fibre. */
  inline bool
  break_less(const FibreBreak &a, const FibreBreak &b)
  {
    if (a.time != b.time)
      return a.time < b.time;
    if (a.x != b.x)
      return a.x < b.x;
    return a.fibre < b.fibre;
  }


  /** Every rank's @p own breaks, all of part @p part, on every rank, in
   * the order of break_less() (collective on @p communicator). */
  std::vector<FibreBreak>
  gather_fibre_breaks(const std::vector<FibreBreak> &own,
                      const char *part,
                      const MPI_Comm communicator);


  struct Observables
  {
    /** Kinetic energy of the yarn [J]. */
    double kinetic_energy = 0.;
    /** Elastic (strain) energy of the yarn [J]. */
    double elastic_energy = 0.;
    /** Energy stored in the contact penalty springs [J]. */
    double contact_energy = 0.;
    /** Energy dissipated so far by friction and contact damping [J]. */
    double dissipated_energy = 0.;
    /** Largest longitudinal strain in the yarn [-]. */
    double max_strain = 0.;
    /** Failed FE cells (broken by the sudden criterion, or whose fibre
     * damage reached 1) or broken DEM trusses, whole yarn [-]. Eroded
     * cells are not counted here (n_eroded). */
    unsigned long n_failed = 0;
    /** FE cells removed because they were crushed below J = 0.2, inverted
     * or gave a non-finite energy (erosion, not material failure), whole
     * yarn [-]; always 0 in the DEM. */
    unsigned long n_eroded = 0;
    /** FE cells whose fibre damage has started (0 < d, broken cells
     * included) with the progressive failure model, whole yarn [-]; 0 in
     * the DEM and with the sudden model, where failure is all or nothing.
     * The first damaged cell is the FE's first fibre break. */
    unsigned long n_damaged = 0;
    /** Momentum of the yarn in the impact direction (-y), the sum over
     * its nodes or spheres of mass times velocity (the masses weighted as
     * the kinetic energy's, so that a hybrid's parts add up), whole yarn
     * [kg m/s]. */
    double momentum = 0.;
    /** Kinetic and strain energy of each group of cells of a model that
     * sorts them (the FE model given FE::Parameters::energy_group) [J];
     * empty otherwise. They sum to kinetic_energy and elastic_energy to
     * round-off. */
    std::vector<double> group_kinetic_energy, group_elastic_energy;
    /** The values of the model's own history columns
     * (ImpactModel::extra_column_names()), in their columns' units; empty
     * for a model without any. */
    std::vector<double> extra_columns;
    /** Whether the yarn is cut through: no load path left between the
     * clamps (the run may stop then). */
    bool cut_through = false;
    /** The station profile of this instant, from which the fronts are
     * measured. The history keeps the fronts, not the profile (emptied
     * once measured: it is a few thousand numbers per row). */
    StationProfile profile;
  };
} // namespace YarnImpact

#endif
