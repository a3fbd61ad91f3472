#ifndef yarn_impact_fe_extra_forces_h
#define yarn_impact_fe_extra_forces_h

#include <yarn_impact/core/checkpoint.h>

#include <mpi.h>

#include <string>
#include <vector>

namespace YarnImpact
{
  namespace FE
  {
    /**
     * Forces that a model made of FE yarns adds on the FE model's nodes,
     * beside the cells' and the projectile's (FE::Parameters::extra_forces;
     * `Model = fabric`: the contact of crossing yarns, doc/fabric.md). The
     * FE model calls it at its set-up, in every compute_forces() after the
     * projectile contact, in its stable step, observables and checkpoint,
     * so that its work, energy and step enter the run like the FE's own.
     * Every function is collective over the model's communicator.
     */
    class ExtraForces
    {
    public:
      virtual ~ExtraForces() = default;

      /**
       * Once, at the end of the FE set-up: @p reference holds the
       * reference positions [m] of this rank's owned nodes, 3 each.
       * @return the indices (into those nodes) of the nodes it acts on,
       * in the order in which add_forces() takes them
       */
      virtual std::vector<unsigned int>
      setup(const std::vector<double> &reference,
            const MPI_Comm communicator) = 0;

      /** Add the forces [N] on the nodes of setup(), 3 each, to @p force,
       * at their current positions @p x [m] and velocities @p v [m/s] (3
       * each), over the step @p dt [s]. */
      virtual void
      add_forces(const std::vector<double> &x,
                 const std::vector<double> &v,
                 const double dt,
                 std::vector<double> &force) = 0;

      /**
       * The cells that have stopped carrying stress (broken or eroded,
       * FE::CellState) among this rank's owned cells, each given by the
       * reference positions [m] of its 8 vertices in deal.II's order
       * (24 values a cell, in @p cells): in every step, before
       * add_forces(), those that failed in it (@p restored false), and
       * once after a restart, before the first step, every failed cell
       * (@p restored true). Collective. Forces that act on a surface use
       * it to leave out the faces of such cells (the eroding contact of
       * explicit codes); the default ignores them.
       */
      virtual void
      remove_cells(const std::vector<double> &cells, const bool restored)
      {
        (void)cells;
        (void)restored;
      }

      /** Largest stable step [s] of its springs alone; the FE model adds
       * its squared frequency to its own: 1/dt^2 = 1/dt_e^2 + 1/dt_c^2. */
      virtual double
      stable_time_step() const = 0;

      /** Energy stored [J] at the last add_forces(), whole model,
       * independent of the partition. */
      virtual double
      energy() const = 0;

      /** Energy dissipated so far [J], whole model, independent of the
       * partition. */
      virtual double
      dissipated() const = 0;

      /** Write this rank's state to a checkpoint. */
      virtual void
      save(Checkpoint::Writer &out) const = 0;

      /** Read what save() wrote, after setup(). */
      virtual void
      load(Checkpoint::Reader &in) = 0;

      /** One line or more for the set-up report, each ending in a newline
       * (the same on every rank). */
      virtual std::string
      report() const = 0;
    };
  } // namespace FE
} // namespace YarnImpact

#endif
