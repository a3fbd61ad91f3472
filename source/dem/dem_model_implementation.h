// The DEM impact model's class, private to source/dem: its set-up and step
// are in dem_model.cc, each step's work in its own file.

#ifndef yarn_impact_dem_dem_model_implementation_h
#define yarn_impact_dem_dem_model_implementation_h

#include <yarn_impact/contact/contact_law.h>
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/dem/decomposition.h>
#include <yarn_impact/dem/dem_model.h>
#include <yarn_impact/dem/fibre_chains.h>
#include <yarn_impact/dem/forces.h>
#include <yarn_impact/dem/integration.h>
#include <yarn_impact/dem/list_check.h>
#include <yarn_impact/dem/neighbour_lists.h>
#include <yarn_impact/dem/observables.h>
#include <yarn_impact/dem/phase_timer.h>
#include <yarn_impact/dem/spheres.h>
#include <yarn_impact/dem/stable_step.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      /**
       * The DEM impact model: the parts of internal (layout, decomposition,
       * state, lists, list check, observables) and the steps that use them.
       */
      class Model : public ImpactModel
      {
      public:
        Model(const YarnImpact::Parameters::Shared &shared_parameters,
              const Parameters &parameters,
              const MPI_Comm communicator);

        std::string
        name() const override
        {
          return chains.clamp_part ? "dem_clamp" : "dem";
        }

        void
        setup(const Projectile &projectile, std::ostream &out) override;

        double
        stable_time_step() const override;

        double
        yarn_top() const override
        {
          // The highest sphere surface of the packing: the projectile starts
          // touching it. Every rank holds the whole fibre layout.
          double top = -std::numeric_limits<double>::max();
          for (const double y : chains.fibre_y0)
            top = std::max(top, y + chains.radius);
          return top;
        }

        double
        compute_forces(const Projectile &projectile, const double dt) override;

        void
        kick(const double dt) override
        {
          // Deferred, as the contract allows: applied in the next drift,
          // fused with it (one pass over memory instead of two);
          // observables and snapshots add it on the fly.
          spheres.pending_kick += dt;
        }

        void
        drift(const double dt) override
        {
          PhaseTimer::Scope scope(phase_timer, PhaseTimer::integration);
          internal::drift(chains, decomposition, lists, spheres, dt);
          spheres.time += dt;
        }

        Observables
        observables() const override
        {
          Observables o = meter.measure(projectile_contact);
          // The timing table's phases (whole-yarn counts, alike on all ranks).
          phase_timer.advance_to(o.cut_through ? 3 : o.n_failed > 0 ? 2 : 0);
          return o;
        }

        AxialProperties
        axial_properties() const override;

        double
        mass() const override
        {
          return chains.total_mass;
        }

        std::string
        write_snapshot(const std::string &directory,
                       const unsigned int index,
                       const double) const override
        {
          return internal::write_snapshot(chains,
                                          decomposition,
                                          spheres,
                                          directory,
                                          index);
        }

        unsigned long
        n_elements() const override
        {
          return static_cast<unsigned long>(chains.nf_whole) *
                 chains.n_whole_stations;
        }

        std::string
        remarks() const override;

        void
        save_state(Checkpoint::Writer &out) const override
        {
          out.tag("dem model");
          out.put(projectile_speed);
          out.put(projectile_contact);
          decomposition.save(out);
          spheres.save(out);
          lists.save(out);
          list_check.save(out);
        }

        void
        load_state(Checkpoint::Reader &in) override
        {
          in.tag("dem model");
          in.get(projectile_speed);
          in.get(projectile_contact);
          decomposition.load(in);
          spheres.load(in);
          lists.load(in);
          list_check.load(in);
        }

        /** Counters for the benchmark (collective). */
        std::string
        statistics() const
        {
          return lists.statistics(spheres.step_count);
        }

        std::optional<std::vector<FibreBreak>>
        fibre_breaks() const override
        {
          return gather_fibre_breaks(chains, decomposition, spheres);
        }

        /** See DEM::coupling_view(). */
        CouplingView
        coupling_view()
        {
          CouplingView v;
          v.n_fibres      = chains.nf;
          v.n_stations    = chains.n_st;
          v.station_begin = decomposition.st_begin;
          v.station_end   = decomposition.st_end;
          v.station_x     = &chains.station_x0;
          v.fibre_y       = &chains.fibre_y0;
          v.fibre_z       = &chains.fibre_z0;
          v.position      = spheres.pos.data();
          v.velocity      = spheres.vel.data();
          v.force         = spheres.force.data();
          v.broken        = spheres.broken.data();
          v.local_index   = [this](const unsigned int s, const unsigned int f) {
            return decomposition.local_index(s, f);
          };
          v.inverse_mass = [this](const unsigned int s, const unsigned int f) {
            return chains.fibre_inverse_mass[f] *
                   chains.station_inverse_mass_factor[s];
          };
          v.sphere_radius        = chains.radius;
          v.projectile_law       = projectile_law;
          v.projectile_constants = projectile_constants;
          return v;
        }

      private:
        /** Gap below which a sphere counts as touching the projectile in
         * the stable step [m]. */
        double
        projectile_margin() const;

        /** Grow the list halos and the ghost layers to the stations that
         * came near (collective); whether the ghost layers grew. */
        bool
        check_locality();
        /** Rebuild the lists of the blocks that are stale or whose criterion
         * fails (when @p check_criterion), or that miss a contact (`DEM/List
         * rebuilds = missed contact`). */
        void
        update_lists(const bool check_criterion);

        const YarnImpact::Parameters::Shared shared;
        const Parameters prm;
        const FibreChains chains;
        Decomposition decomposition;
        Spheres spheres;
        NeighbourLists lists;
        ListCheck list_check;
        const FibreContactLaw fibre_law;
        /** The projectile's contact law (`Projectile contact law`) and its
         * constants. */
        const Contact::LawType projectile_law;
        const Contact::ContactConstants projectile_constants;
        ObservablesMeter meter;
        /** The scalar bound with `Coordination number` contacts [s]. */
        const double critical_step;
        /** The bound from the springs there are (`Stable time step =
         * contacts`). */
        const ContactStableStep contact_step;
        /** Projectile speed at the last set-up or force evaluation [m/s]. */
        double projectile_speed = 0.;
        const bool failure;
        const double failure_strain;

        /** Where the projectile was at the last force evaluation. */
        ProjectileContactState projectile_contact;
        /** The parts of the step by phase (`Phase timing`); mutable: the
         * const observables() and stable_time_step() are timed or move
         * the phase on. */
        mutable PhaseTimer phase_timer;
      };
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
