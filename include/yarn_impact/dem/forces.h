#ifndef yarn_impact_dem_forces_h
#define yarn_impact_dem_forces_h

#include <yarn_impact/contact/contact_law.h>
#include <yarn_impact/dem/decomposition.h>
#include <yarn_impact/dem/fibre_chains.h>
#include <yarn_impact/dem/neighbour_lists.h>
#include <yarn_impact/dem/parameters.h>
#include <yarn_impact/dem/spheres.h>

#include <vector>

namespace YarnImpact
{
  class Projectile;

  namespace DEM
  {
    namespace internal
    {
      /**
       * The forces of the trusses (s, s+1) with at least one owned end, on
       * the positions @p x [m], added to @p F [N]. With @p failure, a truss
       * strained beyond @p failure_strain [-] breaks (its flag in
       * @p broken) and its elastic energy is added to @p dissipated [J]
       * (one value per sphere) of the truss's owned sphere at the lower
       * station, and @p time [s] to its @p break_time.
       */
      void
      truss_forces(const FibreChains &chains,
                   const Decomposition &decomposition,
                   const bool failure,
                   const double failure_strain,
                   const double *__restrict x,
                   double *__restrict F,
                   std::uint8_t *__restrict broken,
                   const double time,
                   double *__restrict break_time,
                   double *__restrict dissipated);

      /**
       * The fibre-fibre contact forces of the listed pairs of @p blocks by
       * @p law over the step @p dt [s] on positions @p x [m] and velocities
       * @p v [m/s], added to @p F [N]; the pairs' contact flags and
       * tangential histories are updated, the energy dissipated by the
       * pairs of a row is added to @p dissipated [J] (one value per sphere)
       * of the row's sphere, if owned.
       */
      void
      fibre_contact_forces(std::vector<ListBlock> &blocks,
                           const FibreContactLaw &law,
                           const double d,
                           const Decomposition &decomposition,
                           const double *__restrict x,
                           const double *__restrict v,
                           double *__restrict F,
                           const double dt,
                           double *__restrict dissipated);

      /**
       * The contact forces of the mirror pairs of @p blocks (a sphere with
       * the image of another one, or of itself, in a symmetry plane), as
       * fibre_contact_forces(): i feels the force, j its mirror image
       * (nothing more for a self-image pair); the dissipated energy goes to
       * the lower sphere, i, if owned.
       */
      void
      mirror_contact_forces(std::vector<ListBlock> &blocks,
                            const FibreContactLaw &law,
                            const double d,
                            const Decomposition &decomposition,
                            const double *__restrict x,
                            const double *__restrict v,
                            double *__restrict F,
                            const double dt,
                            double *__restrict dissipated);

      /**
       * The contact forces of the rigid cylindrical @p projectile on the
       * owned spheres of the cross-sections that can reach it, by the law
       * @p law_type built from @p constants, over the step @p dt [s], added to
       * the forces of @p spheres [N]; the energy dissipated is added to
       * each sphere's `dissipated` [J] and the contact geometry stored in
       * @p contact.
       * The law is chosen once per call, not per sphere.
       * @return the reaction (y-force on the projectile) of this rank's
       * modelled part [N]
       */
      double
      projectile_contact_forces(const Projectile &projectile,
                                const Contact::LawType law_type,
                                const Contact::ContactConstants &constants,
                                const FibreChains &chains,
                                const Decomposition &decomposition,
                                Spheres &spheres,
                                const double dt,
                                ProjectileContactState &contact);
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
