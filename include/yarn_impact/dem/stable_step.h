#ifndef yarn_impact_dem_stable_step_h
#define yarn_impact_dem_stable_step_h

#include <yarn_impact/contact/contact_constants.h>
#include <yarn_impact/dem/decomposition.h>
#include <yarn_impact/dem/fibre_chains.h>
#include <yarn_impact/dem/neighbour_lists.h>
#include <yarn_impact/dem/parameters.h>
#include <yarn_impact/dem/spheres.h>

#include <vector>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      /**
       * The critical time step of the DEM impact model from the springs it
       * has now (`DEM/Stable time step = contacts`, doc/theory.md section
       * 3.2). With the stiffness written as a sum of springs, K = sum_e k_e
       * a_e a_e^T, where a spring e stretches by d_e . (u_i - u_j),
       *
       *   u^T K u = sum_e k_e (d_e . (u_i - u_j))^2
       *          <= 2 sum_i u_i^T K_ii u_i,  K_ii = sum_{f at i} k_f d_f d_f^T,
       *
       * so that the largest squared frequency is at most twice the largest
       * eigenvalue of a sphere's own 3x3 stiffness block over its mass. The
       * block sees directions: a truss along the fibre and a contact across
       * it do not add up as in a row sum. For a chain of trusses the bound
       * is exact (4 k/m).
       *
       * The springs: the trusses (axial, and the geometric stiffness T/l
       * across them), the fibre-fibre and mirror pairs in contact (the
       * normal spring, and the tangential one across it), and the projectile
       * contact of every sphere near it (the margin is given by the caller from
       * the projectile's speed). Only the pairs in contact: they are listed
       * whatever the partition and the list rebuilds, so the step is the
       * same on any number of ranks. Each rank evaluates its owned spheres;
       * one MPI_Allreduce gives the maximum. The directions and contacts
       * are those of the call; contacts that start before the next call
       * (`Time/Time step update interval` steps later) are covered by the
       * margin between the bound and the measured stability limit
       * (doc/performance-dem.md).
       */
      class ContactStableStep
      {
      public:
        /** The springs' constants: fibre contacts @p fibre_k_n and
         * @p fibre_k_t [N/m], projectile contact @p projectile [N/m]. */
        ContactStableStep(const FibreChains &chains,
                          const double fibre_k_n,
                          const double fibre_k_t,
                          const Contact::ContactConstants &projectile);

        /**
         * The bound on the largest squared angular frequency of the model
         * [1/s^2] for the positions of @p spheres, the lists @p blocks and
         * the projectile axis at height @p projectile_y [m] with contact
         * distance @p Rr [m] (R + r; 0: no projectile yet). Collective.
         */
        double
        omega2_bound(const Decomposition &decomposition,
                     const std::vector<ListBlock> &blocks,
                     const Spheres &spheres,
                     const double projectile_y,
                     const double Rr,
                     const double projectile_margin) const;

      private:
        const FibreChains &chains;
        const double k_n, k_t;
        const double k_p, k_pt;
        /** Scratch: the stiffness blocks of the owned spheres, 6 per
         * sphere [N/m]. */
        mutable std::vector<float> blocks_ii;
      };
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
