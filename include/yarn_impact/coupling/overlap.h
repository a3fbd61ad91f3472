#ifndef yarn_impact_coupling_overlap_h
#define yarn_impact_coupling_overlap_h

#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/coupling/bridging_domain.h>
#include <yarn_impact/coupling/fibre_bars.h>
#include <yarn_impact/coupling/hybrid_model.h>
#include <yarn_impact/coupling/section_tie.h>
#include <yarn_impact/dem/dem_model.h>

#include <deal.II/grid/tria.h>

#include <mpi.h>

#include <array>
#include <utility>
#include <vector>

namespace YarnImpact
{
  namespace Coupling
  {
    /**
     * One overlap of the hybrid yarn: the DEM part it ties to the FE part,
     * the constraint, and the work done through it.
     */
    struct Overlap
    {
      /** The DEM part it ties (owned by the model). */
      ImpactModel *dem_part = nullptr;
      /** Reference x of its first node layer [m]. */
      double x_begin = 0.;
      /** The DEM part's stations it ties: [station_begin, station_end). */
      unsigned int station_begin = 0, station_end = 0;

      /** With quarter symmetry: the FE nodes on the plane z = 0 are held
       * in z, and so are they in the constraint. */
      bool z_symmetry = false;

      /**
       * The overlap on x < 0 of a whole yarn, whose FE part (and bars) is
       * built as the mirror image x -> -x of the one on x > 0
       * (FE::Parameters::mirrored): the spheres' reference x, forces and
       * accelerations are reflected into that frame and back, and the
       * spheres are counted from the station nearest the DEM-only zone,
       * so that the constraint is the one of x > 0 (x_begin is then the
       * mirror image's, a - w).
       */
      bool mirrored = false;

      /** The DEM station of the @p q-th coupled station, counted from the
       * DEM-only zone [-]. */
      unsigned int
      station_of(const unsigned int q) const
      {
        return mirrored ? station_end - 1 - q : station_begin + q;
      }
      /** The inverse of station_of() [-]. */
      unsigned int
      coupled_station(const unsigned int s) const
      {
        return mirrored ? station_end - 1 - s : s - station_begin;
      }
      /** The factor from the DEM's x components to the FE part's (and
       * back) [-]. */
      double
      x_sign() const
      {
        return mirrored ? -1. : 1.;
      }

      BridgingConstraint constraint;
      /** The transverse tie's section modes per node layer
       * (HybridParameters::transverse_modes; 0: y and z by `constraint`,
       * sphere by sphere) [-]. */
      unsigned int transverse_modes = 0;
      /** With transverse_modes > 0: y and z tied on the section's coarse
       * modes only (doc/hybrid.md section 2.5); x by the bars' ties. */
      SectionTie section_tie;
      /** Coupled FE nodes owned here: coupled index and local dofs. */
      std::vector<std::pair<unsigned int, std::array<unsigned int, 3>>>
        owned_nodes;
      /** Work done by the continuum on the particles (the multipliers'
       * power, summed), in the modelled part [J]. */
      double work = 0.;
      /** The multipliers' generalised forces of the last step on the
       * overlap's nodes (N^T lambda, 3 per node) and, under fibre bars,
       * on each fibre's tied bar nodes (the x component, by fibre and
       * node) [N]: the work over a step averages them with the step's
       * own, as the kicks apply forces (doc/hybrid.md section 2.3). */
      std::vector<double> previous_node_multipliers, previous_bar_multipliers;
      std::vector<double> node_force, particle_force, node_acceleration,
        particle_acceleration, multipliers;
      /** The overlap's node velocities [m/s], N^T lambda [N] and zeros,
       * for the coupling's power. */
      std::vector<double> node_velocity, node_multipliers, zero_node_force;
      /** Fibres of the DEM part. */
      unsigned int n_fibres = 0;

      /**
       * With a far field of fibre bars (owned by the model; null: the
       * continuum's): the spheres' axial motion is tied to their own
       * fibre's bars instead of the continuum (whose axial motion is then
       * held), one constraint per fibre over the overlap's bar nodes
       * (doc/hybrid.md section 3.4); y and z stay tied to the continuum.
       */
      FibreBars *bars = nullptr;
      /** The bars' node at the overlap's x_begin: 0 by the nose, the
       * first of the clamp overlap's nodes at the clamp (set by
       * set_up) [-]. */
      unsigned int bar_offset = 0;
      std::vector<ChainConstraint> fibre_constraints;
      /** One fibre's bar node and sphere forces, accelerations and
       * multipliers (one value each, the x component). */
      std::vector<double> bar_force, bar_acceleration, sphere_force,
        sphere_acceleration, sphere_multipliers, zeros;

      /**
       * Find the overlap's nodes of the FE part @p fe_model (the vertices
       * of @p section on the layout's node layers from x_begin) and the
       * DEM part's spheres of [station_begin, station_end), build and
       * factorise the constraint, and apply it once (collective).
       */
      void
      set_up(ImpactModel &fe_model,
             const dealii::Triangulation<2> &section,
             const HybridLayout &layout,
             const YarnImpact::Parameters::Yarn &yarn,
             const MPI_Comm communicator);

      /**
       * Tie the overlap: gather its nodes' and spheres' forces, replace
       * them by those that give each the coupled acceleration
       * (BridgingConstraint), and add the multipliers' work over the
       * step @p dt [s] (collective).
       */
      void
      couple(ImpactModel &fe_model,
             const double dt,
             const MPI_Comm communicator);

      /** The largest generalised force of the coupled system on the
       * overlap's nodes (continuum and, under fibre bars, bar nodes) from
       * the forces the last couple() gathered [N]: zero in equilibrium
       * (the patch test). */
      double
      largest_generalised_force() const;

    private:
      /** The bar nodes' forces of the overlap before the last tie, by
       * fibre and node [N]. */
      std::vector<double> gathered_bar_force;

      /** Build and factorise the per-fibre axial constraints. */
      void
      set_up_axial_ties(const HybridLayout &layout,
                        const DEM::CouplingView &dem);

      /** Solve them: the bar nodes' and spheres' coupled axial
       * accelerations (bars->force, particle_acceleration's x) from the
       * gathered forces; returns the multipliers' power [W]. */
      double
      tie_axially();

      /** @p n zeros. */
      const double *
      zero_force(const unsigned int n)
      {
        zeros.resize(n, 0.);
        return zeros.data();
      }
    };
  } // namespace Coupling
} // namespace YarnImpact

#endif
