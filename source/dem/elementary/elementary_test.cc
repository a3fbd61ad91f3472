// DEM elementary tests: a periodic segment of the yarn (the impact model's
// fibres, packing and contact laws) under a homogeneous deformation, with
// its homogenised stress. The theory, the boundary conditions and the
// checks are in doc/identification.md; run_elementary_test() chains the
// phases of elementary_phases.h: the loading, the measurement on its rows
// and the checks.
#include <yarn_impact/core/output_file.h>
#include <yarn_impact/dem/elementary/elementary_test.h>

#include <deal.II/base/mpi.h>

#include <filesystem>
#include <ostream>

#include "elementary_phases.h"

namespace YarnImpact
{
  namespace DEM
  {
    using namespace dealii;

    std::string
    elementary_test_file(const ElementaryLoading loading)
    {
      switch (loading)
        {
          case ElementaryLoading::tension:
            return "elementary_tension.csv";
          case ElementaryLoading::compaction:
            return "elementary_compaction.csv";
          case ElementaryLoading::distortion:
            return "elementary_distortion.csv";
          default:
            return "";
        }
    }


    bool
    run_elementary_test(const YarnImpact::Parameters::Shared &shared,
                        const Parameters &dem,
                        const ElementaryTestParameters &test,
                        const MPI_Comm communicator,
                        std::ostream &out)
    {
      const bool root = Utilities::MPI::this_mpi_process(communicator) == 0;
      const bool testing =
        YarnImpact::Parameters::deterministic(shared.output.verbosity);
      internal::PeriodicSegment seg(shared, dem, test, communicator);
      const auto &y      = shared.yarn;
      const double phi   = y.fibre_area() / y.section_area();
      const double E_phi = y.fibre_modulus * phi;

      if (root && !testing)
        out << "[elementary] " << seg.nf << " fibres x " << seg.ns
            << " cross-sections (" << seg.n << " spheres), periodic along x "
            << "over " << seg.Lx0 * 1e6 << " um; packing scale "
            << seg.packing_scale << "; fibre area fraction of the FE "
            << "ellipse " << phi << "; dt " << seg.dt * 1e9 << " ns\n";

      const std::string file =
        shared.output.directory + "/" + elementary_test_file(test.loading);
      const std::string partial = file + ".partial";
      AppendFile csv;
      collective_output(communicator, [&] {
        if (root)
          {
            csv.open(partial);
            csv.append(std::string(internal::elementary_csv_header) + '\n');
          }
      });
      const std::string name =
        elementary_test_file(test.loading).substr(11, std::string::npos);
      internal::Recorder rec(seg,
                             root ? &csv : nullptr,
                             name.substr(0, name.size() - 4),
                             partial);

      internal::Report report;
      report.text << "Elementary test (" << rec.name << ", " << seg.nf
                  << " fibres, " << seg.ns << " cross-sections, periodic)\n";
      // The loading, then what is measured on its rows and checked.
      if (test.loading == ElementaryLoading::tension)
        {
          internal::run_tension(seg, rec);
          internal::check_tension(internal::measure_tension(rec.rows,
                                                            seg.break_strains(),
                                                            E_phi),
                                  seg,
                                  phi,
                                  E_phi,
                                  report);
        }
      else
        {
          const std::vector<double> pressures =
            (test.loading == ElementaryLoading::distortion
               ? test.confining_pressures
               : std::vector<double>{0.});
          for (const double pc : pressures)
            {
              const std::size_t first = rec.rows.size();
              internal::run_plates(seg, rec, pc);
              internal::check_plates(
                internal::measure_plates(rec.rows, first, pc, test.max_strain),
                pc,
                dem.friction,
                testing,
                report);
            }
        }
      if (!testing)
        report.text << "  neighbour-list rebuilds: " << seg.n_rebuilds
                    << "\n  rows written to " << file << '\n';

      // The curves get their final name only once complete.
      collective_output(communicator, [&] {
        if (!root)
          return;
        std::error_code ec;
        std::filesystem::rename(partial, file, ec);
        if (ec)
          throw OutputError("cannot rename '" + partial + "' to '" + file +
                            "': " + ec.message() + ".");
      });
      if (root)
        YarnImpact::Parameters::print_summary_text(report.text.str(),
                                                   shared.output.verbosity,
                                                   out);
      collective_output(communicator, [&] {
        if (root)
          write_file_atomically(shared.output.directory + "/summary.txt",
                                report.text.str());
      });
      return report.passed;
    }
  } // namespace DEM
} // namespace YarnImpact
