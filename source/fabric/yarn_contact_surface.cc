// The surface of the yarn-yarn contact and its candidate search
// (doc/fe-model.md section 8.4).

#include <yarn_impact/fabric/yarn_contact.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_map>

namespace YarnImpact
{
  namespace Fabric
  {
    std::vector<std::pair<unsigned int, unsigned int>>
    match_surface_nodes(const std::vector<dealii::Point<3>> &surface,
                        const std::vector<double> &fe_reference)
    {
      std::map<std::array<double, 3>, unsigned int> index;
      for (unsigned int n = 0; n < surface.size(); ++n)
        index.emplace(
          std::array<double, 3>{{surface[n][0], surface[n][1], surface[n][2]}},
          n);
      std::vector<std::pair<unsigned int, unsigned int>> found;
      for (unsigned int k = 0; 3 * k < fe_reference.size(); ++k)
        {
          const auto it = index.find({{fe_reference[3 * k],
                                       fe_reference[3 * k + 1],
                                       fe_reference[3 * k + 2]}});
          if (it != index.end())
            found.emplace_back(it->second, k);
        }
      std::sort(found.begin(), found.end());
      return found;
    }


    ContactSurface
    make_contact_surface(const dealii::Triangulation<3, 3> &mesh,
                         const double density,
                         const std::set<unsigned int> &boundary_ids)
    {
      ContactSurface s;
      // Surface nodes numbered by vertex index: the same on every rank.
      std::vector<int> node_of(mesh.n_vertices(), -1);
      std::vector<std::pair<unsigned int, unsigned int>> face_vertices;
      for (const auto &cell : mesh.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          {
            const auto face = cell->face(f);
            if (!face->at_boundary() ||
                (!boundary_ids.empty() &&
                 boundary_ids.count(face->boundary_id()) == 0))
              continue;
            // deal.II's lexicographic face vertices 0 1 2 3 in cyclic
            // order are 0 1 3 2.
            std::array<unsigned int, 4> c = {{face->vertex_index(0),
                                              face->vertex_index(1),
                                              face->vertex_index(3),
                                              face->vertex_index(2)}};
            const auto &v                 = mesh.get_vertices();
            const dealii::Tensor<1, 3> normal =
              dealii::cross_product_3d(v[c[2]] - v[c[0]], v[c[3]] - v[c[1]]);
            if (normal * (face->center() - cell->center()) < 0.)
              std::swap(c[1], c[3]);
            for (const unsigned int i : c)
              node_of[i] = 0;
            s.faces.push_back(c);
            s.face_yarn.push_back(cell->material_id());
          }
      for (unsigned int i = 0; i < mesh.n_vertices(); ++i)
        if (node_of[i] == 0)
          {
            node_of[i] = s.reference.size();
            s.reference.push_back(mesh.get_vertices()[i]);
          }
      s.node_yarn.assign(s.n_nodes(), 0);
      s.area.assign(s.n_nodes(), 0.);
      s.mass.assign(s.n_nodes(), 0.);
      for (unsigned int f = 0; f < s.faces.size(); ++f)
        for (unsigned int &i : s.faces[f])
          {
            i              = node_of[i];
            s.node_yarn[i] = s.face_yarn[f];
          }

      // Areas: the integral of each node's bilinear shape function over
      // its faces (2 x 2 Gauss points, exact for a flat face).
      const double g[2] = {0.5 - 0.5 / std::sqrt(3.),
                           0.5 + 0.5 / std::sqrt(3.)};
      for (const auto &c : s.faces)
        for (const double xi : g)
          for (const double eta : g)
            {
              const double N[4] = {(1 - xi) * (1 - eta),
                                   xi * (1 - eta),
                                   xi * eta,
                                   (1 - xi) * eta};
              dealii::Tensor<1, 3> dxi, deta;
              const double dNxi[4]  = {-(1 - eta), 1 - eta, eta, -eta};
              const double dNeta[4] = {-(1 - xi), -xi, xi, 1 - xi};
              for (unsigned int a = 0; a < 4; ++a)
                {
                  dxi += dNxi[a] * s.reference[c[a]];
                  deta += dNeta[a] * s.reference[c[a]];
                }
              const double J = dealii::cross_product_3d(dxi, deta).norm();
              for (unsigned int a = 0; a < 4; ++a)
                s.area[c[a]] += 0.25 * N[a] * J;
            }

      // Lumped masses: Q1's shape function i is vertex i's.
      dealii::FE_Q<3> fe(1);
      const dealii::MappingQ1<3> mapping;
      dealii::FEValues<3> values(mapping,
                                 fe,
                                 dealii::QGauss<3>(2),
                                 dealii::update_values |
                                   dealii::update_JxW_values);
      for (const auto &cell : mesh.active_cell_iterators())
        {
          values.reinit(cell);
          for (unsigned int i = 0; i < 8; ++i)
            {
              const int node = node_of[cell->vertex_index(i)];
              if (node < 0)
                continue;
              for (unsigned int q = 0; q < values.n_quadrature_points; ++q)
                s.mass[node] +=
                  density * values.shape_value(i, q) * values.JxW(q);
            }
        }
      return s;
    }


    void
    YarnContact::rebuild()
    {
      // The histories of the touching contacts: a node's owner evaluates
      // all its contacts, so they are this rank's own (or load()'s).
      std::vector<double> all = std::move(loaded);
      loaded.clear();
      append_touching(all);
      std::map<std::pair<unsigned int, unsigned int>, const double *> old;
      for (unsigned int i = 0; i < all.size();
           i += 9 + 4 * static_cast<unsigned int>(all[i + 8]))
        old[{static_cast<unsigned int>(all[i]),
             static_cast<unsigned int>(all[i + 1])}] = &all[i + 2];

      // Bins of side h, the largest face box grown by 2 d_max + skin: each
      // face goes into the bins its grown box meets.
      const unsigned int n_faces = surface.faces.size();
      // Touching contacts hold their nodes to 2 d_max.
      const double grow = 2. * parameters.detection_depth + parameters.skin;
      std::vector<std::array<double, 6>> box(n_faces);
      double h = 0.;
      for (unsigned int f = 0; f < n_faces; ++f)
        {
          auto &b = box[f];
          for (unsigned int d = 0; d < 3; ++d)
            {
              b[d]     = position[3 * surface.faces[f][0] + d];
              b[d + 3] = b[d];
            }
          for (const unsigned int node : surface.faces[f])
            for (unsigned int d = 0; d < 3; ++d)
              {
                b[d]     = std::min(b[d], position[3 * node + d]);
                b[d + 3] = std::max(b[d + 3], position[3 * node + d]);
              }
          // The projection's tolerance lets a point lie 1e-9 of the face
          // outside it: 1e-6 of the box covers that.
          double extent = 0.;
          for (unsigned int d = 0; d < 3; ++d)
            extent = std::max(extent, b[d + 3] - b[d]);
          for (unsigned int d = 0; d < 3; ++d)
            {
              b[d] -= grow + 1e-6 * extent;
              b[d + 3] += grow + 1e-6 * extent;
              h = std::max(h, b[d + 3] - b[d]);
            }
        }
      const auto key = [](const long i, const long j, const long k) {
        return (static_cast<std::uint64_t>(i & 0x1fffff) << 42) |
               (static_cast<std::uint64_t>(j & 0x1fffff) << 21) |
               static_cast<std::uint64_t>(k & 0x1fffff);
      };
      const auto bin = [h](const double x) {
        return static_cast<long>(std::floor(x / h));
      };
      std::unordered_map<std::uint64_t, std::vector<unsigned int>> bins;
      for (unsigned int f = 0; f < n_faces; ++f)
        for (long i = bin(box[f][0]); i <= bin(box[f][3]); ++i)
          for (long j = bin(box[f][1]); j <= bin(box[f][4]); ++j)
            for (long k = bin(box[f][2]); k <= bin(box[f][5]); ++k)
              bins[key(i, j, k)].push_back(f);

      slots.clear();
      slot_faces.clear();
      std::vector<std::pair<unsigned int, unsigned int>> found;
      // The slots of this rank's nodes only: each contact is evaluated by
      // its node's owner (add_terms() sends the forces on the faces' nodes
      // to theirs).
      for (unsigned int s = 0; s < surface.n_nodes(); ++s)
        {
          if (!is_owned[s])
            continue;
          const double *p = &position[3 * s];
          const auto it   = bins.find(key(bin(p[0]), bin(p[1]), bin(p[2])));
          if (it == bins.end())
            continue;
          found.clear();
          for (const unsigned int f : it->second)
            if (surface.face_yarn[f] != surface.node_yarn[s] &&
                p[0] >= box[f][0] && p[0] <= box[f][3] && p[1] >= box[f][1] &&
                p[1] <= box[f][4] && p[2] >= box[f][2] && p[2] <= box[f][5])
              found.emplace_back(surface.face_yarn[f], f);
          std::sort(found.begin(), found.end());
          // One slot per other yarn.
          for (unsigned int a = 0; a < found.size();)
            {
              unsigned int b = a;
              while (b < found.size() && found[b].first == found[a].first)
                ++b;
              Slot slot;
              slot.node  = s;
              slot.yarn  = found[a].first;
              slot.begin = slot_faces.size();
              for (unsigned int c = a; c < b; ++c)
                slot_faces.push_back(found[c].second);
              slot.end     = slot_faces.size();
              const auto o = old.find({slot.node, slot.yarn});
              if (o != old.end())
                {
                  slot.touching = true;
                  std::copy(o->second, o->second + 3, slot.history);
                  slot.stiffness = o->second[3];
                  slot.offset    = o->second[4];
                  slot.energy    = o->second[5];
                  slot.n_tied    = static_cast<unsigned int>(o->second[6]);
                  for (unsigned int k = 0; k < slot.n_tied; ++k)
                    {
                      const double *tied = o->second + 7 + 4 * k;
                      slot.tied_face[k]  = static_cast<unsigned int>(tied[0]);
                      std::copy(tied + 1, tied + 4, slot.tied_history[k]);
                    }
                }
              slots.push_back(slot);
              a = b;
            }
        }
      built_position = position;
      built          = true;
      ++rebuilds;
    }


    void
    YarnContact::append_touching(std::vector<double> &out) const
    {
      for (const Slot &slot : slots)
        if (slot.touching && is_owned[slot.node])
          {
            out.insert(out.end(),
                       {double(slot.node),
                        double(slot.yarn),
                        slot.history[0],
                        slot.history[1],
                        slot.history[2],
                        slot.stiffness,
                        slot.offset,
                        slot.energy,
                        double(slot.n_tied)});
            for (unsigned int k = 0; k < slot.n_tied; ++k)
              out.insert(out.end(),
                         {double(slot.tied_face[k]),
                          slot.tied_history[k][0],
                          slot.tied_history[k][1],
                          slot.tied_history[k][2]});
          }
    }


    void
    YarnContact::save(Checkpoint::Writer &out) const
    {
      out.tag("yarn contact");
      std::vector<double> touching, work;
      append_touching(touching);
      for (const unsigned int node : owned)
        work.push_back(node_dissipated[node]);
      out.put(touching);
      out.put(work);
    }


    void
    YarnContact::load(Checkpoint::Reader &in)
    {
      in.tag("yarn contact");
      std::vector<double> touching, work(owned.size());
      in.get(touching);
      in.get_same_size(work, "dissipated work of the yarn contact's nodes");
      for (unsigned int k = 0; k < owned.size(); ++k)
        node_dissipated[owned[k]] = work[k];
      loaded = touching;
      slots.clear();
      slot_faces.clear();
      built = false;
    }
  } // namespace Fabric
} // namespace YarnImpact
