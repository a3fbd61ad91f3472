// The hybrid yarn's model class, private to source/coupling: its step and
// outputs are in hybrid_model.cc, its patch test in hybrid_patch_test.cc.

#ifndef yarn_impact_coupling_hybrid_model_implementation_h
#define yarn_impact_coupling_hybrid_model_implementation_h

#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/output_file.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/core/yarn_section.h>
#include <yarn_impact/coupling/bridging_domain.h>
#include <yarn_impact/coupling/fibre_bars.h>
#include <yarn_impact/coupling/hybrid_model.h>
#include <yarn_impact/coupling/hybrid_parts.h>
#include <yarn_impact/coupling/overlap.h>
#include <yarn_impact/dem/dem_model.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/mpi.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>

namespace YarnImpact
{
  namespace Coupling
  {
    namespace internal
    {
      /**
       * The hybrid yarn: the parts, and the coupling applied after all
       * have computed their forces (doc/hybrid.md section 3).
       */
      class HybridModel : public ImpactModel
      {
      public:
        HybridModel(const YarnImpact::Parameters::Shared &shared,
                    const FE::Parameters &fe,
                    const DEM::Parameters &dem,
                    const HybridParameters &hybrid,
                    const MPI_Comm communicator)
          : shared(shared)
          , fe_parameters(fe)
          , layout(hybrid_layout(shared, fe, dem, hybrid))
          , communicator(communicator)
        {
          HybridParts parts = hybrid_parts(shared, fe, dem, layout);
          if (!layout.fibre_bars)
            parts.fe.section_quadrature_factor =
              section_quadrature(shared, fe, dem);
          dem_shared = parts.dem_shared;
          fe_shared  = parts.fe_shared;
          fe_model   = FE::create_model(fe_shared, parts.fe, communicator);
          dem_model  = DEM::create_model(dem_shared, parts.dem, communicator);
          nose.z_symmetry = clamp.z_symmetry = quarter();
          nose.dem_part                      = dem_model.get();
          nose.x_begin                       = layout.overlap_begin;
          nose.station_begin                 = layout.first_coupled_station;
          nose.station_end                   = layout.dem_trusses + 1;
          if (layout.fibre_bars)
            nose.bars = &bars;
          nose.transverse_modes = left.transverse_modes =
            hybrid.transverse_modes;
          if (layout.whole)
            {
              // The side x < 0 as the mirror image of the side x > 0: the
              // same FE part and bars, reflected where they meet the DEM
              // part (Overlap::mirrored) and where they are written.
              FE::Parameters mirror = parts.fe;
              mirror.mirrored       = true;
              mirror.snapshot_name  = "fe_left";
              left_fe_model = FE::create_model(fe_shared, mirror, communicator);
              nose.station_begin += layout.dem_trusses;
              nose.station_end += layout.dem_trusses;
              left.dem_part      = dem_model.get();
              left.mirrored      = true;
              left.x_begin       = layout.overlap_begin;
              left.station_begin = 0;
              left.station_end = layout.overlap_cells * layout.cell_trusses + 1;
              if (layout.fibre_bars)
                {
                  left.bars          = &left_bars;
                  left_bars.mirrored = true;
                }
            }
          if (layout.clamp_cells > 0)
            {
              clamp_model =
                DEM::create_model(shared, parts.dem_clamp, communicator);
              clamp.dem_part      = clamp_model.get();
              clamp.x_begin       = layout.clamp_begin;
              clamp.station_begin = 0;
              clamp.station_end =
                layout.overlap_cells * layout.cell_trusses + 1;
              // Under fibre bars the clamp part's spheres are tied to the
              // bars' last nodes in x, to the continuum in y and z.
              if (layout.fibre_bars)
                clamp.bars = &bars;
            }
        }

        std::string
        name() const override
        {
          return "hybrid";
        }

        void
        setup(const Projectile &projectile, std::ostream &out) override;

        /** The yarn's momentum along the impact direction, all parts
         * together (Observables::momentum; the fibre bars move along x
         * only), which with the projectile's is conserved until a wave
         * reaches a clamp [kg m/s]; then each part's energy balance
         * (doc/hybrid.md 2.3): the energy of the FE part (with its fibre
         * bars) and of the DEM part(s), each kinetic, elastic, contact
         * and dissipated, the work done by the FE part on the DEM part(s)
         * through the overlaps and the projectile's work on the FE part
         * (its contact after the cut) [mJ]. */
        std::vector<std::string>
        extra_column_names() const override
        {
          return {"yarn momentum [kg m/s]",
                  "FE part energy [mJ]",
                  "DEM part energy [mJ]",
                  "coupling work on the DEM part [mJ]",
                  "projectile work on the FE part [mJ]"};
        }

        double
        yarn_top() const override
        {
          return dem_model->yarn_top();
        }

        double
        stable_time_step() const override
        {
          double dt = std::min(fe_model->stable_time_step(),
                               dem_model->stable_time_step());
          if (clamp_model)
            dt = std::min(dt, clamp_model->stable_time_step());
          if (layout.fibre_bars)
            dt = std::min(dt, bars.stable_time_step());
          if (left_fe_model)
            dt = std::min(dt, left_fe_model->stable_time_step());
          if (left_fe_model && layout.fibre_bars)
            dt = std::min(dt, left_bars.stable_time_step());
          return dt;
        }

        double
        compute_forces(const Projectile &projectile, const double dt) override
        {
          if (layout.fibre_bars)
            bars.set_continuum_axial(*fe_model);
          double f_fe = fe_model->compute_forces(projectile, dt);
          if (layout.fibre_bars)
            f_fe +=
              symmetry() *
              bars.compute_forces(*fe_model, projectile, dt, communicator);
          double f_left = 0.;
          if (left_fe_model)
            {
              if (layout.fibre_bars)
                left_bars.set_continuum_axial(*left_fe_model);
              f_left = left_fe_model->compute_forces(projectile, dt);
              if (layout.fibre_bars)
                f_left += left_bars.compute_forces(*left_fe_model,
                                                   projectile,
                                                   dt,
                                                   communicator);
            }
          const double f_dem = dem_model->compute_forces(projectile, dt);
          // The FE part's force on the projectile does work on it at the
          // step's mid velocity, averaged over the step's two ends as the
          // kicks apply it (Verlet's trapezoid).
          fe_projectile_work -= 0.5 * (fe_projectile_force + f_fe + f_left) *
                                projectile.velocity() * dt;
          fe_projectile_force = f_fe + f_left;
          // Before the cut, a touch means fibres the DEM part should carry
          // would wrap the nose in the continuum; after it (every fibre
          // broken, which no later step undoes) the FE part's contact (its
          // surface's, or its fibre bars' nodes') is the model there
          // (doc/hybrid.md section 1).
          if ((f_fe != 0. || f_left != 0.) && fe_touch_displacement < 0.)
            {
              if (!every_fibre_broken())
                throw RunError(
                  "the projectile touches the FE part of the hybrid yarn "
                  "before the yarn is cut: raise Hybrid/DEM half-length");
              fe_touch_displacement = projectile.displacement();
            }
          if (clamp_model && clamp_model->compute_forces(projectile, dt) != 0.)
            throw RunError(
              "the projectile touches the DEM part at the clamp: lower "
              "Hybrid/Clamp DEM length");
          nose.couple(*fe_model, dt, communicator);
          if (left_fe_model)
            left.couple(*left_fe_model, dt, communicator);
          if (clamp_model)
            clamp.couple(*fe_model, dt, communicator);
          return f_fe + f_left + f_dem;
        }

        void
        kick(const double dt) override
        {
          fe_model->kick(dt);
          dem_model->kick(dt);
          if (clamp_model)
            clamp_model->kick(dt);
          if (layout.fibre_bars)
            bars.kick(dt);
          if (left_fe_model)
            left_fe_model->kick(dt);
          if (left_fe_model && layout.fibre_bars)
            left_bars.kick(dt);
        }

        void
        drift(const double dt) override
        {
          fe_model->drift(dt);
          dem_model->drift(dt);
          if (clamp_model)
            clamp_model->drift(dt);
          if (layout.fibre_bars)
            bars.drift(dt);
          if (left_fe_model)
            left_fe_model->drift(dt);
          if (left_fe_model && layout.fibre_bars)
            left_bars.drift(dt);
        }

        Observables
        observables() const override;

        AxialProperties
        axial_properties() const override
        {
          return dem_model->axial_properties();
        }

        double
        mass() const override
        {
          return fe_model->mass() + dem_model->mass() +
                 (clamp_model ? clamp_model->mass() : 0.) +
                 (left_fe_model ? left_fe_model->mass() : 0.);
        }

        std::string
        write_snapshot(const std::string &directory,
                       const unsigned int index,
                       const double time) const override;

        /** The FE part erodes its cells (doc/hybrid.md 3.4). */
        bool
        erodes_cells() const override
        {
          return true;
        }

        unsigned long
        n_elements() const override
        {
          return dem_model->n_elements() +
                 (clamp_model ? clamp_model->n_elements() : 0ul);
        }

        void
        save_state(Checkpoint::Writer &out) const override
        {
          out.tag("hybrid model");
          fe_model->save_state(out);
          dem_model->save_state(out);
          out.put(nose.work);
          out.put(nose.previous_node_multipliers);
          out.put(nose.previous_bar_multipliers);
          if (clamp_model)
            {
              clamp_model->save_state(out);
              out.put(clamp.work);
              out.put(clamp.previous_node_multipliers);
              out.put(clamp.previous_bar_multipliers);
            }
          if (layout.fibre_bars)
            bars.save_state(out);
          if (left_fe_model)
            {
              left_fe_model->save_state(out);
              out.put(left.work);
              out.put(left.previous_node_multipliers);
              out.put(left.previous_bar_multipliers);
              if (layout.fibre_bars)
                left_bars.save_state(out);
            }
          out.put(fe_touch_displacement);
          out.put(fe_projectile_force);
          out.put(fe_projectile_work);
        }

        void
        load_state(Checkpoint::Reader &in) override
        {
          in.tag("hybrid model");
          fe_model->load_state(in);
          dem_model->load_state(in);
          in.get(nose.work);
          in.get(nose.previous_node_multipliers);
          in.get(nose.previous_bar_multipliers);
          if (clamp_model)
            {
              clamp_model->load_state(in);
              in.get(clamp.work);
              in.get(clamp.previous_node_multipliers);
              in.get(clamp.previous_bar_multipliers);
            }
          if (layout.fibre_bars)
            bars.load_state(in);
          if (left_fe_model)
            {
              left_fe_model->load_state(in);
              in.get(left.work);
              in.get(left.previous_node_multipliers);
              in.get(left.previous_bar_multipliers);
              if (layout.fibre_bars)
                left_bars.load_state(in);
            }
          in.get(fe_touch_displacement);
          in.get(fe_projectile_force);
          in.get(fe_projectile_work);
        }

        /** The DEM parts' broken trusses (part "dem", and "clamp" for the
         * DEM part at the clamp) and the broken fibre bars ("bars"). */
        std::optional<std::vector<FibreBreak>>
        fibre_breaks() const override
        {
          std::vector<FibreBreak> breaks = *dem_model->fibre_breaks();
          if (clamp_model)
            {
              // Held here: a range-for over *fibre_breaks() would read the
              // temporary optional after its end.
              const std::optional<std::vector<FibreBreak>> at_clamp =
                clamp_model->fibre_breaks();
              for (FibreBreak b : *at_clamp)
                {
                  b.part = "clamp";
                  breaks.push_back(b);
                }
            }
          if (layout.fibre_bars)
            for (const FibreBreak &b : bars.fibre_breaks(communicator))
              breaks.push_back(b);
          if (left_fe_model && layout.fibre_bars)
            for (const FibreBreak &b : left_bars.fibre_breaks(communicator))
              breaks.push_back(b);
          std::sort(breaks.begin(), breaks.end(), break_less);
          return breaks;
        }

        std::string
        remarks() const override
        {
          std::ostringstream s;
          // Each part's remarks on lines of their own.
          auto lines = [&s](const std::string &text) {
            s << text;
            if (!text.empty() && text.back() != '\n')
              s << '\n';
          };
          lines(dem_model->remarks());
          if (clamp_model)
            if (const std::string at_clamp = clamp_model->remarks();
                !at_clamp.empty())
              lines("At the clamp: " + at_clamp);
          // The broken bars of a far field, per millimetre of |x|.
          const auto far_field = [&s](const FibreBars &b, const char *which) {
            s << "Hybrid far field" << which << ": " << b.n_broken()
              << " fibre bars broken";
            const std::vector<unsigned long> c = b.broken_per_millimetre();
            const char *separator = (b.mirrored ? " (|x|:" : " (x:");
            for (unsigned int mm = 0; mm < c.size(); ++mm)
              if (c[mm] > 0)
                {
                  s << separator << " " << c[mm] << " in " << mm << "-"
                    << mm + 1 << " mm";
                  separator = ",";
                }
            if (*separator == ',')
              s << ")";
            s << "\n";
          };
          if (layout.fibre_bars)
            far_field(bars, "");
          if (left_fe_model && layout.fibre_bars)
            far_field(left_bars, " at x < 0");
          if (fe_touch_displacement >= 0.)
            s << "Hybrid contact: the projectile touched the FE part after "
                 "the yarn was cut, at a projectile displacement of "
              << std::setprecision(6) << fe_touch_displacement * 1e3
              << " mm; the FE part's contact"
              << (layout.fibre_bars ? " (its fibre bars' nodes)" : "")
              << " acted from then on\n";
          for (const Overlap *o : overlaps())
            {
              const char *which = (o == &nose   ? ""
                                   : o == &left ? " at x < 0"
                                                : " at the clamp");
              s << "Hybrid coupling" << which
                << ": work done by the FE part on the DEM part through the "
                   "overlap "
                << std::setprecision(6) << symmetry() * o->work * 1e3
                << " mJ\n";
            }
          return s.str();
        }

        /** See Coupling::patch_test(). */
        double
        patch_test(const double strain);

      private:
        /** The overlaps in use: the one by the nose (on x > 0), and the
         * one at the clamp if there is a DEM part there, or the one on
         * x < 0 of a whole yarn. */
        std::vector<const Overlap *>
        overlaps() const
        {
          if (clamp_model)
            return {&nose, &clamp};
          if (left_fe_model)
            return {&nose, &left};
          return {&nose};
        }

        /** Whether the part modelled is the quarter z >= 0 of the half
         * x >= 0. */
        bool
        quarter() const
        {
          return shared.general.symmetry ==
                 YarnImpact::Parameters::Symmetry::quarter;
        }

        double
        symmetry() const
        {
          return YarnImpact::Parameters::symmetry_factor(
            shared.general.symmetry);
        }

        const YarnImpact::Parameters::Shared &shared;
        const FE::Parameters fe_parameters;
        const HybridLayout layout;
        const MPI_Comm communicator;
        /** The parts' problems (the FE model keeps a reference to its
         * own; the clamp part's is @p shared). */
        YarnImpact::Parameters::Shared dem_shared, fe_shared;
        std::unique_ptr<ImpactModel> fe_model, dem_model, clamp_model;
        Overlap nose, clamp;
        /** The far field's fibres, with Hybrid/Far field = fibre bars. */
        FibreBars bars;
        /** A whole yarn's side x < 0 (HybridLayout::whole; null model
         * otherwise): its FE part, overlap and bars, built as the mirror
         * images of those of x > 0. */
        std::unique_ptr<ImpactModel> left_fe_model;
        Overlap left;
        FibreBars left_bars;

        /** The projectile's displacement [m] at the first step it touched
         * the FE part, the yarn cut; from then on the FE part's contact
         * acts without a check (broken fibres stay broken). Negative
         * while it has not touched. */
        double fe_touch_displacement = -1.;

        /** The FE part's force on the projectile at the last step [N]
         * and the projectile's work on the FE part since the start [J]
         * (both of the whole yarn). */
        double fe_projectile_force = 0.;
        double fe_projectile_work  = 0.;

        /** Whether the yarn is cut: every fibre has a broken truss in a
         * DEM part or (under fibre bars) a broken bar (collective). */
        bool
        every_fibre_broken() const
        {
          const DEM::CouplingView dem = DEM::coupling_view(*dem_model);
          std::vector<double> broken(dem.n_fibres, 0.);
          const auto mark = [&broken](const DEM::CouplingView &part) {
            for (unsigned int s = part.station_begin;
                 s < std::min(part.station_end, part.n_stations - 1);
                 ++s)
              for (unsigned int f = 0; f < part.n_fibres; ++f)
                if (part.broken[part.local_index(s, f)])
                  broken[f] = 1.;
          };
          mark(dem);
          if (clamp_model)
            mark(DEM::coupling_view(*clamp_model));
          dealii::Utilities::MPI::max(broken, communicator, broken);
          for (unsigned int f = 0; f < dem.n_fibres; ++f)
            if (broken[f] == 0. &&
                !(layout.fibre_bars &&
                  (bars.fibre_broken(f) ||
                   (left_fe_model && left_bars.fibre_broken(f)))))
              return false;
          return dem.n_fibres > 0;
        }
      };
    } // namespace internal
  }   // namespace Coupling
} // namespace YarnImpact

#endif
