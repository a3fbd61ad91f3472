// The eroding yarn contact: the faces of failed cells leave the contact
// (doc/fe-model.md section 8.4, "Failed cells").

#include <yarn_impact/fabric/yarn_contact.h>

#include <algorithm>

namespace YarnImpact
{
  namespace Fabric
  {
    void
    YarnContact::remove_cells(const std::vector<double> &cells,
                              const bool restored)
    {
      // Every rank applies every rank's cells: the surface is known to all.
      int n_ranks;
      MPI_Comm_size(communicator, &n_ranks);
      const int n = cells.size();
      std::vector<int> sizes(n_ranks), offsets(n_ranks + 1, 0);
      MPI_Allgather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, communicator);
      for (int r = 0; r < n_ranks; ++r)
        offsets[r + 1] = offsets[r] + sizes[r];
      if (offsets.back() == 0)
        return;
      std::vector<double> all(offsets.back());
      MPI_Allgatherv(cells.data(),
                     n,
                     MPI_DOUBLE,
                     all.data(),
                     sizes.data(),
                     offsets.data(),
                     MPI_DOUBLE,
                     communicator);
      // A face is a failed cell's when its four nodes are among the
      // cell's vertices, found on the surface by position as the FE nodes
      // are (match_surface_nodes(): vertex k is cell k / 8's); a boundary
      // face has one cell.
      std::vector<std::vector<unsigned int>> on_surface(all.size() / 24);
      for (const auto &[node, k] : match_surface_nodes(surface.reference, all))
        on_surface[k / 8].push_back(node);
      for (const auto &cell : on_surface)
        {
          const auto in_cell = [&](const unsigned int node) {
            return std::find(cell.begin(), cell.end(), node) != cell.end();
          };
          for (const unsigned int node : cell)
            for (const unsigned int f : node_faces[node])
              if (!face_removed[f] && std::all_of(surface.faces[f].begin(),
                                                  surface.faces[f].end(),
                                                  in_cell))
                {
                  face_removed[f] = 1;
                  ++n_removed;
                  if (!restored)
                    removed_now.push_back(f);
                  for (const unsigned int node : surface.faces[f])
                    --node_live_faces[node];
                }
        }
    }


    void
    YarnContact::find_eroding()
    {
      eroding.clear();
      if (removed_now.empty())
        return;
      // The touching contacts that may end for it: their node's faces or
      // their candidate faces went now.
      std::vector<std::uint8_t> now(surface.faces.size(), 0);
      for (const unsigned int f : removed_now)
        now[f] = 1;
      removed_now.clear();
      for (const Slot &slot : slots)
        {
          if (!slot.touching || !is_owned[slot.node])
            continue;
          bool hit = false;
          for (const unsigned int f : node_faces[slot.node])
            hit = hit || now[f];
          for (unsigned int i = slot.begin; i < slot.end && !hit; ++i)
            hit = now[slot_faces[i]];
          if (hit)
            eroding.push_back({{slot.node, slot.yarn}, slot.energy});
        }
      std::sort(eroding.begin(), eroding.end());
    }


    void
    YarnContact::end_contact(Slot &slot)
    {
      if (slot.touching)
        {
          const std::pair<unsigned int, unsigned int> key = {slot.node,
                                                             slot.yarn};
          const auto it =
            std::lower_bound(eroding.begin(),
                             eroding.end(),
                             key,
                             [](const auto &entry, const auto &k) {
                               return entry.first < k;
                             });
          if (it != eroding.end() && it->first == key)
            node_dissipated[slot.node] += it->second;
        }
      slot.touching = false;
      slot.n_tied   = 0;
      slot.energy   = 0.;
    }
  } // namespace Fabric
} // namespace YarnImpact
