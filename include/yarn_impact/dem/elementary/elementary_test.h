#ifndef yarn_impact_dem_elementary_elementary_test_h
#define yarn_impact_dem_elementary_elementary_test_h

#include <yarn_impact/core/parameters.h>
#include <yarn_impact/dem/parameters.h>

#include <mpi.h>

#include <iosfwd>
#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace YarnImpact
{
  namespace DEM
  {
    /** Which homogeneous deformation an elementary test imposes on the
     * periodic yarn segment (doc/identification.md section 2). */
    enum class ElementaryLoading
    {
      none,       ///< no elementary test: the impact
      tension,    ///< stretch along the fibres, to failure
      compaction, ///< rigid plates normal to y close, z free; then reopen
      distortion, ///< as compaction, under a confining pressure in z
    };

    /** The walls normal to z in the compaction test. */
    enum class SideWalls
    {
      none,  ///< the section is free to spread in z
      fixed, ///< rigid frictionless walls where the section's edges start
    };

    /**
     * Parameters of the DEM elementary tests (subsection `Elementary test`).
     * The segment has the impact model's fibres, packing, contact laws and
     * friction (subsections `Yarn` and `DEM`).
     */
    struct ElementaryTestParameters
    {
      /** The loading; none runs the impact. */
      ElementaryLoading loading = ElementaryLoading::none;
      /** Cross-sections of the periodic segment, at DEM/Sphere spacing
       * (at least 3, so that a sphere meets one periodic image of another)
       * [-]. */
      unsigned int stations = 4;
      /** Rate of the imposed strain: of the segment's length (tension) or
       * of the plate gap (compaction, distortion) [1/s]. */
      double strain_rate = 2e3;
      /** Largest imposed strain: axial engineering strain (tension) or
       * plate strain 1 - gap/gap_0 (compaction, distortion) [-]. */
      double max_strain = 0.4;
      /** Whether the plates reopen to their starting gap after loading. */
      bool unload = true;
      /** Compaction: whether walls normal to z hold the section's width. */
      SideWalls side_walls = SideWalls::none;
      /** Local (non-viscous) damping coefficient alpha in [0, 1): each force
       * component is reduced by alpha |F| against the velocity [-]. */
      double local_damping = 0.7;
      /** Time constant of a viscous damping of every sphere's velocity
       * (0: none) [s]. */
      double damping_time = 2e-6;
      /** Confining pressures of the distortion test, one run each [Pa]. */
      std::vector<double> confining_pressures = {2e6, 10e6, 50e6};
      /** Time during which the four walls of the distortion test are held
       * at the confining pressure before the plates close [s]. */
      double consolidation_time = 10e-6;
      /** Imposed-strain increment between two rows of the CSV [-]. */
      double output_strain_interval = 0.005;

      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };

    /**
     * Run the elementary test @p test on a periodic segment of the yarn of
     * @p shared and @p dem, and write
     * `<Output/Directory>/elementary_<loading>.csv` (one row per output
     * increment: imposed deformation, affine deformation gradient, Charmetant
     * invariants, Kirchhoff stress of the segment from its virial and from its
     * boundary forces, energies, broken fibres). With Output/Verbosity = test
     * the summary is deterministic. Collective over @p communicator: every rank
     * holds the positions of all spheres and computes the forces on the spheres
     * of its own fibres, so 1 and N ranks give the same curves bit for bit.
     * @param out the set-up report and the summary (rank 0 writes)
     * @return whether every check of the summary passed
     * @throw InputError on an impossible set-up, RunError on a blow-up
     */
    bool
    run_elementary_test(const YarnImpact::Parameters::Shared &shared,
                        const Parameters &dem,
                        const ElementaryTestParameters &test,
                        const MPI_Comm communicator,
                        std::ostream &out);

    /** File name of the CSV that run_elementary_test() writes for
     * @p loading (relative to Output/Directory). */
    std::string
    elementary_test_file(const ElementaryLoading loading);
  } // namespace DEM
} // namespace YarnImpact

#endif
