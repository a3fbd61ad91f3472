// What the ranks of the yarn-yarn contact send each other
// (doc/fe-model.md section 8.4): every surface node at a rebuild, the
// nodes each rank's contacts need between rebuilds.

#include <yarn_impact/fabric/yarn_contact.h>

#include <algorithm>

namespace YarnImpact
{
  namespace Fabric
  {
    void
    YarnContact::gather(const std::vector<double> &x,
                        const std::vector<double> &v)
    {
      std::vector<double> mine(6 * owned.size()), all(6 * surface.n_nodes());
      for (unsigned int k = 0; k < owned.size(); ++k)
        for (unsigned int d = 0; d < 3; ++d)
          {
            mine[6 * k + d]     = x[3 * k + d];
            mine[6 * k + 3 + d] = v[3 * k + d];
          }
      std::vector<int> n6(counts.size()), offset6(counts.size());
      for (unsigned int r = 0; r < counts.size(); ++r)
        {
          n6[r]      = 6 * counts[r];
          offset6[r] = 6 * displacements[r];
        }
      MPI_Allgatherv(mine.data(),
                     mine.size(),
                     MPI_DOUBLE,
                     all.data(),
                     n6.data(),
                     offset6.data(),
                     MPI_DOUBLE,
                     communicator);
      for (unsigned int k = 0; k < gather_order.size(); ++k)
        for (unsigned int d = 0; d < 3; ++d)
          {
            position[3 * gather_order[k] + d] = all[6 * k + d];
            velocity[3 * gather_order[k] + d] = all[6 * k + 3 + d];
          }
    }


    bool
    YarnContact::lists_may_miss(const std::vector<double> &x) const
    {
      int miss                = built ? 0 : 1;
      const double half_skin2 = 0.25 * parameters.skin * parameters.skin;
      for (unsigned int k = 0; k < owned.size() && !miss; ++k)
        {
          const double *b = &built_position[3 * owned[k]];
          const double d0 = x[3 * k] - b[0], d1 = x[3 * k + 1] - b[1],
                       d2 = x[3 * k + 2] - b[2];
          miss            = d0 * d0 + d1 * d1 + d2 * d2 > half_skin2;
        }
      int any = 0;
      MPI_Allreduce(&miss, &any, 1, MPI_INT, MPI_MAX, communicator);
      return any != 0;
    }


    void
    YarnContact::set_up_exchange()
    {
      // The nodes this rank's slots read: the slave's faces (for its
      // area vector) and its candidate faces.
      std::vector<std::uint8_t> needed(surface.n_nodes(), 0);
      for (const Slot &slot : slots)
        {
          for (const unsigned int f : node_faces[slot.node])
            for (const unsigned int node : surface.faces[f])
              needed[node] = 1;
          for (unsigned int i = slot.begin; i < slot.end; ++i)
            for (const unsigned int node : surface.faces[slot_faces[i]])
              needed[node] = 1;
        }
      const unsigned int n_ranks = counts.size();

      // Requests, ascending by owner then node, then what each owner
      // sends back in that order.
      std::vector<std::vector<unsigned int>> from(n_ranks);
      for (unsigned int node = 0; node < surface.n_nodes(); ++node)
        if (needed[node] && !is_owned[node])
          from[node_owner[node]].push_back(node);
      receive_nodes.clear();
      receive_counts.assign(n_ranks, 0);
      receive_offsets.assign(n_ranks + 1, 0);
      for (unsigned int r = 0; r < n_ranks; ++r)
        {
          receive_nodes.insert(receive_nodes.end(),
                               from[r].begin(),
                               from[r].end());
          receive_offsets[r + 1] = receive_nodes.size();
          receive_counts[r]      = from[r].size();
        }
      send_counts.assign(n_ranks, 0);
      send_offsets.assign(n_ranks + 1, 0);
      MPI_Alltoall(receive_counts.data(),
                   1,
                   MPI_INT,
                   send_counts.data(),
                   1,
                   MPI_INT,
                   communicator);
      for (unsigned int r = 0; r < n_ranks; ++r)
        send_offsets[r + 1] = send_offsets[r] + send_counts[r];
      send_nodes.resize(send_offsets.back());
      MPI_Alltoallv(receive_nodes.data(),
                    receive_counts.data(),
                    receive_offsets.data(),
                    MPI_UNSIGNED,
                    send_nodes.data(),
                    send_counts.data(),
                    send_offsets.data(),
                    MPI_UNSIGNED,
                    communicator);
    }


    void
    YarnContact::exchange(const std::vector<double> &x,
                          const std::vector<double> &v)
    {
      for (unsigned int k = 0; k < owned.size(); ++k)
        for (unsigned int d = 0; d < 3; ++d)
          {
            position[3 * owned[k] + d] = x[3 * k + d];
            velocity[3 * owned[k] + d] = v[3 * k + d];
          }
      const unsigned int n_ranks = counts.size();
      std::vector<double> out(6 * send_nodes.size()),
        in(6 * receive_nodes.size());
      for (unsigned int i = 0; i < send_nodes.size(); ++i)
        {
          const unsigned int k = local_index[send_nodes[i]];
          for (unsigned int d = 0; d < 3; ++d)
            {
              out[6 * i + d]     = x[3 * k + d];
              out[6 * i + 3 + d] = v[3 * k + d];
            }
        }
      std::vector<int> n_out(n_ranks), at_out(n_ranks), n_in(n_ranks),
        at_in(n_ranks);
      for (unsigned int r = 0; r < n_ranks; ++r)
        {
          n_out[r]  = 6 * send_counts[r];
          at_out[r] = 6 * send_offsets[r];
          n_in[r]   = 6 * receive_counts[r];
          at_in[r]  = 6 * receive_offsets[r];
        }
      MPI_Alltoallv(out.data(),
                    n_out.data(),
                    at_out.data(),
                    MPI_DOUBLE,
                    in.data(),
                    n_in.data(),
                    at_in.data(),
                    MPI_DOUBLE,
                    communicator);
      for (unsigned int i = 0; i < receive_nodes.size(); ++i)
        for (unsigned int d = 0; d < 3; ++d)
          {
            position[3 * receive_nodes[i] + d] = in[6 * i + d];
            velocity[3 * receive_nodes[i] + d] = in[6 * i + 3 + d];
          }
    }


    void
    YarnContact::add_terms(std::vector<double> &force)
    {
      const unsigned int n_ranks = counts.size();
      std::vector<int> n_out(n_ranks), at_out(n_ranks + 1, 0), n_in(n_ranks),
        at_in(n_ranks + 1, 0);
      std::vector<double> out;
      for (unsigned int r = 0; r < n_ranks; ++r)
        {
          n_out[r] = remote_terms[r].size();
          out.insert(out.end(), remote_terms[r].begin(), remote_terms[r].end());
          at_out[r + 1] = at_out[r] + n_out[r];
        }
      if (n_ranks > 1)
        MPI_Alltoall(n_out.data(),
                     1,
                     MPI_INT,
                     n_in.data(),
                     1,
                     MPI_INT,
                     communicator);
      for (unsigned int r = 0; r < n_ranks; ++r)
        at_in[r + 1] = at_in[r] + n_in[r];
      // This rank's terms, then those of its nodes from the other ranks.
      std::vector<double> &terms = local_terms;
      const std::size_t n_local  = terms.size();
      terms.resize(n_local + at_in[n_ranks]);
      if (n_ranks > 1)
        MPI_Alltoallv(out.data(),
                      n_out.data(),
                      at_out.data(),
                      MPI_DOUBLE,
                      terms.data() + n_local,
                      n_in.data(),
                      at_in.data(),
                      MPI_DOUBLE,
                      communicator);
      // Each node's terms in the global order of their slots (node, then
      // yarn) and of the terms within a slot: the order of a one-rank
      // evaluation, so that the sums are the same bit for bit on any
      // partition.
      const unsigned int n_terms = terms.size() / term_size;
      std::vector<unsigned int> order(n_terms);
      for (unsigned int i = 0; i < n_terms; ++i)
        order[i] = i;
      std::sort(order.begin(),
                order.end(),
                [&](const unsigned int a, const unsigned int b) {
                  const double *x = &terms[term_size * a],
                               *y = &terms[term_size * b];
                  return std::lexicographical_compare(x, x + 4, y, y + 4);
                });
      for (const unsigned int i : order)
        {
          const double *t      = &terms[term_size * i];
          const unsigned int k = local_index[static_cast<unsigned int>(t[0])];
          for (unsigned int d = 0; d < 3; ++d)
            force[3 * k + d] += t[4 + d];
        }
    }
  } // namespace Fabric
} // namespace YarnImpact
