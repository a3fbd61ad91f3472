// The yarn contact at the boundaries of faces (doc/fabric.md section 2,
// "Edges and vertices").

#include <yarn_impact/fabric/yarn_contact.h>

#include <algorithm>
#include <cmath>

#include "yarn_contact_geometry.h"

namespace YarnImpact
{
  namespace Fabric
  {
    using namespace internal;

    bool
    YarnContact::boundary_contact(const unsigned int face,
                                  double xi,
                                  double eta,
                                  const double *p,
                                  const double reach,
                                  double N[4],
                                  double n[3],
                                  double &depth,
                                  unsigned int key[2]) const
    {
      // The face's closest point on its extension brought back onto it
      // names the feature, one of its edges or vertices; the feature's own
      // closest point to the node, from its nodes alone, is the same
      // whichever face names it.
      xi                      = std::min(1., std::max(0., xi));
      eta                     = std::min(1., std::max(0., eta));
      const auto &corners     = surface.faces[face];
      const double weights[4] = {(1 - xi) * (1 - eta),
                                 xi * (1 - eta),
                                 xi * eta,
                                 (1 - xi) * eta};
      unsigned int feature[2], n_feature = 0;
      for (unsigned int a = 0; a < 4; ++a)
        if (weights[a] > 0.)
          {
            if (n_feature == 2)
              return false;
            feature[n_feature++] = corners[a];
          }
      if (n_feature == 0)
        return false;
      double feature_weight[2] = {1., 0.};
      double r[3];
      if (n_feature == 2)
        {
          if (feature[1] < feature[0])
            std::swap(feature[0], feature[1]);
          const double *xa = &position[3 * feature[0]];
          const double *xb = &position[3 * feature[1]];
          double e[3];
          for (unsigned int d = 0; d < 3; ++d)
            {
              e[d] = xb[d] - xa[d];
              r[d] = p[d] - xa[d];
            }
          const double t = dot(r, e) / dot(e, e);
          if (!(t > 0.))
            n_feature = 1;
          else if (!(t < 1.))
            {
              feature[0] = feature[1];
              n_feature  = 1;
            }
          else
            {
              feature_weight[0] = 1. - t;
              feature_weight[1] = t;
              for (unsigned int d = 0; d < 3; ++d)
                r[d] -= t * e[d];
            }
        }
      if (n_feature == 1)
        for (unsigned int d = 0; d < 3; ++d)
          r[d] = p[d] - position[3 * feature[0] + d];
      const double distance2 = dot(r, r);
      if (!(distance2 > 0.) || distance2 > reach * reach)
        return false;
      // On a symmetry plane when all its nodes are: the faces' images
      // across the plane count among its faces.
      bool mirror[2] = {true, true};
      for (unsigned int k = 0; k < n_feature; ++k)
        {
          mirror[0] = mirror[0] && on_symmetry_plane(feature[k], 0);
          mirror[1] = mirror[1] && on_symmetry_plane(feature[k], 2);
        }
      // The feature's point, from which the faces leave it.
      double X[3];
      for (unsigned int d = 0; d < 3; ++d)
        X[d] = p[d] - r[d];
      // The point must lie behind every face that holds the feature, and
      // behind their images, and the feature must be each one's closest
      // point to it: the wedge of a concave edge or vertex, where it
      // projects onto none of them; there its distance to the feature is
      // its distance to the surface, its penetration, which meets a face's
      // depth where the point's projection reaches that face.
      const double parameter[4][2] = {{0., 0.}, {1., 0.}, {1., 1.}, {0., 1.}};
      unsigned int n_faces         = 0;
      for (const unsigned int g : node_faces[feature[0]])
        {
          // A failed cell's face holds no feature.
          if (face_removed[g])
            continue;
          const auto &cg     = surface.faces[g];
          double at[2]       = {0., 0.};
          unsigned int found = 0;
          for (unsigned int k = 0; k < n_feature; ++k)
            for (unsigned int a = 0; a < 4; ++a)
              if (cg[a] == feature[k])
                {
                  at[0] += feature_weight[k] * parameter[a][0];
                  at[1] += feature_weight[k] * parameter[a][1];
                  ++found;
                }
          if (found != n_feature)
            continue;
          const double *c[4];
          for (unsigned int a = 0; a < 4; ++a)
            c[a] = &position[3 * cg[a]];
          // The face's normal there, and the directions along which its
          // points leave the feature: from a vertex its two edges, from
          // an edge the face's own direction across it.
          double ng[3], away[2][3];
          face_normal(c, at[0], at[1], ng);
          unsigned int n_away = 0;
          for (unsigned int a = 0; a < 4; ++a)
            if (cg[a] == feature[0])
              {
                const unsigned int next = cg[(a + 1) % 4],
                                   prev = cg[(a + 3) % 4];
                if (n_feature == 1)
                  {
                    for (unsigned int d = 0; d < 3; ++d)
                      {
                        away[0][d] = position[3 * next + d] - X[d];
                        away[1][d] = position[3 * prev + d] - X[d];
                      }
                    n_away = 2;
                  }
                else
                  {
                    // Across the edge: the normal times the edge, turned
                    // toward the face's other corners.
                    const unsigned int other = next == feature[1] ? prev : next;
                    double e[3], across[3];
                    for (unsigned int d = 0; d < 3; ++d)
                      e[d] = position[3 * feature[1] + d] -
                             position[3 * feature[0] + d];
                    cross(ng, e, across);
                    double toward[3];
                    for (unsigned int d = 0; d < 3; ++d)
                      toward[d] =
                        position[3 * other + d] - position[3 * feature[0] + d];
                    const double sign = dot(across, toward) < 0. ? -1. : 1.;
                    for (unsigned int d = 0; d < 3; ++d)
                      away[0][d] = sign * across[d];
                    n_away = 1;
                  }
              }
          // Behind the face and beyond the feature, for the face and its
          // images: the feature is the face's closest point to the node.
          const auto holds = [&](const bool flip_x, const bool flip_z) {
            double q[3] = {r[0], r[1], r[2]};
            if (flip_x)
              q[0] = -q[0];
            if (flip_z)
              q[2] = -q[2];
            if (!(dot(q, ng) < 0.))
              return false;
            for (unsigned int k = 0; k < n_away; ++k)
              if (dot(q, away[k]) > 0.)
                return false;
            return true;
          };
          if (!holds(false, false) || (mirror[0] && !holds(true, false)) ||
              (mirror[1] && !holds(false, true)) ||
              (mirror[0] && mirror[1] && !holds(true, true)))
            return false;
          ++n_faces;
        }
      // A feature at the surface's own boundary (a yarn's clamped end) is
      // not inside a wedge: an edge needs two faces, a vertex three,
      // images counted.
      const unsigned int images = (1 + mirror[0]) * (1 + mirror[1]);
      if (n_faces * images < (n_feature == 2 ? 2u : 3u))
        return false;
      const double distance = std::sqrt(distance2);
      for (unsigned int d = 0; d < 3; ++d)
        n[d] = -r[d] / distance;
      for (unsigned int a = 0; a < 4; ++a)
        {
          N[a] = 0.;
          for (unsigned int k = 0; k < n_feature; ++k)
            if (corners[a] == feature[k])
              N[a] = feature_weight[k];
        }
      depth  = distance;
      key[0] = feature[0];
      key[1] = feature[n_feature - 1];
      return true;
    }
  } // namespace Fabric
} // namespace YarnImpact
