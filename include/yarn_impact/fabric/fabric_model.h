#ifndef yarn_impact_fabric_fabric_model_h
#define yarn_impact_fabric_fabric_model_h

#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/fabric/clamp_grip.h>
#include <yarn_impact/fabric/woven_patch.h>
#include <yarn_impact/fabric/yarn_contact.h>
#include <yarn_impact/fe/parameters.h>

#include <mpi.h>

#include <memory>
#include <string>

namespace YarnImpact
{
  namespace Fabric
  {
    /** What `Model = fabric` is made of (subsection `Fabric`, and the FE
     * yarns' subsection `FE`). */
    struct FabricParameters
    {
      /** The patch; its section is that of subsection `Yarn`. */
      WovenPatchGeometry patch;
      /** The contact of crossing yarns (subsection `Fabric/Yarn
       * contact`). */
      YarnContactParameters contact;
      /** The clamps' grip (subsection `Fabric/Clamp grip`); a pull-out
       * force of 0 clamps the ends rigidly. */
      ClampGripParameters grip;
      /** The deflection (along -y) above which a point of the yarns'
       * surface is inside the cone, for the history's cone fronts [m]. */
      double cone_threshold = 10e-6;
      /** `Fabric/Mesh file`: the Gmsh mesh to read instead of generating
       * the patch (MeshFile); empty: the patch. */
      std::string mesh_file;
      /** `Fabric/Orientation file`: each cell's fibre direction for the
       * read mesh; empty: estimated from the mesh. */
      std::string orientation_file;
      /** `Fabric/Step timing`: time the parts of the step (StepTimer) and
       * add their table to the run's summary; only clocks are read. */
      bool step_timing = false;
    };

    /**
     * The FE model of subsection `FE` (its law, failure and projectile
     * contact; FE::Parameters) on the woven patch @p fabric.patch
     * (doc/fabric.md): the patch's mesh and fibre directions given to the
     * FE model (FE::GivenMesh, FE::Parameters::fibre_direction), the yarn
     * ends clamped that WovenPatchGeometry::clamp_warp_ends and
     * clamp_weft_ends say, and the YarnContact of crossing yarns as its
     * extra forces (FE::ExtraForces), its surface made from the whole mesh
     * on every rank, and with a grip of finite force (@p fabric.grip)
     * the ClampGrip of the clamped ends as its second extra forces; the
     * energies of the yarns under the projectile's
     * footprint and of the others apart (FE::Parameters::energy_group).
     * The struck face is +y; the projectile strikes at
     * `Projectile/Impact offset x`, `z`. Its name is "fabric".
     * @param shared the run's parameters; the model uses a copy whose
     * `Yarn/Length` is the warp yarns' span, n_weft s [m]
     */
    std::unique_ptr<ImpactModel>
    create_fabric_model(const YarnImpact::Parameters::Shared &shared,
                        const FE::Parameters &fe,
                        const FabricParameters &fabric,
                        const MPI_Comm communicator);

    /**
     * Give the FE parameters @p p the generated patch (FE::GivenMesh):
     * its mesh, fibre directions, section heights and sections, each
     * cell's ply, and the energy groups 2 p (ply p's primary yarns) and
     * 2 p + 1 (its secondary ones).
     * @param primary_ids set to the primary yarns' list, @p ply_heights
     * to the plies' heights, for the set-up report
     * @return the length of all yarns' centrelines [m]
     */
    double
    use_patch(const std::shared_ptr<const WovenPatch> &patch,
              const YarnImpact::Parameters::Projectile &projectile,
              FE::Parameters &p,
              std::string &primary_ids,
              std::string &ply_heights);
  } // namespace Fabric
} // namespace YarnImpact

#endif
