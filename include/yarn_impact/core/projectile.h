#ifndef yarn_impact_core_projectile_h
#define yarn_impact_core_projectile_h

#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/parameters.h>

namespace YarnImpact
{
  /**
   * The rigid cylindrical projectile. Its axis is parallel to z (across the
   * yarn's width); it moves along y only. A sphere (`Projectile/Shape`,
   * Model = fabric only) has its centre on the line x = z = 0 where the
   * cylinder has its axis: everything here holds for it with "centre" for
   * "axis" and "point" for "line"; so does the flat-faced cylinder, its
   * axis along y, with its face, a radius below that centre, for the
   * lowest line. Both can strike off the line x = z = 0
   * (`Projectile/Impact offset x`, `z`). At t = 0 its lowest line touches
   * the top of the yarn at mid-span: the axis is at
   * \f$y_c = a_y + R\f$, where \f$a_y\f$ is the thickness semi-axis.
   *
   * The projectile always carries the full mass; models return the force of
   * the whole yarn (their modelled part times the symmetry factor), so its
   * motion does not depend on the symmetry chosen.
   *
   * Time integration is velocity Verlet (kick-drift-kick), the same
   * central-difference scheme the models use.
   */
  class Projectile
  {
  public:
    /**
     * @param parameters projectile data
     * @param yarn_thickness_semi_axis semi-axis of the yarn section along y [m]
     */
    Projectile(const Parameters::Projectile &parameters,
               const double yarn_thickness_semi_axis);

    /** Put the projectile at rest position touching the top of the yarn,
     * its lowest line at y = @p yarn_top [m]. */
    void
    place_on(const double yarn_top)
    {
      y0 = yarn_top + r;
      y  = y0;
    }

    /** Radius of the cylinder or the sphere [m]. */
    double
    radius() const
    {
      return r;
    }

    /** Whether the projectile is a sphere (centred on x = z = 0), not the
     * cylinder along z. */
    bool
    sphere() const
    {
      return shape_ == Parameters::ProjectileShape::sphere;
    }

    /** The projectile's shape (`Projectile/Shape`). */
    Parameters::ProjectileShape
    shape() const
    {
      return shape_;
    }

    /** The x [m] of the cylinder's axis, the sphere's centre or the flat
     * cylinder's axis (`Projectile/Impact offset x`). */
    double
    offset_x() const
    {
      return x0;
    }

    /** The z [m] of the sphere's centre or the flat cylinder's axis
     * (`Projectile/Impact offset z`; the cylinder along z has none). */
    double
    offset_z() const
    {
      return z0;
    }

    /** Mass [kg]. */
    double
    mass() const
    {
      return m;
    }

    /** Current y coordinate of the axis [m]; of the flat cylinder's
     * centre line at its radius above its face, so that the face is at
     * axis_position() - radius() (the lowest point of every shape). */
    double
    axis_position() const
    {
      return y;
    }

    /** Current velocity along y [m/s] (negative: towards the yarn). */
    double
    velocity() const
    {
      return v;
    }

    /** Speed in the impact direction, \f$-v_y\f$ [m/s]. */
    double
    impact_speed() const
    {
      return -v;
    }

    /** Displacement in the impact direction since t = 0 [m]. */
    double
    displacement() const
    {
      return y0 - y;
    }

    /** Kinetic energy [J]. */
    double
    kinetic_energy() const
    {
      return 0.5 * m * v * v;
    }

    /** Whether the velocity is prescribed (not changed by the yarn). */
    bool
    prescribed() const
    {
      return is_prescribed;
    }

    /**
     * Half of a velocity-Verlet kick: \f$v \mathrel{+}= \Delta t F/m\f$ for a
     * free projectile. For a prescribed velocity the work of the driving
     * force \f$-F\f$ is accumulated instead.
     * @param dt time increment [s]
     * @param force force of the whole yarn on the projectile along y [N]
     */
    void
    kick(const double dt, const double force);

    /** Drift: \f$y \mathrel{+}= \Delta t\, v\f$. @param dt time increment [s]
     */
    void
    drift(const double dt)
    {
      y += dt * v;
    }

    /** Work done on the system by the driver that prescribes the velocity
     * [J] (0 for a free projectile). */
    double
    external_work() const
    {
      return work;
    }

    /** Write the motion (position, velocity, work) to a checkpoint. */
    void
    save(Checkpoint::Writer &out) const;

    /** Read what save() wrote. */
    void
    load(Checkpoint::Reader &in);

  private:
    double m;
    double r;
    double y0;
    double y;
    double v;
    bool is_prescribed;
    Parameters::ProjectileShape shape_;
    double x0, z0;
    double work = 0.;
  };
} // namespace YarnImpact

#endif
