#ifndef yarn_impact_dem_observables_h
#define yarn_impact_dem_observables_h

#include <yarn_impact/contact/contact_law.h>
#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/dem/decomposition.h>
#include <yarn_impact/dem/fibre_chains.h>
#include <yarn_impact/dem/neighbour_lists.h>
#include <yarn_impact/dem/parameters.h>
#include <yarn_impact/dem/spheres.h>

#include <string>
#include <vector>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      /**
       * The observables of the DEM impact model for the history: energies
       * (kinetic, trusses, contacts, dissipated), failed trusses, the
       * largest strain, whether the yarn is cut through, and the profile of
       * the stations folded about x = 0 (on which analysis measures the
       * wave fronts). Reads the model's parts
       * given at construction; every call is collective.
       */
      /** Every broken truss of the model, its break time and where it
       * lies (the mid-point of its reference stations), gathered from the
       * ranks that own its lower sphere and sorted by break_less(): the
       * same on every rank (collective). */
      std::vector<FibreBreak>
      gather_fibre_breaks(const FibreChains &chains,
                          const Decomposition &decomposition,
                          const Spheres &spheres);


      class ObservablesMeter
      {
      public:
        /** A meter of the model made of these parts; @p fibre_law and the
         * projectile's law @p projectile_law with its @p projectile_constants
         * are read at every measure(). */
        ObservablesMeter(const FibreChains &chains,
                         const Decomposition &decomposition,
                         const Spheres &spheres,
                         const NeighbourLists &lists,
                         const FibreContactLaw &fibre_law,
                         const Contact::LawType projectile_law,
                         const Contact::ContactConstants &projectile_constants);

        /** Record the initial width of the folded profile [m] (at set-up,
         * collective). */
        void
        record_initial_width();

        /**
         * The observables now; the projectile contacts are those of the
         * last force evaluation, at @p contact. The yarn is cut through when
         * every fibre has a failed truss. Every sum over the spheres (the
         * energies, the failed trusses, the section's second moments) is a
         * ReproducibleSum with each term counted on one rank (a pair on the
         * rank that owns its lower sphere), so that the observables are the
         * same, bit for bit, on any number of ranks.
         */
        Observables
        measure(const ProjectileContactState &contact) const;

      private:
        const FibreChains &chains;
        const Decomposition &decomposition;
        const Spheres &spheres;
        const NeighbourLists &lists;
        const FibreContactLaw &fibre_law;
        const Contact::LawType projectile_law;
        const Contact::ContactConstants &projectile_constants;
        /** Initial width of each profile station [m]. */
        std::vector<double> initial_width;
        /** Scratch of the reductions. */
        mutable std::vector<double> profile_buffer;
      };


      /**
       * Write the VTU piece of this rank's owned cross-sections (plus the
       * first ghost one on the right, so that the trusses across the rank
       * boundary are drawn) as `dem_NNNN_rQ.vtu` in @p directory, and on
       * rank 0 the record `dem_NNNN.pvtu` (collective).
       * @return the name of the record
       */
      std::string
      write_snapshot(const FibreChains &chains,
                     const Decomposition &decomposition,
                     const Spheres &spheres,
                     const std::string &directory,
                     const unsigned int index);
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
