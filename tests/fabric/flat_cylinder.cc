// The flat-faced cylinder's contact geometry (Projectile/Shape = flat
// cylinder, doc/fabric.md section 1): Contact::flat_cylinder_overlap for
// the cylinder of radius R = 1.1 mm, its axis the y axis, its face at
// y = 0.2 mm, against closed forms. A point inside (above the face, within
// the radius) touches with the smaller of its depth above the face (normal
// -y) and its depth inside the rim (normal radial, in the x-z plane); a
// point below the face or outside the radius does not, nor one on the
// face or the rim (the test is strict); the result does not depend on the
// point's angle about the axis.

#include <yarn_impact/contact/projectile_contact.h>

#include <cmath>
#include <cstdio>
#include <initializer_list>

using namespace YarnImpact;

namespace
{
  const double R = 1.1e-3, face = 0.2e-3;

  /** Whether the point at radius r, angle a about the y axis, height y
   * touches with overlap @p expected along (nx, ny, nz) to 1e-15 m and
   * 1e-15. */
  bool
  touches(const double r,
          const double a,
          const double y,
          const double expected,
          const double nx,
          const double ny,
          const double nz)
  {
    double delta = -1., n[3] = {0., 0., 0.};
    if (!Contact::flat_cylinder_overlap(r * std::cos(a),
                                        y,
                                        r * std::sin(a),
                                        face,
                                        R,
                                        delta,
                                        n))
      return false;
    return std::abs(delta - expected) < 1e-15 && std::abs(n[0] - nx) < 1e-15 &&
           std::abs(n[1] - ny) < 1e-15 && std::abs(n[2] - nz) < 1e-15;
  }

  bool
  misses(const double r, const double a, const double y)
  {
    double delta = -1., n[3] = {0., 0., 0.};
    return !Contact::flat_cylinder_overlap(r * std::cos(a),
                                           y,
                                           r * std::sin(a),
                                           face,
                                           R,
                                           delta,
                                           n) &&
           delta == -1.;
  }
} // namespace

int
main()
{
  bool face_ok = true, rim_ok = true, out_ok = true;
  for (const double a : {0., 0.7, 2.5, -1.9})
    {
      const double c = std::cos(a), s = std::sin(a);
      // 2 um above the face at the axis, at half the radius and 3 um
      // inside the rim: the face is the shorter way out.
      face_ok &= touches(0., a, face + 2e-6, 2e-6, 0., -1., 0.);
      face_ok &= touches(0.5 * R, a, face + 2e-6, 2e-6, 0., -1., 0.);
      face_ok &= touches(R - 3e-6, a, face + 2e-6, 2e-6, 0., -1., 0.);
      // 1 um inside the rim, 5 um above the face: out through the rim.
      rim_ok &= touches(R - 1e-6, a, face + 5e-6, 1e-6, c, 0., s);
      rim_ok &= touches(R - 1e-6, a, face + 1e-3, 1e-6, c, 0., s);
      // Below the face, outside the rim, on either.
      out_ok &= misses(0.5 * R, a, face - 1e-6);
      out_ok &= misses(R + 1e-6, a, face + 2e-6);
      out_ok &= misses(0.5 * R, a, face);
    }
  // On the rim exactly (at a = 0, where x = R holds every bit).
  out_ok &= misses(R, 0., face + 2e-6);
  std::printf("inside, nearer the face: overlap the depth, normal -y: %s\n",
              face_ok ? "OK" : "WRONG");
  std::printf("inside, nearer the rim: overlap R - r, normal radial: %s\n",
              rim_ok ? "OK" : "WRONG");
  std::printf("below the face, outside or on the rim: no contact: %s\n",
              out_ok ? "OK" : "WRONG");
}
