// The geometry of the yarn contact (source/fabric/yarn_contact.cc): the
// closest point of a node to a bilinear face, the box test that skips it,
// a face's normal. Private to the fabric's yarn contact.
#ifndef yarn_impact_fabric_yarn_contact_geometry_h
#define yarn_impact_fabric_yarn_contact_geometry_h

#include <algorithm>
#include <cmath>

namespace YarnImpact
{
  namespace Fabric
  {
    namespace internal
    {
      /** The closest point of a bilinear face to a point. */
      struct Projection
      {
        /** Shape functions at the closest point [-]. */
        double N[4];
        /** Unit normal there, out of the face's yarn [-]. */
        double n[3];
        /** Signed distance along n [m] (negative: penetrated). */
        double gap;
        /** The closest point's coordinates in the face [-]. */
        double xi, eta;
      };

      /** Where the closest point of a face lies. */
      enum class Side
      {
        /** on the face (within 1e-9 of it in its coordinates) */
        inside,
        /** on the bilinear surface's extension, beyond the face's edges */
        beyond,
        /** not found (Newton did not converge) */
        failed
      };

      inline void
      cross(const double *a, const double *b, double *c)
      {
        c[0] = a[1] * b[2] - a[2] * b[1];
        c[1] = a[2] * b[0] - a[0] * b[2];
        c[2] = a[0] * b[1] - a[1] * b[0];
      }

      inline double
      dot(const double *a, const double *b)
      {
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
      }

      /**
       * The tangents X_xi and X_eta [m] of the bilinear face with cyclic
       * corners @p c at its coordinates (@p xi, @p eta); X_xi x X_eta
       * points out of the face's yarn.
       */
      inline void
      tangents(const double *const c[4],
               const double xi,
               const double eta,
               double *Xxi,
               double *Xeta)
      {
        for (unsigned int d = 0; d < 3; ++d)
          {
            Xxi[d] =
              (1 - eta) * (c[1][d] - c[0][d]) + eta * (c[2][d] - c[3][d]);
            Xeta[d] = (1 - xi) * (c[3][d] - c[0][d]) + xi * (c[2][d] - c[1][d]);
          }
      }

      /**
       * Closest point of the bilinear face with cyclic corners @p c to
       * @p p by Newton's method on (p - X) . X_xi = (p - X) . X_eta = 0,
       * from the centre: Side::inside if it lies on the face (within a
       * tolerance of 1e-9 in the face's coordinates, so that a node on an
       * edge still finds a face), Side::beyond if it lies on the surface's
       * extension (its coordinates in @p out), Side::failed if Newton has
       * not converged.
       */
      inline Side
      project(const double *const c[4], const double *p, Projection &out)
      {
        double xi = 0.5, eta = 0.5;
        double X[3], Xxi[3], Xeta[3], r[3];
        const double tolerance = 1e-9;
        for (unsigned int iteration = 0;; ++iteration)
          {
            const double N[4] = {(1 - xi) * (1 - eta),
                                 xi * (1 - eta),
                                 xi * eta,
                                 (1 - xi) * eta};
            double Xc[3];
            tangents(c, xi, eta, Xxi, Xeta);
            for (unsigned int d = 0; d < 3; ++d)
              {
                X[d] = N[0] * c[0][d] + N[1] * c[1][d] + N[2] * c[2][d] +
                       N[3] * c[3][d];
                Xc[d] = c[0][d] - c[1][d] + c[2][d] - c[3][d];
                r[d]  = p[d] - X[d];
              }
            if (iteration == 12)
              {
                out.xi  = xi;
                out.eta = eta;
                if (xi < -tolerance || xi > 1 + tolerance || eta < -tolerance ||
                    eta > 1 + tolerance)
                  return Side::beyond;
                std::copy(N, N + 4, out.N);
                break;
              }
            const double F0  = dot(r, Xxi);
            const double F1  = dot(r, Xeta);
            const double J00 = -dot(Xxi, Xxi);
            const double J11 = -dot(Xeta, Xeta);
            const double J01 = -dot(Xxi, Xeta) + dot(r, Xc);
            const double det = J00 * J11 - J01 * J01;
            if (!(std::abs(det) > 0.))
              return Side::failed;
            // A fixed number of iterations (converged long before on the
            // nearly flat faces of a yarn): no test on round-off, so that
            // every rank takes the same path.
            xi -= (J11 * F0 - J01 * F1) / det;
            eta -= (J00 * F1 - J01 * F0) / det;
            if (!(std::abs(xi) < 10. && std::abs(eta) < 10.))
              return Side::failed;
          }
        cross(Xxi, Xeta, out.n);
        const double length = std::sqrt(dot(out.n, out.n));
        for (unsigned int d = 0; d < 3; ++d)
          out.n[d] /= length;
        out.gap = dot(r, out.n);
        // Converged: x_s - X along the normal, within 1e-8 of the face's
        // size (Newton may stall on a warped face far from the point; the
        // search's proof needs x_s = X + g n).
        double tangential = 0.;
        for (unsigned int d = 0; d < 3; ++d)
          {
            const double t = r[d] - out.gap * out.n[d];
            tangential += t * t;
          }
        return tangential <= 1e-16 * (dot(Xxi, Xxi) + dot(Xeta, Xeta))
                 ? Side::inside
                 : Side::failed;
      }


      /**
       * The unit normal @p n of the bilinear face with corners @p c at its
       * coordinates (@p xi, @p eta) brought back onto the face.
       */
      inline void
      face_normal(const double *const c[4], double xi, double eta, double *n)
      {
        double Xxi[3], Xeta[3];
        tangents(c,
                 std::min(1., std::max(0., xi)),
                 std::min(1., std::max(0., eta)),
                 Xxi,
                 Xeta);
        cross(Xxi, Xeta, n);
        const double length = std::sqrt(dot(n, n));
        for (unsigned int d = 0; d < 3; ++d)
          n[d] /= length;
      }


      /**
       * Whether @p p lies in the box of the corners @p c, grown by the
       * detection depth @p depth [m] and 1e-6 of the box's extent: a
       * point outside it is farther than @p depth from the face, so that
       * project() cannot give it a contact, and its 12 Newton iterations
       * are skipped with the same result. Why the margin holds: project()
       * accepts a point whose distance to its closest point X is at most
       * sqrt(gap^2 + 1e-16 (|X_xi|^2 + |X_eta|^2)), that is at most the
       * depth plus 2.5e-8 of the extent, and X lies within 1e-8 of the
       * extent of the box (xi, eta within 1e-9 of [0, 1]). The box's
       * largest extent [m] goes to @p extent.
       */
      inline bool
      may_touch(const double *c[4],
                const double *p,
                const double depth,
                double &extent)
      {
        double lo[3], hi[3];
        extent = 0.;
        for (unsigned int d = 0; d < 3; ++d)
          {
            lo[d] =
              std::min(std::min(c[0][d], c[1][d]), std::min(c[2][d], c[3][d]));
            hi[d] =
              std::max(std::max(c[0][d], c[1][d]), std::max(c[2][d], c[3][d]));
            extent = std::max(extent, hi[d] - lo[d]);
          }
        const double grow = depth + 1e-6 * extent;
        for (unsigned int d = 0; d < 3; ++d)
          if (p[d] < lo[d] - grow || p[d] > hi[d] + grow)
            return false;
        return true;
      }
    } // namespace internal
  }   // namespace Fabric
} // namespace YarnImpact

#endif
