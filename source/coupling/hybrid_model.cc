// The hybrid yarn (doc/hybrid.md): the DEM fibres where the yarn wraps the
// nose and breaks, the FE continuum elsewhere, coupled in an overlap by the
// bridging domain method: the model's set-up, observables and snapshots (the
// class in hybrid_model_implementation.h, its patch test in
// hybrid_patch_test.cc). Its parameters and parts are in hybrid_parameters.cc,
// the FE part's section quadrature in section_quadrature.cc.

#include "hybrid_model_implementation.h"

namespace YarnImpact
{
  namespace Coupling
  {
    using namespace dealii;


    namespace internal
    {


      void
      HybridModel::setup(const Projectile &projectile, std::ostream &out)
      {
        fe_model->setup(projectile, out);
        dem_model->setup(projectile, out);
        if (clamp_model)
          clamp_model->setup(projectile, out);
        if (left_fe_model)
          left_fe_model->setup(projectile, out);

        // The section the FE part was extruded from: its vertices are the
        // coupled nodes of each node layer of an overlap.
        Triangulation<2> section;
        create_yarn_section(section,
                            shared.yarn.thickness_semi_axis,
                            shared.yarn.width_semi_axis,
                            fe_parameters.section_refinements,
                            quarter(),
                            fe_parameters.preserve_section_area);
        if (layout.fibre_bars)
          {
            // Each side's bars on its own FE part, the fibres where the DEM
            // part lays them.
            const DEM::CouplingView dem = DEM::coupling_view(*dem_model);
            auto set_up_bars            = [&](FibreBars &b, ImpactModel &fe) {
              b.set_up(fe,
                       section,
                       layout,
                       shared.yarn,
                       *dem.fibre_y,
                       *dem.fibre_z,
                       shared.yarn.failure,
                       quarter(),
                       communicator);
              b.set_projectile_contact(dem.projectile_law,
                                       dem.projectile_constants,
                                       dem.sphere_radius);
              b.compute_forces(fe, projectile, 0., communicator);
            };
            set_up_bars(bars, *fe_model);
            if (left_fe_model)
              set_up_bars(left_bars, *left_fe_model);
          }
        nose.set_up(*fe_model, section, layout, shared.yarn, communicator);
        if (left_fe_model)
          left.set_up(*left_fe_model,
                      section,
                      layout,
                      shared.yarn,
                      communicator);
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
            if (left_fe_model)
              out << "their mirror images on x < 0; ";
            if (layout.fibre_bars)
              out << "far field: " << bars.n_fibres << " fibres of "
                  << bars.n_nodes - 1 << " bars (" << bars.bars_per_cell
                  << " per FE cell); ";
            for (const Overlap *o : overlaps())
              out << o->constraint.n_nodes() << " coupled FE nodes, "
                  << o->constraint.n_particles() << " coupled spheres; ";
            out << "yarn mass " << mass() * 1e6 << " mg\n";
          }
      }


      Observables
      HybridModel::observables() const
      {
        const Observables a = fe_model->observables();
        const Observables b = dem_model->observables();
        Observables c, d;
        if (clamp_model)
          c = clamp_model->observables();
        if (left_fe_model)
          d = left_fe_model->observables();
        if (std::max(a.max_strain, d.max_strain) >=
              0.9 * shared.yarn.failure_strain &&
            shared.yarn.failure && !layout.fibre_bars)
          {
            std::ostringstream s;
            s << "the FE part's largest fibre strain "
              << std::max(a.max_strain, d.max_strain)
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
        o.n_eroded          = a.n_eroded + b.n_eroded;
        o.n_damaged         = b.n_damaged;
        o.cut_through       = b.cut_through;
        o.momentum          = a.momentum + b.momentum + c.momentum + d.momentum;
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
        // A whole yarn's FE part on x < 0.
        if (left_fe_model)
          {
            o.kinetic_energy += d.kinetic_energy;
            o.elastic_energy += d.elastic_energy;
            o.contact_energy += d.contact_energy;
            o.dissipated_energy += d.dissipated_energy;
            o.max_strain = std::max(o.max_strain, d.max_strain);
            o.n_eroded += d.n_eroded;
          }
        if (layout.fibre_bars)
          {
            // The FE part's strain is the section's alone: the bars carry
            // the fibres'.
            const double factor = symmetry();
            o.max_strain        = std::max(b.max_strain, bars.largest_strain());
            o.kinetic_energy += factor * bars.kinetic_energy();
            o.elastic_energy += factor * bars.elastic_energy();
            o.dissipated_energy += factor * bars.dissipated_energy();
            o.contact_energy += factor * bars.contact_energy();
            o.n_failed += std::lround(factor * bars.n_broken());
            if (left_fe_model)
              {
                o.max_strain =
                  std::max(o.max_strain, left_bars.largest_strain());
                o.kinetic_energy += left_bars.kinetic_energy();
                o.elastic_energy += left_bars.elastic_energy();
                o.dissipated_energy += left_bars.dissipated_energy();
                o.contact_energy += left_bars.contact_energy();
                o.n_failed += left_bars.n_broken();
              }
            o.cut_through = o.cut_through || every_fibre_broken();
          }
        // Each part's energy balance: the DEM part(s) and the rest.
        const auto energy = [](const Observables &x) {
          return x.kinetic_energy + x.elastic_energy + x.contact_energy +
                 x.dissipated_energy;
        };
        const double dem_energy = energy(b) + energy(c);
        double work             = 0.;
        for (const Overlap *overlap : overlaps())
          work += symmetry() * overlap->work;
        o.extra_columns = {o.momentum,
                           1e3 * (energy(o) - dem_energy),
                           1e3 * dem_energy,
                           1e3 * work,
                           1e3 * fe_projectile_work};
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
        const std::vector<double> bar_strain =
          layout.fibre_bars ? bars.largest_strains() : std::vector<double>();
        for (unsigned int k = 0; k < a.profile.size(); ++k)
          {
            const double x = layout.overlap_begin + k * layout.cell_length;
            if (x >= middle && x < clamp_middle)
              {
                append(a.profile, k);
                if (layout.fibre_bars)
                  p.axial_strain.back() = bar_strain[k];
              }
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
        std::string bars_record, left_bars_record;
        if (layout.fibre_bars)
          collective_output(communicator, [&] {
            bars_record = bars.write_snapshot(directory, index);
          });
        // A whole yarn's side x < 0, written where it stands.
        const std::string left_record =
          left_fe_model ? left_fe_model->write_snapshot(directory, index, time)
                        : std::string();
        if (left_fe_model && layout.fibre_bars)
          collective_output(communicator, [&] {
            left_bars_record = left_bars.write_snapshot(directory, index);
          });
        // The multiblock's data sets, in the order of their indices.
        std::vector<std::pair<std::string, std::string>> blocks =
          {{"fe", fe_record}, {"dem", dem_record}};
        if (clamp_model)
          blocks.emplace_back("dem_clamp", clamp_record);
        if (layout.fibre_bars)
          blocks.emplace_back("bars", bars_record);
        if (left_fe_model)
          blocks.emplace_back("fe_left", left_record);
        if (left_fe_model && layout.fibre_bars)
          blocks.emplace_back("bars_left", left_bars_record);
        std::ostringstream name;
        name << "hybrid_" << std::setw(4) << std::setfill('0') << index
             << ".vtm";
        collective_output(communicator, [&] {
          if (Utilities::MPI::this_mpi_process(communicator) == 0)
            {
              // All parts as one multiblock data set, so that ParaView
              // opens them together from hybrid.pvd.
              AtomicFile vtm(directory + "/" + name.str());
              vtm.stream()
                << "<?xml version=\"1.0\"?>\n"
                << "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\">\n"
                << "  <vtkMultiBlockDataSet>\n";
              for (unsigned int k = 0; k < blocks.size(); ++k)
                vtm.stream() << "    <DataSet index=\"" << k << "\" name=\""
                             << blocks[k].first << "\" file=\""
                             << blocks[k].second << "\"/>\n";
              vtm.stream() << "  </vtkMultiBlockDataSet>\n"
                           << "</VTKFile>\n";
              vtm.commit();
            }
        });
        return name.str();
      }
    } // namespace internal


    std::unique_ptr<ImpactModel>
    create_hybrid_model(const YarnImpact::Parameters::Shared &shared,
                        const FE::Parameters &fe,
                        const DEM::Parameters &dem,
                        const HybridParameters &hybrid,
                        const MPI_Comm communicator)
    {
      validate(shared, fe, dem, hybrid);
      return std::make_unique<internal::HybridModel>(shared,
                                                     fe,
                                                     dem,
                                                     hybrid,
                                                     communicator);
    }
  } // namespace Coupling
} // namespace YarnImpact
