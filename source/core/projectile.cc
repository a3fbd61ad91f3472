#include <yarn_impact/core/projectile.h>

namespace YarnImpact
{
  Projectile::Projectile(const Parameters::Projectile &parameters,
                         const double yarn_thickness_semi_axis)
    : m(parameters.mass)
    , r(0.5 * parameters.diameter)
    , y0(yarn_thickness_semi_axis + 0.5 * parameters.diameter)
    , y(y0)
    , v(-parameters.initial_velocity)
    , is_prescribed(parameters.motion ==
                    Parameters::ProjectileMotion::prescribed_velocity)
    , shape_(parameters.shape)
    , x0(parameters.offset_x)
    , z0(parameters.offset_z)
  {}

  void
  Projectile::save(Checkpoint::Writer &out) const
  {
    out.tag("projectile");
    out.put(y0);
    out.put(y);
    out.put(v);
    out.put(work);
  }

  void
  Projectile::load(Checkpoint::Reader &in)
  {
    in.tag("projectile");
    in.get(y0);
    in.get(y);
    in.get(v);
    in.get(work);
  }

  void
  Projectile::kick(const double dt, const double force)
  {
    if (is_prescribed)
      // The driver applies -force; its power is -force * v.
      work += -force * v * dt;
    else
      v += dt * force / m;
  }
} // namespace YarnImpact
