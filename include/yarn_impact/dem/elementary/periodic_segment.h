#ifndef yarn_impact_dem_elementary_periodic_segment_h
#define yarn_impact_dem_elementary_periodic_segment_h

#include <yarn_impact/contact/contact_law.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/dem/elementary/elementary_test.h>
#include <yarn_impact/dem/parameters.h>
#include <yarn_impact/dem/truss.h>
#include <yarn_impact/mechanics/kinematics.h>

#include <mpi.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace YarnImpact
{
  namespace DEM
  {
    /** The periodic yarn segment of the DEM elementary tests
     * (doc/identification.md section 2); used by elementary_test.cc. The
     * segment's members are defined in periodic_segment.cc (set-up and
     * step), periodic_segment_lists.cc, periodic_segment_forces.cc and
     * periodic_segment_measures.cc. */
    namespace internal
    {
      /** The separation @p dx [m] along the periodic axis of length @p L
       * [m] taken to the nearest image; |dx| < 1.5 L here (the same result
       * as dx - L round(dx/L), without the call). Used by the lists, the
       * forces and the measures of the segment alike. */
      inline double
      nearest_image(const double dx, const double L)
      {
        return dx > 0.5 * L ? dx - L : (dx < -0.5 * L ? dx + L : dx);
      }


      /** A rigid wall normal to y or z: a plate (y) or a side wall (z). */
      struct Wall
      {
        /** Whether it exists. */
        bool active = false;
        /** Axis of its normal: 1 (y) or 2 (z). */
        unsigned int axis = 1;
        /** +1: the wall bounds the yarn from above (x_axis < pos), -1 from
         * below. */
        double side = 1.;
        /** Position along its axis [m] and velocity [m/s]. */
        double position = 0., velocity = 0.;
        /** Sum of the normal contact forces on it, positive when the yarn
         * pushes it outwards [N], and its number of contacts. */
        double load       = 0.;
        unsigned int n_in = 0;
        /** Integral part of the servo's velocity [m/s]. */
        double integral = 0.;
      };

      /** Values summed over all spheres for one CSV row. */
      struct Sums
      {
        /** Virial of the trusses and contacts, xx yy zz yz xy xz [N m]. */
        double virial[6] = {0., 0., 0., 0., 0., 0.};
        double kinetic = 0., truss = 0., contact = 0., dissipated = 0.;
      };


      /**
       * The periodic segment: `stations` cross-sections of the yarn's fibres
       * along x, the last joined to the first by a truss across the period.
       * Every rank holds the positions and velocities of all spheres and
       * integrates those of its own fibres (a contiguous range); the
       * walls' contacts are evaluated for all spheres by every rank, so
       * that their loads are the same on every rank.
       */
      class PeriodicSegment
      {
      public:
        /** Lay out the fibres of @p shared and @p dem on @p test's number
         * of cross-sections, split them between the ranks of @p comm, and
         * compute the first forces.
         * @throw InputError on an impossible set-up */
        PeriodicSegment(const YarnImpact::Parameters::Shared &shared,
                        const Parameters &dem,
                        const ElementaryTestParameters &test,
                        const MPI_Comm comm);

        /** Back to the packed, unloaded, unbroken reference state. */
        void
        reset();

        /** One velocity-Verlet step of length dt. */
        void
        step();

        /** Sums over all spheres (collective). */
        Sums
        sums();

        /** Affine deformation gradient of the spheres (least-squares fit
         * of the current (y, z) to the reference ones), row-major 3x3. */
        void
        affine_gradient(Mechanics::Matrix3 &F) const;

        /** Centred second moments <y^2>, <z^2> of the sphere centres
         * [m^2]. */
        std::pair<double, double>
        second_moments() const;

        /** Extreme coordinate of the sphere centres along @p axis. */
        double
        extreme(const unsigned int axis, const double side) const;

        /** The fibres' first break strains, in fibre order, -1 for an
         * unbroken fibre (collective). */
        std::vector<double>
        break_strains() const;

        // Set-up data.
        const YarnImpact::Parameters::Shared &shared;
        const Parameters &dem;
        const ElementaryTestParameters &test;
        const MPI_Comm comm;
        unsigned int rank = 0, n_ranks = 1;
        unsigned int nf = 0, ns = 0;
        std::size_t n = 0;
        double d = 0., radius = 0., L0 = 0., mass = 0., truss_k = 0.;
        double dt = 0., cutoff = 0., packing_scale = 1.;
        /** Reference volume: the FE yarn's ellipse times the segment length
         * [m^3]. */
        double V0 = 0.;
        /** Segment length at rest and now [m]. */
        double Lx0 = 0., Lx = 0.;
        /** The impact model's fibre-fibre law. */
        FibreContactLaw fibre_law;
        /** The walls' law: the projectile's normal constants on the
         * Cundall-Strack law without friction, whatever
         * `Projectile contact law` says. */
        Contact::CundallStrackLaw wall_law;
        unsigned int f_begin = 0, f_end = 0;
        std::size_t i_begin = 0, i_end = 0;

        // State.
        double time = 0.;
        /** Imposed axial strain of the segment (tension) [-]. */
        double axial_strain = 0.;
        std::vector<double> X0, x, v, a;
        std::vector<std::uint8_t> broken; ///< truss (s, s+1) of each sphere
        std::vector<double> fibre_break;  ///< first break strain per fibre
        std::vector<double> dissipated;   ///< cumulative, per own sphere
        double wall_dissipated = 0.;
        std::vector<double> virial; ///< 6 per own sphere, last evaluation
        Wall walls[4];              ///< +y, -y, +z, -z
        /** External virial of the walls, yy and zz [N m]. */
        double wall_virial[2]    = {0., 0.};
        unsigned long n_rebuilds = 0;

      private:
        /** @p mine, @p per values for each own sphere (or each own fibre
         * with @p per_fibre), gathered from all ranks in sphere (fibre)
         * order, so that sums over it do not depend on the ranks. */
        std::vector<double>
        gather(const std::vector<double> &mine,
               const unsigned int per,
               const bool per_fibre) const;
        void
        exchange();
        void
        build_lists();
        void
        compute_forces();

        std::vector<std::uint32_t> start;
        std::vector<std::uint32_t> neighbour;
        std::vector<std::uint8_t> touching;
        std::vector<double> history;
        std::vector<double> x_built;
        std::vector<int> counts, offsets;
        std::vector<double> buffer;
      };

    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
