// The yarn contact's stable step (doc/fe-model.md section 8.4, "The
// stable step"): the springs' bound at the reference areas, and the
// same bound from the current ones where a node or a face has grown.

#include <yarn_impact/fabric/yarn_contact.h>

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "yarn_contact_geometry.h"

namespace YarnImpact
{
  namespace Fabric
  {
    double
    YarnContact::reference_time_step() const
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
    YarnContact::local_rate() const
    {
      // The reference bound holds while no node's area has grown. A node
      // of a cell stretched or flattened past its reference shape takes a
      // stiffer spring, (p / 2) (-A_s . n) from its current area vector,
      // and the nodes of a grown face carry the springs of more slaves: a
      // broken cell stretched twenty times its length would otherwise go
      // unstable (doc/fabric.md section 7). Every possible contact, not
      // only the touching ones, so that the step is small enough before
      // a contact starts: each slave with its current area (or its
      // touching spring's, if larger), each candidate face's nodes with
      // the face's growth, the ratio of its current to its reference
      // diagonals' cross product.
      if (!built)
        return restored_rate; // lists not made since load(): as saved
      const double ratio = std::max(1., parameters.tangential_stiffness_ratio);
      double rate        = 0.;
      for (const Slot &slot : slots)
        {
          const unsigned int s = slot.node;
          const double k_s =
            std::max(0.5 * parameters.penalty * area_vector(s).norm(),
                     slot.touching ? slot.stiffness : 0.);
          if (k_s > 0.5 * parameters.penalty * surface.area[s])
            rate = std::max(rate, 4. * ratio * k_s / surface.mass[s]);
          for (unsigned int i = slot.begin; i < slot.end; ++i)
            {
              const auto &c = surface.faces[slot_faces[i]];
              double d1[3], d2[3], n[3], d1_0[3], d2_0[3], n_0[3];
              for (unsigned int d = 0; d < 3; ++d)
                {
                  d1[d] = position[3 * c[2] + d] - position[3 * c[0] + d];
                  d2[d] = position[3 * c[3] + d] - position[3 * c[1] + d];
                  d1_0[d] =
                    surface.reference[c[2]][d] - surface.reference[c[0]][d];
                  d2_0[d] =
                    surface.reference[c[3]][d] - surface.reference[c[1]][d];
                }
              internal::cross(d1, d2, n);
              internal::cross(d1_0, d2_0, n_0);
              const double growth =
                std::sqrt(internal::dot(n, n) / internal::dot(n_0, n_0));
              if (growth > 1.)
                for (const unsigned int a : c)
                  rate = std::max(rate,
                                  2. * ratio * parameters.penalty *
                                    surface.area[a] * growth / surface.mass[a]);
            }
        }
      return rate;
    }


    double
    YarnContact::stable_time_step() const
    {
      double rate = local_rate();
      MPI_Allreduce(MPI_IN_PLACE, &rate, 1, MPI_DOUBLE, MPI_MAX, communicator);
      const double dt   = reference_time_step();
      const double zeta = parameters.damping_ratio;
      if (!(rate > 0.))
        return dt;
      return std::min(dt,
                      2. / std::sqrt(rate) *
                        (std::sqrt(1. + zeta * zeta) - zeta));
    }
  } // namespace Fabric
} // namespace YarnImpact
