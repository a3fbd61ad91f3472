#ifndef yarn_impact_contact_projectile_contact_h
#define yarn_impact_contact_projectile_contact_h

#include <cmath>

namespace YarnImpact
{
  namespace Contact
  {
    /**
     * The overlap of a point at the offset (@p ex, @p ey, @p ez) [m] from
     * the projectile's axis or centre, closer than @p reach [m]: sets the
     * overlap @p delta [m] and the unit normal @p n along the offset and
     * returns true, or returns false (nothing set).
     */
    inline bool
    radial_overlap(const double ex,
                   const double ey,
                   const double ez,
                   const double reach,
                   double &delta,
                   double *n)
    {
      const double r2 = ex * ex + ey * ey + ez * ez;
      if (r2 >= reach * reach)
        return false;
      const double rho = std::sqrt(r2);
      delta            = reach - rho;
      n[0]             = ex / rho;
      n[1]             = ey / rho;
      n[2]             = ez / rho;
      return true;
    }


    /**
     * The geometry of a point of the yarn touching the rigid cylindrical
     * projectile (axis along z, at x = 0 and y = @p axis_y [m]), shared by
     * the FE's surface nodes and the DEM's spheres: the point at
     * (@p x, @p y) [m] touches when it is closer to the axis than
     * @p reach [m], which is where the models differ: the projectile's
     * radius for a surface node, the radius plus the sphere's for a
     * sphere centre. If it touches, the overlap @p delta [m] and the unit
     * normal @p n (in the x-y plane, from the axis to the point) are set
     * and true is returned; false (nothing set) if it does not.
     */
    inline bool
    projectile_overlap(const double x,
                       const double y,
                       const double axis_y,
                       const double reach,
                       double &delta,
                       double *n)
    {
      // The distance to the axis: the sphere's test on the offset with no
      // component along the axis (the same bits: ez = 0 adds nothing).
      return radial_overlap(x, y - axis_y, 0., reach, delta, n);
    }


    /**
     * projectile_overlap() for the rigid sphere centred at (0, @p centre_y,
     * 0) [m]: the point at (@p x, @p y, @p z) [m] touches when it is
     * closer to the centre than @p reach [m]; the unit normal @p n points
     * from the centre to the point.
     */
    inline bool
    sphere_overlap(const double x,
                   const double y,
                   const double z,
                   const double centre_y,
                   const double reach,
                   double &delta,
                   double *n)
    {
      return radial_overlap(x, y - centre_y, z, reach, delta, n);
    }


    /**
     * projectile_overlap() for the rigid flat-faced cylinder, its axis
     * along y through x = z = 0, its flat face at y = @p face_y [m] and
     * its body above it: the point at (@p x, @p y, @p z) [m] touches when
     * it is inside, above the face and closer to the axis than @p radius
     * [m]. The face and the rim are penalised apart, the edge between them
     * sharp: the overlap is the smaller of the depth above the face,
     * pushed out along -y, and the depth inside the rim, pushed out
     * radially, the shorter way out of the body.
     */
    inline bool
    flat_cylinder_overlap(const double x,
                          const double y,
                          const double z,
                          const double face_y,
                          const double radius,
                          double &delta,
                          double *n)
    {
      const double r2 = x * x + z * z;
      if (y <= face_y || r2 >= radius * radius)
        return false;
      const double rho = std::sqrt(r2), face = y - face_y, rim = radius - rho;
      if (face <= rim)
        {
          delta = face;
          n[0]  = 0.;
          n[1]  = -1.;
          n[2]  = 0.;
        }
      else
        {
          delta = rim;
          n[0]  = x / rho;
          n[1]  = 0.;
          n[2]  = z / rho;
        }
      return true;
    }


    /** The velocity @p v_rel [m/s] of a point moving at @p v [m/s]
     * relative to the projectile moving at @p projectile_velocity [m/s]
     * along y. */
    inline void
    relative_to_projectile(const double *v,
                           const double projectile_velocity,
                           double *v_rel)
    {
      v_rel[0] = v[0];
      v_rel[1] = v[1] - projectile_velocity;
      v_rel[2] = v[2];
    }
  } // namespace Contact
} // namespace YarnImpact

#endif
