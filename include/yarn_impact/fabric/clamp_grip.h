#ifndef yarn_impact_fabric_clamp_grip_h
#define yarn_impact_fabric_clamp_grip_h

#include <yarn_impact/fe/extra_forces.h>

#include <deal.II/grid/tria.h>

#include <string>
#include <vector>

namespace YarnImpact
{
  namespace Fabric
  {
    /** The grip of the clamps on the yarn ends (doc/fabric.md section 11)
     * [SI]. */
    struct ClampGripParameters
    {
      /** The force [N] at which a yarn end slips in its clamp: the
       * pull-out force of one whole yarn end, shared by its end
       * section's nodes by their areas. */
      double pull_out_force = 0.;
      /** The stiffness [N/m] of the grip of one whole yarn end before it
       * slips; 0: E A / h, the axial stiffness of the end's cell (E the
       * law's axial modulus, A the section's area, h the cell's length
       * along the yarn). */
      double stiffness = 0.;
      /** The meshed part is the half x >= 0 (mirror_x) and the half
       * z >= 0 (mirror_z) of the patch: an end section cut by such a
       * plane is half of its yarn's. */
      bool mirror_x = false, mirror_z = false;
    };


    /**
     * Clamps of finite grip on the end sections of the clamped yarns,
     * as the FE model's extra forces (doc/fabric.md section 11): each node
     * of a clamped end section is held by a spring of stiffness k_n to an
     * anchor, the spring's force f = -k_n (x - a). The clamp's jaws press
     * along y, the fabric's normal: along y the spring holds the node
     * whatever the force; in the fabric's plane (x, z) its force is
     * capped at F_n by Coulomb's law (where it would pass F_n the anchor
     * follows the node, the slip a - X grows and F_n times its increment
     * is dissipated). k_n and F_n are the yarn end's stiffness and
     * pull-out force shared by the nodes' areas on the end section. The
     * clamps hold a yarn end rigidly (its nodes fixed by the FE model)
     * when no grip is set (ClampGripParameters::pull_out_force = 0).
     */
    class ClampGrip : public FE::ExtraForces
    {
    public:
      /**
       * @param parameters the grip's constants
       * @param mesh the whole mesh (every cell, material id the yarn):
       * the grip acts on its boundary faces of id @p boundary_id
       * @param density the yarns' density [kg/m^3], for the nodes'
       * lumped masses (the grip's stable step and its default stiffness)
       * @param symmetry the whole patch over the meshed part [-]
       * (1, 2, 4), by which energy() and dissipated() scale the grip's
       */
      ClampGrip(const ClampGripParameters &parameters,
                const dealii::Triangulation<3, 3> &mesh,
                const unsigned int boundary_id,
                const double density,
                const double symmetry);

      /** Set the law's axial modulus E [Pa], for the default stiffness
       * (ClampGripParameters::stiffness = 0); before setup(). */
      void
      set_axial_modulus(const double modulus);

      std::vector<unsigned int>
      setup(const std::vector<double> &reference,
            const MPI_Comm communicator) override;

      void
      add_forces(const std::vector<double> &x,
                 const std::vector<double> &v,
                 const double dt,
                 std::vector<double> &force) override;

      /** Largest slip [m] of a node in its clamp, |a - X| (in the
       * fabric's plane), over the whole model. Collective. */
      double
      largest_slip() const;

      /** The number of yarn ends [-] of the whole patch that slip: with
       * a node whose slip exceeds a thousandth of its spring's stretch at
       * the cap, F_n / k_n. Collective. */
      unsigned int
      n_slipping_ends() const;

      double
      stable_time_step() const override;

      double
      energy() const override;

      double
      dissipated() const override;

      void
      save(Checkpoint::Writer &out) const override;

      void
      load(Checkpoint::Reader &in) override;

      std::string
      report() const override;

    private:
      const ClampGripParameters parameters;
      const double symmetry;
      /** The gripped nodes of the whole mesh: reference position [m],
       * lumped mass [kg], share of their end section's area [-] (of the
       * whole end, with a cut end's mirrored half), the yarn end [-]. */
      std::vector<dealii::Point<3>> reference;
      std::vector<double> mass, share;
      std::vector<unsigned int> end_of;
      /** The whole patch's yarn ends [-] that each meshed end stands for:
       * 1 for one a symmetry plane cuts, 2 or 4 for its mirror images. */
      std::vector<unsigned int> end_copies;
      /** Each node's axial stiffness of its end cell, E A_n / h [N/m],
       * with E = 1 Pa (scaled by set_axial_modulus()). */
      std::vector<double> unit_stiffness;
      unsigned int n_ends   = 0;
      double axial_modulus  = 0.;
      MPI_Comm communicator = MPI_COMM_SELF;
      /** This rank's nodes (indices into the whole mesh's gripped
       * nodes), in the order of add_forces(): stiffness [N/m], cap [N],
       * anchor [m], 3 each. */
      std::vector<unsigned int> owned;
      std::vector<double> k, cap, anchor;
      /** Each of this rank's nodes' stored energy [J] at the last
       * add_forces() and the energy it dissipated so far [J]. */
      std::vector<double> node_energy, node_dissipated;

      /** The sum over the ranks of this rank's nodes' @p terms [J],
       * scaled to the whole patch; partition-independent. Collective. */
      double
      whole_patch_sum(const std::vector<double> &terms) const;

      /** The slip [m] of this rank's node @p i, |a - X|. */
      double
      anchor_slip(const unsigned int i) const;
    };
  } // namespace Fabric
} // namespace YarnImpact

#endif
