#ifndef yarn_impact_fabric_yarn_contact_forces_h
#define yarn_impact_fabric_yarn_contact_forces_h

#include <yarn_impact/fabric/step_timer.h>
#include <yarn_impact/fabric/yarn_contact.h>
#include <yarn_impact/fe/extra_forces.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace YarnImpact
{
  namespace Fabric
  {
    /**
     * The YarnContact of a fabric's yarns as the FE model's extra forces
     * (doc/fabric.md section 1): its surface is that of the whole mesh,
     * made on every rank before the FE model distributes its own copy;
     * each rank's nodes on it are the owned FE nodes found at the same
     * reference position (the two meshes are made by the same code, so
     * that their vertices are equal bit for bit). Also measures the
     * cone's fronts of each ply on the surface.
     */
    class YarnContactForces : public FE::ExtraForces
    {
    public:
      /** @param parameters the contact's constants [SI]
       * @param surface the contact's surface of the whole mesh
       * @param timer the fabric's step timer, which times the contact's
       * parts
       * @param symmetry the whole patch over the meshed part [-]
       * (1, 2, 4), by which energy() and dissipated() scale the
       * contact's to the whole patch's, as the FE model scales its own
       * @param n_plies the plies [-]
       * @param ply_of_yarn the ply [-], below @p n_plies, of each yarn
       * (material id) */
      YarnContactForces(const YarnContactParameters &parameters,
                        ContactSurface &&surface,
                        std::shared_ptr<StepTimer> timer,
                        const double symmetry,
                        const unsigned int n_plies,
                        std::function<unsigned int(unsigned int)> ply_of_yarn);

      std::vector<unsigned int>
      setup(const std::vector<double> &reference,
            const MPI_Comm communicator) override;

      /** The contact leaves out the faces of @p cells
       * (YarnContact::remove_cells()). */
      void
      remove_cells(const std::vector<double> &cells,
                   const bool restored) override;

      void
      add_forces(const std::vector<double> &x,
                 const std::vector<double> &v,
                 const double dt,
                 std::vector<double> &force) override;

      /** The contacts' state and the check of their forces' balance for
       * the run summary: the sum over the steps of the net force,
       * whose every contact's forces cancel to round-off, over the sum
       * of its components' magnitudes [-]. Collective. */
      std::string
      remarks() const;

      /**
       * The cone's (transverse) fronts [m] of each ply at the positions
       * of the last add_forces(), 3 a ply, ply 0 first: the largest
       * reference distance from the impact point (@p x0, @p z0) [m] of
       * a surface node of the ply deflected along -y by more than
       * @p threshold [m], among the nodes within @p band [m] of the line
       * through the impact point along x (the warp yarns' direction),
       * along z (the weft yarns') and along the diagonals x = +-z; 0
       * where none. Collective.
       */
      std::vector<double>
      cone_fronts(const double x0,
                  const double z0,
                  const double threshold,
                  const double band) const;

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
      const YarnContactParameters parameters;
      const ContactSurface surface;
      const std::shared_ptr<StepTimer> timer;
      const double symmetry;
      const unsigned int n_plies;
      const std::function<unsigned int(unsigned int)> ply_of_yarn;
      std::optional<YarnContact> contact;
      MPI_Comm communicator = MPI_COMM_SELF;
      /** The reference positions [m] of this rank's nodes, 3 each, in
       * the order of add_forces(), and their positions [m] at the last
       * add_forces(). */
      std::vector<double> node_reference, positions;
      /** The ply of each of this rank's nodes [-]. */
      std::vector<unsigned int> node_ply;
      /** Sums over the steps of this rank's yarn-contact forces [N] and
       * of their components' magnitudes [N]. */
      double net[3] = {0., 0., 0.}, magnitude = 0.;
    };
  } // namespace Fabric
} // namespace YarnImpact

#endif
