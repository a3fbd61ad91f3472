// The yarn-yarn contact's forces (doc/fe-model.md section 8.4).

#include <yarn_impact/core/reproducible_sum.h>
#include <yarn_impact/fabric/yarn_contact.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "yarn_contact_geometry.h"

namespace YarnImpact
{
  namespace Fabric
  {
    using namespace internal;


    YarnContact::YarnContact(const YarnContactParameters &parameters,
                             const ContactSurface &surface,
                             const std::vector<unsigned int> &owned,
                             const MPI_Comm communicator)
      : parameters(parameters)
      , surface(surface)
      , communicator(communicator)
      , owned(owned)
      , is_owned(surface.n_nodes(), 0)
      , local_index(surface.n_nodes(), 0)
      , position(3 * surface.n_nodes(), 0.)
      , velocity(3 * surface.n_nodes(), 0.)
      , node_faces(surface.n_nodes())
      , node_dissipated(surface.n_nodes(), 0.)
    {
      if (!(parameters.penalty > 0.) || !(parameters.detection_depth > 0.) ||
          !(parameters.skin > 0.) || parameters.friction < 0.)
        throw std::invalid_argument(
          "yarn contact: penalty, detection depth and skin must be positive, "
          "friction not negative");
      for (unsigned int k = 0; k < owned.size(); ++k)
        {
          is_owned[owned[k]]    = 1;
          local_index[owned[k]] = k;
        }
      int n_ranks;
      MPI_Comm_size(communicator, &n_ranks);
      const int n_owned = owned.size();
      counts.resize(n_ranks);
      displacements.assign(n_ranks + 1, 0);
      MPI_Allgather(&n_owned,
                    1,
                    MPI_INT,
                    counts.data(),
                    1,
                    MPI_INT,
                    communicator);
      for (int r = 0; r < n_ranks; ++r)
        displacements[r + 1] = displacements[r] + counts[r];
      if (displacements.back() != int(surface.n_nodes()))
        throw std::invalid_argument(
          "yarn contact: every surface node must be owned by one rank");
      gather_order.resize(surface.n_nodes());
      MPI_Allgatherv(owned.data(),
                     n_owned,
                     MPI_UNSIGNED,
                     gather_order.data(),
                     counts.data(),
                     displacements.data(),
                     MPI_UNSIGNED,
                     communicator);
      for (unsigned int f = 0; f < surface.faces.size(); ++f)
        for (const unsigned int node : surface.faces[f])
          node_faces[node].push_back(f);
      face_removed.assign(surface.faces.size(), 0);
      for (unsigned int i = 0; i < surface.n_nodes(); ++i)
        node_live_faces.push_back(node_faces[i].size());
      remote_terms.resize(n_ranks);
      node_owner.resize(surface.n_nodes());
      for (int r = 0; r < n_ranks; ++r)
        for (int k = displacements[r]; k < displacements[r + 1]; ++k)
          node_owner[gather_order[k]] = r;
    }


    dealii::Tensor<1, 3>
    YarnContact::area_vector(const unsigned int node) const
    {
      // The integral of its shape function times the surface element
      // over each of its faces, in the faces' global order: N_s and
      // X_xi x X_eta are bilinear, so 2 x 2 Gauss points are exact.
      const double g[2] = {0.5 - 0.5 / std::sqrt(3.),
                           0.5 + 0.5 / std::sqrt(3.)};
      dealii::Tensor<1, 3> A;
      for (const unsigned int f : node_faces[node])
        {
          // A failed cell's face is no longer the node's surface.
          if (face_removed[f])
            continue;
          const auto &c    = surface.faces[f];
          const unsigned k = std::find(c.begin(), c.end(), node) - c.begin();
          const double *corners[4];
          for (unsigned int a = 0; a < 4; ++a)
            corners[a] = &position[3 * c[a]];
          for (const double xi : g)
            for (const double eta : g)
              {
                const double N[4] = {(1 - xi) * (1 - eta),
                                     xi * (1 - eta),
                                     xi * eta,
                                     (1 - xi) * eta};
                double Xxi[3], Xeta[3], n[3];
                tangents(corners, xi, eta, Xxi, Xeta);
                cross(Xxi, Xeta, n);
                for (unsigned int d = 0; d < 3; ++d)
                  A[d] += 0.25 * N[k] * n[d];
              }
        }
      // On a symmetry plane the faces of the mirror image are not
      // meshed: without its normal component the node's area vector is
      // the whole node's share, so that its stiffness, -A . n, is too.
      for (const unsigned int axis : {0u, 2u})
        if (on_symmetry_plane(node, axis))
          A[axis] = 0.;
      return A;
    }


    bool
    YarnContact::on_symmetry_plane(const unsigned int node,
                                   const unsigned int axis) const
    {
      // The node's own rounding puts it within 1e-18 m of the plane.
      const bool plane = axis == 0 ? parameters.mirror_x : parameters.mirror_z;
      return plane && std::abs(surface.reference[node][axis]) <
                        1e-6 * parameters.detection_depth;
    }


    template <class Law>
    void
    YarnContact::slot_force(Slot &slot, const double dt)
    {
      const unsigned int s = slot.node;
      const double *p      = &position[3 * s];
      // A node whose faces have all failed has no surface to press with.
      if (node_live_faces[s] == 0)
        {
          end_contact(slot);
          return;
        }
      // The slot's force terms, numbered in the order they are made.
      unsigned int n_terms = 0;
      // The node's area vector, evaluated when a face's projection first
      // needs it (most slots have none near enough): the same numbers.
      double ns[3]   = {0., 0., 0.};
      bool have_area = false;

      // The faces whose normal opposes the node's and that it penetrates
      // by at most d_max, in face order (the deepest dropped beyond
      // max_touched).
      struct Touched
      {
        Projection projection;
        double depth;
        unsigned int face;
        /** On the face's boundary (an edge or a vertex in a wedge), not
         * inside it. */
        bool boundary;
      };
      Touched touched[max_touched];
      unsigned int n_touched = 0;
      // A touching contact holds its node to twice the detection depth
      // (the lists are built to that depth plus the skin): a face pressed
      // harder than its spring can stop in d_max goes on pushing, rather
      // than letting go of k d_max^2 / 2 at once.
      const double reach =
        (slot.touching ? 2. : 1.) * parameters.detection_depth;
      double extent = 0.;
      // The boundary features (edges, vertices) already touched, once each.
      unsigned int features[max_touched][2], n_features = 0;
      const auto normal_opposes = [&](const double *n) {
        if (!have_area)
          {
            const dealii::Tensor<1, 3> A_s = area_vector(s);
            for (unsigned int d = 0; d < 3; ++d)
              ns[d] = A_s[d];
            have_area = true;
          }
        return dot(n, ns) < 0.;
      };
      // Keep @p trial at @p depth on @p f among the touched faces (the
      // deepest dropped beyond max_touched).
      const auto keep = [&](const Projection &trial,
                            const double depth,
                            const unsigned int f,
                            const double face_extent,
                            const bool boundary) {
        extent         = std::max(extent, face_extent);
        unsigned int k = n_touched;
        if (n_touched == max_touched)
          {
            k = 0;
            for (unsigned int j = 1; j < max_touched; ++j)
              if (touched[j].depth > touched[k].depth)
                k = j;
            if (!(depth < touched[k].depth))
              return;
          }
        else
          ++n_touched;
        touched[k] = {trial, depth, f, boundary};
      };
      for (unsigned int i = slot.begin; i < slot.end; ++i)
        {
          const unsigned int f = slot_faces[i];
          if (face_removed[f])
            continue;
          const double *c[4];
          for (unsigned int a = 0; a < 4; ++a)
            c[a] = &position[3 * surface.faces[f][a]];
          double face_extent;
          Projection trial;
          if (!may_touch(c, p, reach, face_extent))
            continue;
          const Side side = project(c, p, trial);
          if (side == Side::beyond)
            {
              // Beyond the face: its edge or vertex, in a wedge.
              Projection edge;
              double depth;
              unsigned int key[2];
              if (n_features == max_touched ||
                  !boundary_contact(f,
                                    trial.xi,
                                    trial.eta,
                                    p,
                                    reach,
                                    edge.N,
                                    edge.n,
                                    depth,
                                    key) ||
                  !normal_opposes(edge.n))
                continue;
              bool seen = false;
              for (unsigned int k = 0; k < n_features; ++k)
                seen = seen ||
                       (features[k][0] == key[0] && features[k][1] == key[1]);
              if (seen)
                continue;
              features[n_features][0] = key[0];
              features[n_features][1] = key[1];
              ++n_features;
              edge.gap = -depth;
              keep(edge, depth, f, face_extent, true);
              continue;
            }
          if (side != Side::inside || !normal_opposes(trial.n))
            continue;
          const double depth = -trial.gap;
          if (!(depth > 0. && depth <= reach))
            continue;
          keep(trial, depth, f, face_extent, false);
        }
      if (n_touched == 0)
        {
          end_contact(slot);
          return;
        }
      slot.energy = 0.;
      // The closest face, the first in face order on an exact tie.
      unsigned int closest = 0;
      for (unsigned int j = 1; j < n_touched; ++j)
        if (touched[j].depth < touched[closest].depth ||
            (touched[j].depth == touched[closest].depth &&
             touched[j].face < touched[closest].face))
          closest = j;
      // A tie: faces within 1e-10 of the faces' size of the closest
      // depth. The node then lies over their common edge or vertex to
      // within the projection's own tolerance (1e-9 of a face outside
      // it), so that the choice among them is round-off's, as at a node
      // on a mirror plane over a face and its image, whose depths differ
      // by about 1e-18 m (1e-15 m at most, the mirrored vertices' rounding)
      // against the tolerance's 1e-14 m on the patch's 0.1 mm faces.
      const double tie = touched[closest].depth + 1e-10 * extent;
      // Ascending by face (an insertion), the smallest faces kept beyond
      // max_tied.
      unsigned int tied[max_touched], n_tied = 0;
      for (unsigned int j = 0; j < n_touched; ++j)
        if (touched[j].depth <= tie)
          {
            unsigned int k = n_tied++;
            for (; k > 0 && touched[tied[k - 1]].face > touched[j].face; --k)
              tied[k] = tied[k - 1];
            tied[k] = j;
          }
      n_tied = std::min(n_tied, max_tied);
      // The law of the node's spring, damping and mass times @p share.
      // A boundary's contact is normal only (no friction, no tangential
      // spring): a node crosses a wedge in a few steps, and the faces'
      // tangential histories carry on past it.
      const auto constants = [&](const double share, const bool boundary) {
        Contact::ContactConstants c;
        c.stiffness = share * slot.stiffness;
        c.damping   = parameters.damping_ratio > 0.
                        ? Contact::critical_damping(parameters.damping_ratio,
                                                  share * surface.mass[s],
                                                  c.stiffness)
                        : 0.;
        c.tangential_stiffness =
          boundary ? 0. : parameters.tangential_stiffness_ratio * c.stiffness;
        c.friction = boundary ? 0. : parameters.friction;
        c.mass     = share * surface.mass[s];
        return c;
      };
      // The node's velocity relative to @p face's point @p projection
      // [m/s].
      const auto relative_velocity = [&](const unsigned int face,
                                         const Projection &projection,
                                         double v_rel[3]) {
        const auto &corners = surface.faces[face];
        for (unsigned int d = 0; d < 3; ++d)
          {
            v_rel[d] = velocity[3 * s + d];
            for (unsigned int a = 0; a < 4; ++a)
              v_rel[d] -= projection.N[a] * velocity[3 * corners[a] + d];
          }
      };
      // A starting contact's spring is unstretched at the depth the node
      // had before this step [m], depth + dt v_rel . n along the normal
      // (the velocities are the step's, x_n - x_{n-1} = dt v), between 0
      // and its depth now: a node that crossed the surface in this step
      // presses by all its depth, as a penalty contact does, and a node
      // already that deep (at rest in a given mesh, or back from beyond
      // d_max or from outside every face's wedge) is not pushed out by a
      // spring that would store k depth^2 / 2 at once.
      const auto unstretched = [&](const Touched &t) {
        double v_rel[3];
        relative_velocity(t.face, t.projection, v_rel);
        const double before = t.depth + dt * dot(v_rel, t.projection.n);
        return std::min(std::max(before, 0.), t.depth);
      };
      // The force of @p law on the node at the depth @p depth [m] below
      // @p face's point @p projection, with the tangential @p history [m],
      // and the opposite force on the face's nodes by their shape
      // functions; the damping and slip work [J] added to @p work.
      const auto press = [&](const Law &law,
                             const unsigned int face,
                             const Projection &projection,
                             const double depth,
                             double *history,
                             double &work) {
        const auto &corners = surface.faces[face];
        double v_rel[3];
        relative_velocity(face, projection, v_rel);
        double f[3];
        Contact::contact_force(law,
                               depth,
                               projection.n,
                               v_rel,
                               dt,
                               history,
                               f,
                               work);
        add_term(s, slot, n_terms++, f);
        for (unsigned int a = 0; a < 4; ++a)
          {
            const double g[3] = {-(projection.N[a] * f[0]),
                                 -(projection.N[a] * f[1]),
                                 -(projection.N[a] * f[2])};
            add_term(corners[a], slot, n_terms++, g);
          }
      };
      if (n_tied > 1)
        {
          // Each tied face takes 1/t of the node's spring, damping and
          // mass, with its own depth, normal, projection and history: the
          // sum over the faces does not depend on their order, and a
          // node on a mirror plane over t faces and images gets t times
          // the force that a model of 1/t of the patch, which meshes one
          // of them, gives its share (doc/fabric.md section 10).
          const double share = 1. / n_tied;
          if (!slot.touching)
            {
              std::fill(slot.history, slot.history + 3, 0.);
              slot.n_tied  = 0;
              double start = 0.;
              for (unsigned int k = 0; k < n_tied; ++k)
                start += dot(ns, touched[tied[k]].projection.n);
              slot.stiffness = -0.5 * parameters.penalty * share * start;
              slot.offset    = unstretched(touched[closest]);
            }
          slot.touching = true;
          // As the node comes up the spring's rest depth follows it: the
          // spring holds nothing then, so no energy comes or goes.
          slot.offset = std::min(slot.offset, touched[closest].depth);
          double history[max_tied][3], mean[3] = {0., 0., 0.}, work = 0.;
          unsigned int n_faces = 0;
          for (unsigned int k = 0; k < n_tied; ++k)
            {
              const Touched &t = touched[tied[k]];
              // Its own history if it was tied before, else the node's;
              // none for a boundary.
              const double none[3] = {0., 0., 0.};
              const double *old    = t.boundary ? none : slot.history;
              for (unsigned int j = 0; j < slot.n_tied && !t.boundary; ++j)
                if (slot.tied_face[j] == t.face)
                  old = slot.tied_history[j];
              std::copy(old, old + 3, history[k]);
              const Law law(constants(share, t.boundary));
              const double depth = t.depth - slot.offset;
              press(law, t.face, t.projection, depth, history[k], work);
              slot.energy += law.energy(depth, history[k]);
              n_faces += !t.boundary;
            }
          node_dissipated[s] += work;
          // The faces' histories (boundaries keep none; with only
          // boundaries tied the last ones stay).
          if (n_faces > 0)
            {
              unsigned int j = 0;
              for (unsigned int k = 0; k < n_tied; ++k)
                if (!touched[tied[k]].boundary)
                  {
                    slot.tied_face[j] = touched[tied[k]].face;
                    std::copy(history[k], history[k] + 3, slot.tied_history[j]);
                    for (unsigned int d = 0; d < 3; ++d)
                      mean[d] += history[k][d] / n_faces;
                    ++j;
                  }
              slot.n_tied = n_faces;
              std::copy(mean, mean + 3, slot.history);
            }
          return;
        }
      const Projection &best       = touched[closest].projection;
      const double best_depth      = touched[closest].depth;
      const unsigned int best_face = touched[closest].face;
      const bool boundary          = touched[closest].boundary;
      // After a tie, the face that stays keeps its own history; a
      // boundary leaves the histories as they are.
      if (!boundary)
        {
          for (unsigned int k = 0; k < slot.n_tied; ++k)
            if (slot.tied_face[k] == best_face)
              std::copy(slot.tied_history[k],
                        slot.tied_history[k] + 3,
                        slot.history);
          slot.n_tied = 0;
        }

      // The node's area facing the face, -A_s . n, when the contact
      // starts: a node on a yarn's edge carries the share of its faces
      // that press, not of those beside. Kept while the contact lasts, so
      // that the normal force derives from the energy k delta^2 / 2 (the
      // closest point's gap has the gradient n, -N_a n). Half the
      // penalty: both sides of a contact are slaves, so two surfaces
      // pressed by d carry p d per area.
      if (!slot.touching)
        {
          std::fill(slot.history, slot.history + 3, 0.);
          slot.stiffness = -0.5 * parameters.penalty * dot(ns, best.n);
          slot.offset    = unstretched(touched[closest]);
        }
      slot.touching      = true;
      slot.offset        = std::min(slot.offset, best_depth);
      const double depth = best_depth - slot.offset;
      const Law law(constants(1., boundary));
      double work = 0., none[3] = {0., 0., 0.};
      double *history = boundary ? none : slot.history;
      press(law, best_face, best, depth, history, work);
      node_dissipated[s] += work;
      slot.energy = law.energy(depth, history);
    }


    void
    YarnContact::add_forces(const std::vector<double> &x,
                            const std::vector<double> &v,
                            const double dt,
                            std::vector<double> &force)
    {
      if (x.size() != 3 * owned.size() || v.size() != x.size() ||
          force.size() != x.size())
        throw std::invalid_argument("yarn contact: 3 values per owned node");
      // Between rebuilds only the nodes this rank's contacts need come
      // from their owners; a rebuild gathers every node.
      bool rebuild_due;
      {
        StepTimer::Scope scope(timer, StepTimer::contact_list_checks);
        rebuild_due = lists_may_miss(x);
      }
      if (rebuild_due)
        {
          StepTimer::Scope scope(timer, StepTimer::contact_list_builds);
          gather(x, v);
          rebuild();
          set_up_exchange();
        }
      else
        {
          StepTimer::Scope scope(timer, StepTimer::contact_exchange);
          exchange(x, v);
        }
      find_eroding();
      // Each rank evaluates its own nodes' slots; add_terms() adds every
      // node's force terms in one global order, the same on any
      // partition.
      StepTimer::Scope scope(timer, StepTimer::contact_forces);
      local_terms.clear();
      for (auto &terms : remote_terms)
        terms.clear();
      Contact::with_contact_law(parameters.law, [&](auto tag) {
        using Law = typename decltype(tag)::type;
        for (Slot &slot : slots)
          slot_force<Law>(slot, dt);
        return 0;
      });
      eroding.clear();
      add_terms(force);
    }


    void
    YarnContact::add_term(const unsigned int node,
                          const Slot &slot,
                          const unsigned int term,
                          const double f[3])
    {
      std::vector<double> &to =
        is_owned[node] ? local_terms : remote_terms[node_owner[node]];
      to.insert(to.end(),
                {double(node),
                 double(slot.node),
                 double(slot.yarn),
                 double(term),
                 f[0],
                 f[1],
                 f[2]});
    }


    double
    YarnContact::stable_time_step() const
    {
      // A node's Gershgorin row sum is 2 k_s (slave) plus 2 k_s (face
      // node of the other side's slave on it), k_s = p A / 2.
      const double ratio = std::max(1., parameters.tangential_stiffness_ratio);
      const double zeta  = parameters.damping_ratio;
      double dt          = std::numeric_limits<double>::max();
      for (unsigned int i = 0; i < surface.n_nodes(); ++i)
        dt = std::min(dt,
                      2. * std::sqrt(surface.mass[i] /
                                     (2. * ratio * parameters.penalty *
                                      surface.area[i])));
      return dt * (std::sqrt(1. + zeta * zeta) - zeta);
    }


    double
    YarnContact::energy() const
    {
      ReproducibleSum sum(1);
      for (const Slot &slot : slots)
        sum.add(0, slot.energy);
      return sum.sum(communicator)[0];
    }


    double
    YarnContact::dissipated() const
    {
      ReproducibleSum sum(1);
      for (const unsigned int node : owned)
        sum.add(0, node_dissipated[node]);
      return sum.sum(communicator)[0];
    }


    unsigned int
    YarnContact::n_touching() const
    {
      unsigned int n = 0;
      for (const Slot &slot : slots)
        n += slot.touching;
      unsigned int total = 0;
      MPI_Allreduce(&n, &total, 1, MPI_UNSIGNED, MPI_SUM, communicator);
      return total;
    }
  } // namespace Fabric
} // namespace YarnImpact
