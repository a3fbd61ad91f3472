#ifndef yarn_impact_core_impact_model_h
#define yarn_impact_core_impact_model_h

#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/observables.h>

#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace YarnImpact
{
  class Projectile;

  /**
   * What Smith theory and the model-consistency report need to know about a
   * model's yarn along its axis.
   */
  struct AxialProperties
  {
    /** Reference area that carries the axial stress [m^2]. */
    double area = 0.;
    /** Density of that area's material [kg/m^3]. */
    double density = 0.;
    /** Small-strain axial modulus [Pa]. */
    double modulus = 0.;
    /** Uniaxial nominal (first Piola-Kirchhoff) stress as a function of the
     * engineering strain, \f$P(\varepsilon)\f$ [Pa]. */
    std::function<double(double)> nominal_stress;

    /** Mass per unit length \f$\rho A\f$ [kg/m]. */
    double
    mass_per_length() const
    {
      return density * area;
    }
    /** Axial stiffness \f$EA\f$ [N]. */
    double
    axial_stiffness() const
    {
      return modulus * area;
    }
  };

  /**
   * The interface every yarn model implements so that ImpactSimulation can
   * drive it (doc/theory.md section 3.1). The only caller of the step
   * phases is advance() (core/time_stepping.h), which makes one velocity
   * Verlet step with the projectile beside the model:
   *
   * @code
   * kick(dt/2); drift(dt); F = compute_forces(projectile, dt); kick(dt/2);
   * @endcode
   *
   * Every step calls the phases in this order, and a model may rely on it
   * and on nothing else:
   * - after setup(), compute_forces() is called once before the first
   *   step;
   * - kick() is a velocity update with the forces of the last
   *   compute_forces(). A model may defer it: record it and apply it at
   *   the next drift(), fused with the position update (the DEM does, one
   *   pass over memory instead of two). Whatever it defers, observables()
   *   and write_snapshot() report the velocities as if it had been
   *   applied;
   * - drift() applies every deferred kick, then moves the positions; it
   *   may also prepare the next compute_forces() from the new positions
   *   (the DEM zeroes the forces it has consumed, and updates its section
   *   extents and neighbour-list criterion on the way);
   * - compute_forces() follows every drift() and leaves what the next
   *   kick() needs.
   *
   * observables(), write_snapshot(), stable_time_step() and save_state()
   * may be called between steps (after the second kick), never inside one. All
   * functions are collective over the model's MPI communicator.
   */
  class ImpactModel
  {
  public:
    virtual ~ImpactModel() = default;

    /** Short name, used in file names and column headers ("fe", "dem"). */
    virtual std::string
    name() const = 0;

    /**
     * Build the discretisation (mesh or particles), the masses and all
     * other data, and compute the forces of the initial state.
     * @param projectile the projectile at t = 0
     * @param out stream for the set-up report (only rank 0 writes)
     */
    virtual void
    setup(const Projectile &projectile, std::ostream &out) = 0;

    /** Highest y coordinate of the discretised yarn at t = 0 (after
     * setup()): the projectile starts touching it [m]. */
    virtual double
    yarn_top() const = 0;

    /** Critical (largest stable) time step of the current configuration,
     * before the safety factor [s]. */
    virtual double
    stable_time_step() const = 0;

    /**
     * Compute internal and contact forces at the current positions, and the
     * accelerations that the next kick uses.
     * @param projectile the projectile at its current position and velocity
     * @param dt the current time step, for the work of friction and damping [s]
     * @return force of the whole yarn on the projectile along y [N]
     */
    virtual double
    compute_forces(const Projectile &projectile, const double dt) = 0;

    /** Velocity update \f$v \mathrel{+}= \Delta t\, a\f$ with the
     * accelerations of the last compute_forces(); may be deferred to the
     * next drift() (see the class documentation). @param dt [s] */
    virtual void
    kick(const double dt) = 0;

    /** Apply the deferred kicks, if any, then the position update
     * \f$x \mathrel{+}= \Delta t\, v\f$; may prepare the next
     * compute_forces() (see the class documentation). @param dt [s] */
    virtual void
    drift(const double dt) = 0;

    /** Observables of the current state, cut-through and station profile
     * included (collective). Calling it or not changes nothing in the
     * steps that follow. */
    virtual Observables
    observables() const = 0;

    /** Axial properties for Smith theory and the consistency report. */
    virtual AxialProperties
    axial_properties() const = 0;

    /** Mass of the whole yarn as discretised [kg]. */
    virtual double
    mass() const = 0;

    /**
     * Write a snapshot: `<directory>/<name>_<index>.pvtu` with its `.vtu`
     * pieces.
     * @return the file name of the record, relative to @p directory
     */
    virtual std::string
    write_snapshot(const std::string &directory,
                   const unsigned int index,
                   const double time) const = 0;

    /** Number of cells (FE) or spheres (DEM) of the whole discretisation,
     * for throughput figures. */
    virtual unsigned long
    n_elements() const = 0;

    /**
     * Write this rank's whole state between two steps to a checkpoint:
     * everything that the next steps, observables(), write_snapshot() and
     * remarks() read and that setup() does not rebuild identically, so
     * that a model set up anew and given load_state() makes bitwise the
     * steps this one would make.
     */
    virtual void
    save_state(Checkpoint::Writer &out) const = 0;

    /** Read what save_state() wrote, after setup() (collective where the
     * model needs it, e.g. to refresh ghost values). */
    virtual void
    load_state(Checkpoint::Reader &in) = 0;

    /** Every fibre break so far, in the order of break_less(), the same on
     * every rank, if the model records them (the run then writes them to
     * `breaks_<name>.csv`); none by default (collective). */
    virtual std::optional<std::vector<FibreBreak>>
    fibre_breaks() const
    {
      return std::nullopt;
    }

    /** The names, with their units, of the model's own history columns,
     * written after the common ones (doc/user-guide.md, "History
     * columns"), whose values observables() gives in
     * Observables::extra_columns, in this order and in these units; none
     * by default. */
    virtual std::vector<std::string>
    extra_column_names() const
    {
      return {};
    }

    /** Whether the model has FE cells that it erodes when they are
     * crushed, inverted or not finite (Observables::n_eroded); the run
     * summary then gives them a line of their own. None by default. */
    virtual bool
    erodes_cells() const
    {
      return false;
    }

    /** Whether the model is one yarn struck across, the set-up that the
     * verification window's Smith quantities describe (a woven patch is
     * not); true by default. */
    virtual bool
    single_yarn() const
    {
      return true;
    }

    /** Model-specific remarks for the run summary (e.g. how the DEM's MPI
     * ghost layers grew); empty by default. Must be identical on all
     * ranks. */
    virtual std::string
    remarks() const
    {
      return {};
    }
  };
} // namespace YarnImpact

#endif
