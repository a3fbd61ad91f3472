// The hybrid yarn (doc/hybrid.md): the DEM fibres where the yarn wraps the
// nose and breaks, the FE continuum elsewhere, coupled in an overlap by the
// bridging domain method: the model, its step and its outputs. Its
// parameters and parts are in hybrid_parameters.cc, the FE part's section
// quadrature in section_quadrature.cc.

#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/output_file.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/coupling/bridging_domain.h>
#include <yarn_impact/coupling/hybrid_model.h>
#include <yarn_impact/coupling/hybrid_parts.h>
#include <yarn_impact/coupling/overlap.h>
#include <yarn_impact/dem/dem_model.h>
#include <yarn_impact/fe/fe_model.h>
#include <yarn_impact/fe/yarn_mesh.h>

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
    using namespace dealii;


    namespace
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
          parts.fe.section_quadrature_factor =
            section_quadrature(shared, fe, dem);
          dem_shared = parts.dem_shared;
          fe_shared  = parts.fe_shared;
          fe_model   = FE::create_model(fe_shared, parts.fe, communicator);
          dem_model  = DEM::create_model(dem_shared, parts.dem, communicator);
          nose.dem_part      = dem_model.get();
          nose.x_begin       = layout.overlap_begin;
          nose.station_begin = layout.first_coupled_station;
          nose.station_end   = layout.dem_trusses + 1;
          if (layout.clamp_cells > 0)
            {
              clamp_model =
                DEM::create_model(shared, parts.dem_clamp, communicator);
              clamp.dem_part      = clamp_model.get();
              clamp.x_begin       = layout.clamp_begin;
              clamp.station_begin = 0;
              clamp.station_end =
                layout.overlap_cells * layout.cell_trusses + 1;
            }
        }

        std::string
        name() const override
        {
          return "hybrid";
        }

        void
        setup(const Projectile &projectile, std::ostream &out) override;

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
          return dt;
        }

        double
        compute_forces(const Projectile &projectile, const double dt) override
        {
          const double f_fe  = fe_model->compute_forces(projectile, dt);
          const double f_dem = dem_model->compute_forces(projectile, dt);
          if (f_fe != 0.)
            throw RunError(
              "the projectile touches the FE part of the hybrid yarn: raise "
              "Hybrid/DEM half-length");
          if (clamp_model && clamp_model->compute_forces(projectile, dt) != 0.)
            throw RunError(
              "the projectile touches the DEM part at the clamp: lower "
              "Hybrid/Clamp DEM length");
          nose.couple(*fe_model, dt, communicator);
          if (clamp_model)
            clamp.couple(*fe_model, dt, communicator);
          return f_fe + f_dem;
        }

        void
        kick(const double dt) override
        {
          fe_model->kick(dt);
          dem_model->kick(dt);
          if (clamp_model)
            clamp_model->kick(dt);
        }

        void
        drift(const double dt) override
        {
          fe_model->drift(dt);
          dem_model->drift(dt);
          if (clamp_model)
            clamp_model->drift(dt);
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
                 (clamp_model ? clamp_model->mass() : 0.);
        }

        std::string
        write_snapshot(const std::string &directory,
                       const unsigned int index,
                       const double time) const override;

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
          if (clamp_model)
            {
              clamp_model->save_state(out);
              out.put(clamp.work);
            }
        }

        void
        load_state(Checkpoint::Reader &in) override
        {
          in.tag("hybrid model");
          fe_model->load_state(in);
          dem_model->load_state(in);
          in.get(nose.work);
          if (clamp_model)
            {
              clamp_model->load_state(in);
              in.get(clamp.work);
            }
        }

        std::string
        remarks() const override
        {
          std::ostringstream s;
          s << dem_model->remarks();
          if (clamp_model)
            s << "At the clamp: " << clamp_model->remarks();
          for (const Overlap *o : overlaps())
            {
              const char *which = (o == &nose ? "" : " at the clamp");
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
        /** The overlaps in use: the one by the nose, and the one at the
         * clamp if there is a DEM part there. */
        std::vector<const Overlap *>
        overlaps() const
        {
          if (clamp_model)
            return {&nose, &clamp};
          return {&nose};
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
      };


      void
      HybridModel::setup(const Projectile &projectile, std::ostream &out)
      {
        fe_model->setup(projectile, out);
        dem_model->setup(projectile, out);
        if (clamp_model)
          clamp_model->setup(projectile, out);

        // The section the FE part was extruded from: its vertices are the
        // coupled nodes of each node layer of an overlap.
        Triangulation<2> section;
        FE::create_yarn_section(section,
                                shared.yarn.thickness_semi_axis,
                                shared.yarn.width_semi_axis,
                                fe_parameters.section_refinements,
                                false,
                                fe_parameters.preserve_section_area);
        nose.set_up(*fe_model, section, layout, shared.yarn, communicator);
        if (clamp_model)
          clamp.set_up(*fe_model, section, layout, shared.yarn, communicator);

        if (Utilities::MPI::this_mpi_process(communicator) == 0)
          {
            out << "[hybrid] DEM part |x| <= " << layout.dem_half_length * 1e3
                << " mm (" << layout.dem_trusses
                << " trusses per fibre), overlap " << layout.overlap_begin * 1e3
                << " to " << layout.dem_half_length * 1e3 << " mm ("
                << layout.overlap_cells << " FE cells of "
                << layout.cell_length * 1e3 << " mm = " << layout.cell_trusses
                << " trusses), FE part to ";
            if (clamp_model)
              out << layout.fe_end * 1e3 << " mm in " << layout.fe_cells
                  << " cells; DEM part at the clamp from "
                  << layout.clamp_begin * 1e3 << " mm (" << layout.clamp_trusses
                  << " trusses per fibre), overlap " << layout.clamp_begin * 1e3
                  << " to " << layout.fe_end * 1e3 << " mm; ";
            else
              out << "the clamp in " << layout.fe_cells << " cells; ";
            for (const Overlap *o : overlaps())
              out << o->constraint.n_nodes() << " coupled FE nodes, "
                  << o->constraint.n_particles() << " coupled spheres; ";
            out << "yarn mass " << mass() * 1e6 << " mg\n";
          }
      }


      double
      HybridModel::patch_test(const double strain)
      {
        std::vector<ImpactModel *> dem_parts = {dem_model.get()};
        if (clamp_model)
          dem_parts.push_back(clamp_model.get());
        {
          const FE::CouplingView fe = FE::coupling_view(*fe_model);
          for (const auto &node : *fe.nodes)
            for (unsigned int d = 0; d < 3; ++d)
              {
                fe.displacement[node[d]] =
                  d == 0 ? strain * (*fe.reference_coordinate)[node[0]] : 0.;
                fe.velocity[node[d]] = 0.;
              }
          for (ImpactModel *part : dem_parts)
            {
              const DEM::CouplingView dem = DEM::coupling_view(*part);
              for (unsigned int s = dem.station_begin; s < dem.station_end; ++s)
                for (unsigned int f = 0; f < dem.n_fibres; ++f)
                  {
                    const std::size_t i = dem.local_index(s, f);
                    dem.position[3 * i] = (1. + strain) * (*dem.station_x)[s];
                    dem.velocity[3 * i] = 0.;
                    dem.velocity[3 * i + 1] = dem.velocity[3 * i + 2] = 0.;
                  }
            }
        }
        Projectile far(shared.projectile, shared.yarn.thickness_semi_axis);
        far.place_on(1.);
        // The models' own forces, then the generalised ones of the coupled
        // system (couple() replaces the overlaps').
        fe_model->compute_forces(far, 0.);
        for (ImpactModel *part : dem_parts)
          part->compute_forces(far, 0.);
        const FE::CouplingView fe = FE::coupling_view(*fe_model);
        double largest            = 0.;
        std::vector<bool> coupled(fe.reference_coordinate->size(), false);
        for (const Overlap *o : overlaps())
          for (const auto &[c, dofs] : o->owned_nodes)
            for (unsigned int d = 0; d < 3; ++d)
              coupled[dofs[d]] = true;
        for (const auto &node : *fe.nodes)
          for (unsigned int d = 0; d < 3; ++d)
            if (!coupled[node[d]] && fe.inverse_mass[node[d]] != 0.)
              largest = std::max(largest, std::abs(fe.force[node[d]]));
        // The free spheres outside the overlaps: the DEM part's by the nose
        // (x normal to the plane x = 0 is held there), the one's at the
        // clamp but the clamped station.
        {
          const DEM::CouplingView dem = DEM::coupling_view(*dem_model);
          for (unsigned int s = dem.station_begin;
               s < std::min(dem.station_end, nose.station_begin);
               ++s)
            for (unsigned int f = 0; f < dem.n_fibres; ++f)
              for (unsigned int d = (s == 0 ? 1 : 0); d < 3; ++d)
                largest =
                  std::max(largest,
                           std::abs(dem.force[3 * dem.local_index(s, f) + d]));
        }
        if (clamp_model)
          {
            const DEM::CouplingView dem = DEM::coupling_view(*clamp_model);
            for (unsigned int s =
                   std::max(dem.station_begin, clamp.station_end);
                 s < std::min(dem.station_end, dem.n_stations - 1);
                 ++s)
              for (unsigned int f = 0; f < dem.n_fibres; ++f)
                for (unsigned int d = 0; d < 3; ++d)
                  largest =
                    std::max(largest,
                             std::abs(
                               dem.force[3 * dem.local_index(s, f) + d]));
          }
        nose.couple(*fe_model, 0., communicator);
        if (clamp_model)
          clamp.couple(*fe_model, 0., communicator);
        for (const Overlap *o : overlaps())
          {
            std::vector<double> generalised(o->node_force.size());
            o->constraint.generalised_force(o->node_force.data(),
                                            o->particle_force.data(),
                                            generalised.data());
            for (const double g : generalised)
              largest = std::max(largest, std::abs(g));
          }
        largest              = Utilities::MPI::max(largest, communicator);
        const double tension = shared.yarn.fibre_modulus * M_PI * 0.25 *
                               shared.yarn.fibre_diameter *
                               shared.yarn.fibre_diameter * strain;
        return largest / tension;
      }


      Observables
      HybridModel::observables() const
      {
        const Observables a = fe_model->observables();
        const Observables b = dem_model->observables();
        Observables c;
        if (clamp_model)
          c = clamp_model->observables();
        if (a.max_strain >= 0.9 * shared.yarn.failure_strain &&
            shared.yarn.failure)
          {
            std::ostringstream s;
            s << "the FE part's largest fibre strain " << a.max_strain
              << " is within 10 % of Yarn/Failure strain "
              << shared.yarn.failure_strain
              << ": fibres would break outside the DEM part"
              << (clamp_model ? "s" : "") << "; raise Hybrid/DEM half-length"
              << (clamp_model ? " or Hybrid/Clamp DEM length"
                              : " (or set Hybrid/Clamp DEM length)");
            throw RunError(s.str());
          }
        Observables o;
        o.kinetic_energy    = a.kinetic_energy + b.kinetic_energy;
        o.elastic_energy    = a.elastic_energy + b.elastic_energy;
        o.contact_energy    = a.contact_energy + b.contact_energy;
        o.dissipated_energy = a.dissipated_energy + b.dissipated_energy;
        o.max_strain        = std::max(a.max_strain, b.max_strain);
        o.n_failed          = b.n_failed;
        o.n_eroded          = b.n_eroded;
        o.n_damaged         = b.n_damaged;
        o.cut_through       = b.cut_through;
        if (clamp_model)
          {
            o.kinetic_energy += c.kinetic_energy;
            o.elastic_energy += c.elastic_energy;
            o.contact_energy += c.contact_energy;
            o.dissipated_energy += c.dissipated_energy;
            o.max_strain = std::max(o.max_strain, c.max_strain);
            o.n_failed += c.n_failed;
            o.n_eroded += c.n_eroded;
            o.n_damaged += c.n_damaged;
            // Every fibre broken within one of the parts (a fibre broken
            // at the nose and another at the clamp do not count).
            o.cut_through = o.cut_through || c.cut_through;
          }
        // The profile: the DEM's stations up to the middle of the overlap,
        // the FE's beyond (up to the middle of the clamp's overlap, and
        // the clamp part's stations after it).
        const double middle =
          0.5 * (layout.overlap_begin + layout.dem_half_length);
        const double clamp_middle =
          clamp_model ? 0.5 * (layout.clamp_begin + layout.fe_end)
                      : std::numeric_limits<double>::infinity();
        StationProfile &p = o.profile;
        auto append = [&p](const StationProfile &q, const unsigned int k) {
          p.position.push_back(q.position[k]);
          p.axial_strain.push_back(q.axial_strain[k]);
          p.deflection.push_back(q.deflection[k]);
          p.width.push_back(q.width[k]);
          p.initial_width.push_back(q.initial_width[k]);
          p.rms_width.push_back(q.rms_width[k]);
        };
        for (unsigned int k = 0; k < b.profile.size(); ++k)
          if (k * layout.station_spacing < middle)
            append(b.profile, k);
        for (unsigned int k = 0; k < a.profile.size(); ++k)
          {
            const double x = layout.overlap_begin + k * layout.cell_length;
            if (x >= middle && x < clamp_middle)
              append(a.profile, k);
          }
        if (clamp_model)
          for (unsigned int k = 0; k < c.profile.size(); ++k)
            if (layout.clamp_begin + k * layout.station_spacing >= clamp_middle)
              append(c.profile, k);
        return o;
      }


      std::string
      HybridModel::write_snapshot(const std::string &directory,
                                  const unsigned int index,
                                  const double time) const
      {
        const std::string fe_record =
          fe_model->write_snapshot(directory, index, time);
        const std::string dem_record =
          dem_model->write_snapshot(directory, index, time);
        const std::string clamp_record =
          clamp_model ? clamp_model->write_snapshot(directory, index, time)
                      : std::string();
        std::ostringstream name;
        name << "hybrid_" << std::setw(4) << std::setfill('0') << index
             << ".vtm";
        collective_output(communicator, [&] {
          if (Utilities::MPI::this_mpi_process(communicator) == 0)
            {
              // Both parts as one multiblock data set, so that ParaView
              // opens them together from hybrid.pvd.
              AtomicFile vtm(directory + "/" + name.str());
              vtm.stream()
                << "<?xml version=\"1.0\"?>\n"
                << "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\">\n"
                << "  <vtkMultiBlockDataSet>\n"
                << "    <DataSet index=\"0\" name=\"fe\" file=\"" << fe_record
                << "\"/>\n"
                << "    <DataSet index=\"1\" name=\"dem\" file=\"" << dem_record
                << "\"/>\n"
                << (clamp_model ? "    <DataSet index=\"2\" name=\"dem_clamp\" "
                                  "file=\"" +
                                    clamp_record + "\"/>\n"
                                : std::string())
                << "  </vtkMultiBlockDataSet>\n"
                << "</VTKFile>\n";
              vtm.commit();
            }
        });
        return name.str();
      }
    } // namespace


    double
    patch_test(const YarnImpact::Parameters::Shared &shared,
               const FE::Parameters &fe,
               const DEM::Parameters &dem,
               const HybridParameters &hybrid,
               const double strain,
               const MPI_Comm communicator)
    {
      validate(shared, fe, dem, hybrid);
      HybridModel model(shared, fe, dem, hybrid, communicator);
      std::ostringstream quiet;
      Projectile far(shared.projectile, shared.yarn.thickness_semi_axis);
      far.place_on(1.);
      model.setup(far, quiet);
      return model.patch_test(strain);
    }


    std::unique_ptr<ImpactModel>
    create_hybrid_model(const YarnImpact::Parameters::Shared &shared,
                        const FE::Parameters &fe,
                        const DEM::Parameters &dem,
                        const HybridParameters &hybrid,
                        const MPI_Comm communicator)
    {
      validate(shared, fe, dem, hybrid);
      return std::make_unique<HybridModel>(shared,
                                           fe,
                                           dem,
                                           hybrid,
                                           communicator);
    }
  } // namespace Coupling
} // namespace YarnImpact
