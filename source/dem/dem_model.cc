// The DEM yarn: fibres as chains of spheres joined by trusses, with
// penalty contacts (doc/dem.md). This file only orchestrates: each step
// lives in its own file (doc/architecture.md lists them). Everything that
// runs every step is a plain loop over contiguous arrays: no allocation,
// maps or virtual calls.

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>

#include "dem_model_implementation.h"

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      namespace
      {
        constexpr double infinity = std::numeric_limits<double>::infinity();
      }


      Model::Model(const YarnImpact::Parameters::Shared &shared_parameters,
                   const Parameters &parameters,
                   const MPI_Comm communicator)
        : shared(shared_parameters)
        , prm(parameters)
        , chains(shared, prm)
        , decomposition(prm, chains, communicator)
        , lists(prm, shared, chains, decomposition, spheres.pos)
        , list_check(prm, chains, decomposition, spheres.pos)
        // Contact laws (doc/dem.md section 2).
        , fibre_law(fibre_contact_law(prm, chains.truss_k, chains.sphere_mass))
        , projectile_law(prm.projectile_contact_law)
        , projectile_constants(projectile_contact_constants(prm,
                                                            chains.truss_k,
                                                            chains.sphere_mass))
        , meter(chains,
                decomposition,
                spheres,
                lists,
                fibre_law,
                projectile_law,
                projectile_constants)
        // Stable step (doc/theory.md 3.2): Gershgorin bound of a sphere with
        // two trusses, `coordination` fibre contacts and the projectile,
        // reduced for the contact damping.
        , critical_step(
            critical_time_step(prm, chains.truss_k, chains.sphere_mass))
        , contact_step(chains,
                       fibre_law.k_n,
                       fibre_law.k_t,
                       projectile_constants)
        , failure(shared.yarn.failure)
        , failure_strain(shared.yarn.failure_strain)
        , phase_timer(prm.phase_timing)
      {}


      double
      Model::stable_time_step() const
      {
        double critical = critical_step;
        if (prm.stable_step == StableStep::contacts)
          {
            PhaseTimer::Scope scope(phase_timer, PhaseTimer::stable_step);
            const double omega2 =
              contact_step.omega2_bound(decomposition,
                                        lists.blocks,
                                        spheres,
                                        projectile_contact.yc,
                                        projectile_contact.Rr,
                                        projectile_margin());
            if (omega2 > 0.)
              {
                // Damping lowers the step as in the scalar bound. The step
                // is rounded down to 10 significant bits: the bound's sums
                // may differ in their last bits with the partition, and the
                // step must not (the same history on any number of ranks).
                const double dt =
                  2. / std::sqrt(omega2) * damping_step_factor(prm);
                int e;
                std::frexp(dt, &e);
                const double q = std::ldexp(1., e - 11);
                critical       = std::floor(dt / q) * q;
              }
          }
        // The contact bound holds while a sphere meets the projectile over
        // many steps: a fast projectile must not close more than a tenth of
        // a sphere radius in one step, or it would jump over spheres (it
        // binds above about 510 m/s with the contacts step of the paper's
        // case, 700 m/s with the scalar one; doc/dem.md section 3).
        if (projectile_speed > 0.)
          return std::min(critical, 0.1 * chains.radius / projectile_speed);
        return critical;
      }


      double
      Model::projectile_margin() const
      {
        // What the projectile closes in two update intervals at the step
        // of the scalar bound (shorter than the step used), and at least a
        // tenth of a diameter.
        return std::max(0.1 * chains.d,
                        2. * projectile_speed *
                          shared.time.time_step_update_interval *
                          critical_step);
      }


      AxialProperties
      Model::axial_properties() const
      {
        AxialProperties a;
        a.area           = chains.nf_whole * chains.fibre_area;
        a.density        = shared.yarn.fibre_density;
        a.modulus        = shared.yarn.fibre_modulus;
        const double E   = a.modulus;
        a.nominal_stress = [E](const double e) { return E * e; };
        return a;
      }


      void
      Model::setup(const Projectile &projectile, std::ostream &out)
      {
        projectile_speed          = std::abs(projectile.velocity());
        const std::size_t n_local = decomposition.n_local;
        const unsigned int n_st   = chains.n_st;
        spheres.pos.assign(3 * n_local, 0.);
        spheres.vel.assign(3 * n_local, 0.);
        spheres.force.assign(3 * n_local, 0.);
        spheres.broken.assign(n_local, 0);
        spheres.projectile_tangential_displacement.assign(3 * n_local, 0.);
        spheres.proj_step.assign(n_local, 0);
        spheres.dissipated.assign(n_local, 0.);
        spheres.break_time.assign(n_local, 0.);
        spheres.st_xlo.assign(n_st, infinity);
        spheres.st_xhi.assign(n_st, -infinity);
        spheres.st_ymax.assign(n_st, -infinity);
        for (unsigned int s = decomposition.lo; s < decomposition.hi; ++s)
          for (unsigned int f = 0; f < chains.nf; ++f)
            {
              const std::size_t i    = decomposition.local_index(s, f);
              spheres.pos[3 * i]     = chains.station_x0[s];
              spheres.pos[3 * i + 1] = chains.fibre_y0[f];
              spheres.pos[3 * i + 2] = chains.fibre_z0[f];
            }
        for (unsigned int s = decomposition.st_begin; s < decomposition.st_end;
             ++s)
          compute_station_extents(chains, decomposition, spheres, s);
        meter.record_initial_width();

        // The first lists, then those of the blocks whose cross-sections
        // changed with the first locality check (storage holds the initial
        // positions of every station).
        for (ListBlock &B : lists.blocks)
          if (B.active())
            lists.rebuild(B);
        check_locality();
        update_lists(false);
        spheres.forces_consumed = true;

        const double E0 = 0.5 * projectile.mass() * projectile.velocity() *
                          projectile.velocity();
        if (decomposition.rank == 0)
          {
            const unsigned long n_pairs = lists.n_listed_pairs();
            out << std::setprecision(5) << "[dem] " << chains.nf_whole
                << " fibres (hexagonal packing scale " << chains.packing_scale
                << "), " << chains.n_whole_stations
                << " spheres per fibre, spacing " << chains.L0 * 1e6
                << " um; modelled: " << chains.nf << " fibres x " << n_st
                << " cross-sections = "
                << static_cast<unsigned long>(chains.nf) * n_st
                << " spheres on " << decomposition.n_ranks << " rank(s)\n"
                << "[dem] sphere mass " << chains.sphere_mass << " kg, truss "
                << "stiffness " << chains.truss_k << " N/m, contact stiffness "
                << fibre_law.k_n << " N/m (projectile "
                << projectile_constants.stiffness
                << " N/m), rank 0 pairs listed " << n_pairs
                << ", initial projectile energy " << E0 * 1e3 << " mJ\n";
          }
      }


      bool
      Model::check_locality()
      {
        // The global x-extent of every cross-section is identical on all
        // ranks, so a failure or a growth below is collective.
        const std::vector<double> *lo_x = nullptr, *hi_x = nullptr;
        {
          PhaseTimer::Scope scope(phase_timer, PhaseTimer::communication);
          decomposition.global_extents(spheres.st_xlo,
                                       spheres.st_xhi,
                                       lo_x,
                                       hi_x);
        }
        PhaseTimer::Scope scope(phase_timer, PhaseTimer::list_checks);
        check_symmetry_plane(chains, *lo_x);
        lists.grow_halos(*lo_x, *hi_x);
        if (!decomposition.grow_ghost_layers(*lo_x, *hi_x))
          return false;
        lists.set_block_ranges();
        return true;
      }


      void
      Model::update_lists(const bool check_criterion)
      {
        bool must_rebuild;
        {
          PhaseTimer::Scope scope(phase_timer, PhaseTimer::list_checks);
          must_rebuild = lists.evaluate_criteria(check_criterion);
        }
        PhaseTimer::Scope scope(phase_timer, PhaseTimer::list_rebuilds);
        const unsigned long blocks0  = lists.n_rebuilds,
                            rows0    = lists.rebuilt_rows,
                            partial0 = lists.n_partial,
                            fast0    = lists.partial_spheres;
        if (check_criterion &&
            prm.list_rebuilds == Parameters::ListRebuilds::missed_contact)
          list_check.rebuild_on_missed_contacts(lists, spheres.step_count);
        else
          lists.rebuild_failing(must_rebuild, check_criterion);
        phase_timer.count_rebuilds(lists.n_rebuilds - blocks0,
                                   lists.rebuilt_rows - rows0,
                                   lists.n_partial - partial0,
                                   lists.partial_spheres - fast0);
      }


      double
      Model::compute_forces(const Projectile &projectile, const double dt)
      {
        projectile_speed = std::abs(projectile.velocity());
        ++spheres.step_count;
        phase_timer.count_step(dt);
        {
          PhaseTimer::Scope scope(phase_timer, PhaseTimer::communication);
          decomposition.exchange_ghosts(spheres.pos);
          decomposition.exchange_ghosts(spheres.vel);
        }
        {
          PhaseTimer::Scope scope(phase_timer, PhaseTimer::list_checks);
          lists.accumulate_ghost_criteria();
        }
        if (check_locality())
          {
            // New ghost cross-sections: fetch them; every block is stale.
            PhaseTimer::Scope scope(phase_timer, PhaseTimer::communication);
            decomposition.exchange_ghosts(spheres.pos);
            decomposition.exchange_ghosts(spheres.vel);
          }
        update_lists(true);
        if (prm.check_lists)
          {
            PhaseTimer::Scope scope(phase_timer, PhaseTimer::list_checks);
            list_check.check(lists, spheres.step_count);
          }

        const double *x = spheres.pos.data();
        const double *v = spheres.vel.data();
        double *F       = spheres.force.data();
        // The energy dissipated, added to each sphere's account.
        double *dissipated = spheres.dissipated.data();
        {
          PhaseTimer::Scope scope(phase_timer, PhaseTimer::trusses);
          clear_forces(decomposition, spheres);
          truss_forces(chains,
                       decomposition,
                       failure,
                       failure_strain,
                       x,
                       F,
                       spheres.broken.data(),
                       spheres.time,
                       spheres.break_time.data(),
                       dissipated);
        }
        {
          PhaseTimer::Scope scope(phase_timer, PhaseTimer::pair_contacts);
          fibre_contact_forces(lists.blocks,
                               fibre_law,
                               chains.d,
                               decomposition,
                               x,
                               v,
                               F,
                               dt,
                               dissipated);
          mirror_contact_forces(lists.blocks,
                                fibre_law,
                                chains.d,
                                decomposition,
                                x,
                                v,
                                F,
                                dt,
                                dissipated);
        }
        double reaction;
        {
          PhaseTimer::Scope scope(phase_timer, PhaseTimer::projectile_contact);
          reaction = projectile_contact_forces(projectile,
                                               projectile_law,
                                               projectile_constants,
                                               chains,
                                               decomposition,
                                               spheres,
                                               dt,
                                               projectile_contact);
        }
        if (decomposition.n_ranks > 1)
          {
            PhaseTimer::Scope scope(phase_timer, PhaseTimer::communication);
            reaction =
              dealii::Utilities::MPI::sum(reaction, decomposition.comm);
          }
        // The first contact, on every rank alike (the reaction is reduced).
        if (reaction != 0.)
          phase_timer.advance_to(1);
        return chains.factor * reaction;
      }


      std::string
      Model::remarks() const
      {
        const MPI_Comm comm = decomposition.comm;
        std::ostringstream s;
        s << list_check.remarks(lists, spheres.step_count);
        const char *separator = (s.tellp() > 0 ? "\n  " : "");
        if (phase_timer.enabled)
          {
            s << separator << phase_timer.report(comm);
            separator = "\n  ";
          }
        const std::string ghosts = decomposition.remarks();
        if (!ghosts.empty())
          s << separator << ghosts;
        return s.str();
      }
    } // namespace internal


    using internal::Model;


    CouplingView
    coupling_view(ImpactModel &model)
    {
      Model *dem = dynamic_cast<Model *>(&model);
      if (dem == nullptr)
        throw std::logic_error("DEM::coupling_view: not a DEM model");
      return dem->coupling_view();
    }


    std::string
    statistics(const ImpactModel &model)
    {
      const auto *m = dynamic_cast<const Model *>(&model);
      return m ? m->statistics() : std::string();
    }


    std::unique_ptr<ImpactModel>
    create_model(const YarnImpact::Parameters::Shared &shared,
                 const Parameters &parameters,
                 const MPI_Comm communicator)
    {
      return std::make_unique<Model>(shared, parameters, communicator);
    }
  } // namespace DEM
} // namespace YarnImpact
