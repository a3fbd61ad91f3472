#ifndef yarn_impact_coupling_hybrid_model_h
#define yarn_impact_coupling_hybrid_model_h

#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/memory_estimate.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/dem/parameters.h>
#include <yarn_impact/fe/parameters.h>

#include <mpi.h>

#include <memory>

namespace dealii
{
  class ParameterHandler;
}

namespace YarnImpact
{
  namespace Coupling
  {
    /** The parameters of `Model = hybrid` (subsection `Hybrid`). */
    struct HybridParameters
    {
      /** Half-length a of the DEM part, |x| <= a, before rounding to whole
       * FE cells from the clamp [m]. */
      double dem_half_length = 3e-3;
      /** Width w of the overlap a - w <= |x| <= a, before rounding to whole
       * FE cells [m]. */
      double overlap_width = 1e-3;

      /** Length b of the DEM part at the clamp, L/2 - b <= x <= L/2, before
       * rounding to whole FE cells; 0: none, the FE part reaches the clamp
       * [m]. */
      double clamp_dem_length = 0.;

      /** The far field: the identified continuum alone (false), or the
       * continuum's section motion with each fibre's own axial bars
       * (true, `Far field = fibre bars`, doc/hybrid.md section 3.4). */
      bool fibre_bars = false;
      /** Fibre bars per FE cell; 0: one per DEM truss [-]. */
      unsigned int bars_per_cell = 0;
      /** FE cells along the axis of the hybrid's FE part over the half
       * yarn, in place of `FE/Cells along the axis`; 0: that entry [-]. */
      unsigned int fe_axial_cells = 0;

      /** The overlap's transverse tie (`Transverse tie`, doc/hybrid.md
       * section 2.5): 0, every sphere on the continuum's field (`field`);
       * 1, the section's mean per node layer (`section mean`); 3, its mean
       * and linear moments (`section affine`) [-]. */
      unsigned int transverse_modes = 0;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };

    /**
     * Where the parts of a hybrid yarn lie on x >= 0, rounded so that the
     * FE cells of the overlap hold whole DEM truss lengths and its node
     * layers sit on DEM stations (doc/hybrid.md section 3.1). With
     * `Symmetry = none` (whole) the DEM part spans |x| <= a and the side
     * x <= 0 has an FE part, an overlap and bars of its own, the mirror
     * images of these.
     */
    struct HybridLayout
    {
      /** The DEM's station spacing l, L / 2 over a whole number of trusses
       * [m]. */
      double station_spacing = 0.;
      /** Trusses per FE cell m [-], and the FE cell length h = m l [m]. */
      unsigned int cell_trusses = 0;
      double cell_length        = 0.;
      /** Cells of the overlap n_w and of the whole FE part [-]. */
      unsigned int overlap_cells = 0, fe_cells = 0;
      /** Trusses of the DEM part along a fibre [-]. */
      unsigned int dem_trusses = 0;
      /** The DEM part's half-length a and the overlap's start a - w [m]. */
      double dem_half_length = 0., overlap_begin = 0.;
      /** First DEM station of the overlap [-]. */
      unsigned int first_coupled_station = 0;
      /** The DEM part at the clamp (Hybrid/Clamp DEM length): its cells
       * and trusses (0: none), where it begins, x_c = L/2 - b, and where
       * the FE part ends, x_c + w (L/2 without it) [m]. */
      unsigned int clamp_cells = 0, clamp_trusses = 0;
      double clamp_begin = 0., fe_end = 0.;
      /** Whether the yarn is modelled whole (`Symmetry = none`): the DEM
       * part spans |x| <= a and the side x < 0 has the mirror images of
       * the FE part, its overlap and its bars. */
      bool whole = false;
      /** Whether the far field has fibre bars (HybridParameters), and how
       * many per FE cell [-]. */
      bool fibre_bars            = false;
      unsigned int bars_per_cell = 0;

      /** Particle weight beta of overlap cell @p k (0 at a - w) [-]. */
      double
      particle_weight(const unsigned int k) const
      {
        return 1. - (k + 0.5) / overlap_cells;
      }
      /** Particle weight of cell @p k of the clamp part's overlap (0 at
       * x_c, its free end) [-]. */
      double
      clamp_particle_weight(const unsigned int k) const
      {
        return (k + 0.5) / overlap_cells;
      }
    };

    /** The layout of @p hybrid for the yarn of @p shared; throws InputError
     * naming the parameter when it cannot be built. */
    HybridLayout
    hybrid_layout(const YarnImpact::Parameters::Shared &shared,
                  const FE::Parameters &fe,
                  const DEM::Parameters &dem,
                  const HybridParameters &hybrid);

    /** The set-up checks of `Model = hybrid`, with those of both parts;
     * throws InputError naming the parameter. */
    void
    validate(const YarnImpact::Parameters::Shared &shared,
             const FE::Parameters &fe,
             const DEM::Parameters &dem,
             const HybridParameters &hybrid);

    /** Memory of both parts; the parameter that makes it large is the DEM
     * half-length. */
    MemoryEstimate
    memory_estimate(const YarnImpact::Parameters::Shared &shared,
                    const FE::Parameters &fe,
                    const DEM::Parameters &dem,
                    const HybridParameters &hybrid);

    /**
     * The hybrid yarn (doc/hybrid.md): the DEM fibres on |x| <= a, the FE
     * continuum (density and axial modulus from the fibres, no failure) on
     * |x| >= a - w, coupled in the overlap by the bridging domain method
     * (BridgingConstraint): weights per FE cell layer, the overlap's
     * spheres moving with the continuum.
     */
    /**
     * The patch test of the coupling (doc/hybrid.md section 4): the hybrid
     * yarn of these parameters at rest under the uniform axial stretch
     * x -> (1 + @p strain) x of both parts, the projectile far away. Returns
     * the largest force on a degree of freedom of the coupled system (a
     * free sphere, an FE node outside the overlap, or an overlap node with
     * the forces of its spheres through N^T), over one fibre's tension
     * E_f A_f @p strain [-]: 0 without ghost forces. Collective.
     */
    double
    patch_test(const YarnImpact::Parameters::Shared &shared,
               const FE::Parameters &fe,
               const DEM::Parameters &dem,
               const HybridParameters &hybrid,
               const double strain,
               const MPI_Comm communicator);

    std::unique_ptr<ImpactModel>
    create_hybrid_model(const YarnImpact::Parameters::Shared &shared,
                        const FE::Parameters &fe,
                        const DEM::Parameters &dem,
                        const HybridParameters &hybrid,
                        const MPI_Comm communicator);
  } // namespace Coupling
} // namespace YarnImpact

#endif
