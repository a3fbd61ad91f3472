#ifndef yarn_impact_fabric_yarn_contact_h
#define yarn_impact_fabric_yarn_contact_h

#include <yarn_impact/contact/contact_law.h>
#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/fabric/step_timer.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpi.h>

#include <array>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

namespace dealii
{
  template <int dim, int spacedim>
  class Triangulation;
}

namespace YarnImpact
{
  namespace Fabric
  {
    /**
     * The lateral surface of a mesh of several yarns (doc/fe-model.md
     * section 8.4), the same on every MPI rank: its nodes (the mesh's
     * vertices on it) and its bilinear faces, each with its yarn. Node
     * indices are positions in these arrays, the global numbering of the
     * contact.
     */
    struct ContactSurface
    {
      /** Reference position of each node [m]. */
      std::vector<dealii::Point<3>> reference;
      /** Yarn (material id) of each node [-]. */
      std::vector<unsigned int> node_yarn;
      /** Each node's share of the surface, the integral of its shape
       * function over its faces [m^2]. */
      std::vector<double> area;
      /** Each node's lumped mass, the row sum of the Q1 mass matrix [kg]. */
      std::vector<double> mass;
      /** Each face's nodes, in cyclic order c0 c1 c2 c3 such that
       * (c2 - c0) x (c3 - c1) points out of its yarn. */
      std::vector<std::array<unsigned int, 4>> faces;
      /** Yarn of each face [-]. */
      std::vector<unsigned int> face_yarn;

      /** Number of nodes [-]. */
      unsigned int
      n_nodes() const
      {
        return reference.size();
      }
    };


    /**
     * The surface of @p mesh (Q1 hexahedra, every cell present, the
     * material id its yarn) made of its boundary faces whose boundary id
     * is in @p boundary_ids (all boundary faces if empty), with the lumped
     * masses of density @p density [kg/m^3]. Nodes are numbered in the
     * order of the mesh's vertex indices.
     */
    ContactSurface
    make_contact_surface(const dealii::Triangulation<3, 3> &mesh,
                         const double density,
                         const std::set<unsigned int> &boundary_ids = {});


    /**
     * The nodes of a surface of the whole mesh (@p surface, reference
     * positions [m]) that are among an FE model's nodes on this rank
     * (@p fe_reference, their reference positions [m], 3 each), found by
     * position: the two meshes are made by the same code, so that their
     * vertices are equal bit for bit.
     * @return (surface node, index into @p fe_reference's nodes) pairs in
     * the surface's order
     */
    std::vector<std::pair<unsigned int, unsigned int>>
    match_surface_nodes(const std::vector<dealii::Point<3>> &surface,
                        const std::vector<double> &fe_reference);


    /** The yarn-yarn contact's constants [SI]. */
    struct YarnContactParameters
    {
      /** The contact law (its tangential part: Cundall-Strack is the
       * stick spring with Coulomb's cap). */
      Contact::LawType law = Contact::LawType::cundall_strack;
      /** Penalty p: contact pressure per penetration [Pa/m]. */
      double penalty = 5e13;
      /** Coulomb friction coefficient mu [-]. */
      double friction = 0.2;
      /** Tangential stiffness over normal stiffness [-]. */
      double tangential_stiffness_ratio = 1.;
      /** Normal damping, fraction of the critical damping of a node's
       * mass on its spring [-]. */
      double damping_ratio = 0.;
      /** Deepest penetration detected, d_max [m]: a node deeper below a
       * face does not start a contact with it; a touching contact holds
       * its node to 2 d_max. */
      double detection_depth = 20e-6;
      /** Skin s of the candidate search [m]: the lists are rebuilt when a
       * node has moved s/2 since the last build. */
      double skin = 20e-6;
      /** The symmetry planes x = 0 and z = 0 that bound the modelled part
       * (WovenPatchGeometry::mirror_x, mirror_z): a node on one takes the
       * part of its area vector in the plane, the whole node's area
       * vector (the sum of its mirror images, whose normal components
       * cancel) over the images. Not `.prm` entries. */
      bool mirror_x = false, mirror_z = false;
    };


    /**
     * Penalty contact with friction between the lateral surfaces of
     * different yarns (doc/fe-model.md section 8.4). Every surface node is
     * a slave against the faces of every other yarn (both sides of a
     * contact are slaves): its penetration below the closest face whose
     * normal opposes its own, found by closest-point projection onto the
     * bilinear face, gives the force of a Contact law (contact_law.h) of
     * normal stiffness p A_s / 2 (A_s the node's area facing the face,
     * fixed when the contact starts) on the node and the opposite force on
     * the face's nodes by their shape functions at the projection, so
     * that momentum is conserved to round-off. The spring is unstretched
     * at the depth the node had before the step in which the contact
     * started (0 for a node that crossed the surface in it), a rest depth
     * that follows the node up: no contact starts with stored energy. A
     * touching contact holds its node to twice the detection depth. A node over
     * an edge or a vertex whose faces it penetrates equally, to within 1e-10 of
     * the faces' size (a tie), is shared equally among them: each gets 1/t of
     * its stiffness, damping and mass with its own depth, normal and
     * tangential history, whatever the faces' order (doc/fabric.md
     * section 10). Tangential history per contact (node, other yarn), and
     * per tied face. Candidates from bins, rebuilt by a displacement
     * criterion that misses no contact.
     *
     * MPI: the surface and its topology are known to every rank; each
     * rank owns some nodes and gives their positions and velocities; at
     * a rebuild every rank gathers all of them (6 doubles a surface node,
     * once per skin/2 of motion), between rebuilds only those its
     * contacts need, from their owners; each rank evaluates the contacts
     * of the nodes it owns, once each, and sends the forces on the faces'
     * nodes it does not own to their owners, which add every node's terms
     * in one global order (the contact's node, its other yarn, the term's
     * place in it), so that any number of ranks gives the same forces bit
     * for bit.
     */
    class YarnContact
    {
    public:
      /**
       * @param parameters penalty [Pa/m], friction [-], law, search [m]
       * @param surface the surface, the same on every rank
       * @param owned the nodes this rank owns; every node owned by exactly
       * one rank of @p communicator (throws std::invalid_argument if the
       * counts do not add up)
       * @param communicator the ranks that share the surface
       */
      YarnContact(const YarnContactParameters &parameters,
                  const ContactSurface &surface,
                  const std::vector<unsigned int> &owned,
                  const MPI_Comm communicator);

      /**
       * Add the contact forces [N] on the owned nodes to @p force (3 per
       * owned node, in the order of `owned`) at the owned nodes'
       * positions @p x [m] and velocities @p v [m/s] (3 per owned node),
       * over the step @p dt [s]. Collective.
       */
      void
      add_forces(const std::vector<double> &x,
                 const std::vector<double> &v,
                 const double dt,
                 std::vector<double> &force);

      /**
       * The largest stable step [s] of a node on its contact springs,
       * the smallest over the nodes of 2 sqrt(m / k), m the node's lumped
       * mass, k = 2 max(1, k_t/k_n) p A its Gershgorin row sum when it is
       * both a slave (stiffness p A / 2) and the face node of the other
       * side's slave on it (conforming surfaces), reduced for the damping
       * as the projectile contact's; the same on every rank. The model's
       * step adds its squared frequency: 1/dt^2 = 1/dt_e^2 + 1/dt_c^2.
       */
      double
      stable_time_step() const;

      /** Energy stored in the contacts [J] at the last add_forces(), summed
       * over the ranks independently of the partition. Collective. */
      double
      energy() const;

      /** Damping and slip work of the contacts so far [J], summed over the
       * ranks independently of the partition. Collective. */
      double
      dissipated() const;

      /**
       * Leave out of the contact the faces of @p cells, cells that carry
       * no stress any more (broken or eroded), each given by the
       * reference positions [m] of its 8 vertices (24 values a cell; this
       * rank's, every rank gives its own): the eroding contact. A face
       * of such a cell presses nothing and is pressed by nothing, a node
       * whose faces all belong to such cells is no slave, and a node's
       * area vector counts its remaining faces only. A touching contact
       * that ends in the next add_forces() because its node or the faces
       * it could press were removed here hands the energy its spring held
       * to dissipated(), as a failed cell hands its strain energy to the
       * FE model's; with @p restored (the cells failed before a restart)
       * nothing is handed. Collective.
       */
      void
      remove_cells(const std::vector<double> &cells, const bool restored);

      /** Faces left out by remove_cells() so far [-]. */
      unsigned int
      n_removed_faces() const
      {
        return n_removed;
      }

      /** Candidate lists built so far [-]. */
      unsigned int
      n_rebuilds() const
      {
        return rebuilds;
      }

      /** Contacts (node, other yarn) touching at the last add_forces(),
       * over all ranks [-]. Collective. */
      unsigned int
      n_touching() const;

      /** Time the parts of add_forces() in @p step_timer (null: none);
       * it only reads clocks. */
      void
      set_timer(StepTimer *step_timer)
      {
        timer = step_timer;
      }

      /** Write the contact's state to a checkpoint: the touching
       * contacts whose node this rank owns (node, other yarn, tangential
       * history [m], normal stiffness [N/m], the spring's rest depth [m],
       * the energy it held [J], tied faces and their histories [m]) and each
       * owned node's dissipated work [J]. The candidate lists are not written:
       * they are built again after load(), and longer or shorter lists give the
       * same forces. */
      void
      save(Checkpoint::Writer &out) const;

      /** Read what save() wrote on this rank, with the same owned nodes;
       * the next add_forces() builds the lists and hands the histories to
       * every rank that evaluates their contacts. */
      void
      load(Checkpoint::Reader &in);

    private:
      /** A possible contact: a node against the candidate faces of one
       * other yarn, with its tangential history. */
      struct Slot
      {
        unsigned int node = 0, yarn = 0;
        /** Range of its candidate faces in `slot_faces`. */
        unsigned int begin = 0, end = 0;
        bool touching     = false;
        double history[3] = {0., 0., 0.};
        /** Normal stiffness, fixed when the contact starts [N/m]. */
        double stiffness = 0.;
        /** Depth at which the normal spring is unstretched [m]: the depth
         * the node had before the step in which the contact started (0
         * when it crossed the surface then), following the node up. */
        double offset = 0.;
        /** Energy stored at the last evaluation [J]. */
        double energy = 0.;
        /** The tied faces of the last evaluation (none: one face or no
         * contact), ascending, and each one's tangential history [m]. */
        unsigned int n_tied       = 0;
        unsigned int tied_face[4] = {0, 0, 0, 0};
        double tied_history[4][3] = {};
      };

      /** Whether surface node @p node lies on the symmetry plane normal
       * to @p axis (0: x = 0, 2: z = 0) that bounds the modelled part. */
      bool
      on_symmetry_plane(const unsigned int node, const unsigned int axis) const;

      /**
       * A node @p p [m] whose closest point on the bilinear extension of
       * @p face lies at its coordinates (@p xi, @p eta), beyond the face:
       * whether it touches the face's boundary there, an edge or a vertex
       * in the wedge of the faces that hold it (behind all of them and
       * their images on a symmetry plane), within the detection depth.
       * Then the weights of the face's corners at that point @p N [-], the
       * normal @p n [-] out of the face's yarn, from the node to the
       * feature, the distance @p depth [m], and the feature's nodes @p key
       * (ascending, a vertex twice).
       */
      bool
      boundary_contact(const unsigned int face,
                       double xi,
                       double eta,
                       const double *p,
                       const double reach,
                       double N[4],
                       double n[3],
                       double &depth,
                       unsigned int key[2]) const;

      /** The most faces a tie shares the node among: the faces about a
       * vertex of a quadrilateral surface. */
      static constexpr unsigned int max_tied = 4;

      /** The most faces a node's evaluation keeps among those it
       * penetrates (the deepest dropped beyond it). */
      static constexpr unsigned int max_touched = 8;

      /** Append the touching contacts of the owned slave nodes to @p out,
       * 9 + 4 t doubles each (node, yarn, tangential history, stiffness,
       * the spring's rest depth, the energy it held at its last
       * evaluation, t tied faces, each face and its history): the record
       * a checkpoint
       * and a rebuild's history hand-over share. */
      void
      append_touching(std::vector<double> &out) const;

      /** Gather every node's position and velocity from the owned ones
       * of all ranks into `position` and `velocity`. Collective. */
      void
      gather(const std::vector<double> &x, const std::vector<double> &v);

      /** Whether a node has moved more than skin/2 since the last
       * rebuild (or there was none), from the owned nodes' positions @p x
       * [m] on every rank: then the lists may miss a contact. The same
       * answer on every rank. Collective. */
      bool
      lists_may_miss(const std::vector<double> &x) const;

      /** After a rebuild: which owned nodes each rank needs (the nodes of
       * its slots' candidate faces and of their nodes' own faces), and
       * which it receives. Collective. */
      void
      set_up_exchange();

      /** Between rebuilds: the owned nodes' positions @p x [m] and
       * velocities @p v [m/s] into `position` and `velocity`, and the
       * needed nodes' from their owners. Collective. */
      void
      exchange(const std::vector<double> &x, const std::vector<double> &v);

      /** Build the slots from bins of the faces' grown boxes, carrying
       * the touching contacts' histories over. Collective. */
      void
      rebuild();

      /** Area vector of @p node [m^2]: the integral of its shape
       * function times the outward surface element over its faces, in
       * the current configuration. */
      dealii::Tensor<1, 3>
      area_vector(const unsigned int node) const;

      /** End @p slot's contact: no longer touching, no energy; the energy
       * its spring held goes to its node's dissipated work if
       * remove_cells() listed it among the eroding contacts. */
      void
      end_contact(Slot &slot);

      /** Evaluate one slot (its node owned) by @p Law over the step @p dt
       * [s], its force terms kept by add_term(). */
      template <class Law>
      void
      slot_force(Slot &slot, const double dt);

      /** Doubles a force term takes: the node it acts on, the slot's node
       * and yarn, the term's number within the slot, the force [N]. */
      static constexpr unsigned int term_size = 7;

      /** Keep the force @p f [N] on @p node, the term number @p term of
       * @p slot: in `local_terms` if this rank owns the node, else in
       * the node's owner's `remote_terms`. */
      void
      add_term(const unsigned int node,
               const Slot &slot,
               const unsigned int term,
               const double f[3]);

      /** Send the terms on other ranks' nodes to their owners and add
       * every term on an owned node to @p force [N] (3 per owned node), in
       * the global order of their slots and of the terms within a slot.
       * Collective. */
      void
      add_terms(std::vector<double> &force);

      YarnContactParameters parameters;
      ContactSurface surface;
      MPI_Comm communicator;
      /** This rank's nodes and, per node, whether it owns it. */
      std::vector<unsigned int> owned;
      std::vector<std::uint8_t> is_owned;
      /** Position in `owned` of each owned node. */
      std::vector<unsigned int> local_index;
      /** Every rank's owned count and nodes, in gather order. */
      std::vector<int> counts, displacements;
      std::vector<unsigned int> gather_order;
      /** The rank that owns each node. */
      std::vector<unsigned int> node_owner;
      /** The force terms of the last add_forces() on owned nodes, and on
       * each rank's nodes, term_size doubles each. */
      std::vector<double> local_terms;
      std::vector<std::vector<double>> remote_terms;
      /** Owned nodes sent to and nodes received from each rank, with
       * the counts and offsets of their MPI_Alltoallv [-]. */
      std::vector<unsigned int> send_nodes, receive_nodes;
      std::vector<int> send_counts, send_offsets, receive_counts,
        receive_offsets;
      /** Every node's current position [m] and velocity [m/s], 3 each
       * (those a rank neither owns nor needs are stale between
       * rebuilds). */
      std::vector<double> position, velocity;
      /** Positions at the last rebuild [m]. */
      std::vector<double> built_position;
      /** Faces of each node, ascending. */
      std::vector<std::vector<unsigned int>> node_faces;
      std::vector<Slot> slots;
      std::vector<unsigned int> slot_faces;
      /** Whether each face has been left out (remove_cells()). */
      std::vector<std::uint8_t> face_removed;
      /** Faces of each node not left out [-]. */
      std::vector<unsigned int> node_live_faces;
      unsigned int n_removed = 0;
      /** The faces removed by remove_cells() since the last add_forces()
       * (not those of a restart) [-]. */
      std::vector<unsigned int> removed_now;
      /** The touching contacts (node, other yarn) of owned nodes whose
       * node's faces or candidate faces were removed since the last
       * add_forces(), and the energy their springs held [J], ascending:
       * handed to dissipated() if the contact ends in this add_forces(). */
      std::vector<std::pair<std::pair<unsigned int, unsigned int>, double>>
        eroding;

      /** Fill `eroding` from the slots and `removed_now`, after the
       * lists are built. */
      void
      find_eroding();
      /** Damping and slip work of each owned node as a slave [J]. */
      std::vector<double> node_dissipated;
      /** Touching contacts read by load(), as append_touching() writes
       * them, for the next rebuild. */
      std::vector<double> loaded;
      unsigned int rebuilds = 0;
      bool built            = false;
      /** The fabric's step timer, or null. */
      StepTimer *timer = nullptr;
    };
  } // namespace Fabric
} // namespace YarnImpact

#endif
