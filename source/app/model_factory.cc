#include <yarn_impact/app/application.h>
#include <yarn_impact/app/model_factory.h>
#include <yarn_impact/coupling/hybrid_model.h>
#include <yarn_impact/dem/dem_model.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <limits>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace YarnImpact
{
  void
  declare_model_type(dealii::ParameterHandler &prm)
  {
    prm.declare_entry("Model",
                      "fe",
                      dealii::Patterns::Selection("fe|dem|both|hybrid"),
                      "Model to run: the mesoscopic finite-element yarn "
                      "(fe), the microscopic discrete-element fibres (dem), "
                      "both on the same problem (both), or the hybrid yarn: "
                      "the DEM fibres near the impact, the FE continuum "
                      "elsewhere, coupled in an overlap (hybrid, subsection "
                      "Hybrid, doc/hybrid.md).");
  }


  ModelType
  parse_model_type(dealii::ParameterHandler &prm)
  {
    const std::string m = prm.get("Model");
    return (m == "fe"       ? ModelType::fe
            : m == "dem"    ? ModelType::dem
            : m == "hybrid" ? ModelType::hybrid
                            : ModelType::both);
  }


  std::unique_ptr<ImpactModel>
  create_model(const ModelType type,
               const AllParameters &p,
               const MPI_Comm communicator)
  {
    if (type == ModelType::dem)
      return DEM::create_model(p.shared, p.dem, communicator);
    if (type == ModelType::hybrid)
      return Coupling::create_hybrid_model(p.shared,
                                           p.fe,
                                           p.dem,
                                           p.hybrid,
                                           communicator);
    return FE::create_model(p.shared, p.fe, communicator);
  }


  namespace
  {
    /**
     * What the periodic segment of an elementary test allocates: every rank
     * holds the positions, velocities, accelerations and exchange buffers
     * of all spheres (about 400 B each, counted once per rank) and the
     * neighbour lists and contact histories of its own (about 600 B each,
     * measured: 0.8 GB for 800 000 spheres on one rank). Refused with the
     * parameter that makes it large, also where the segment would not fit
     * an MPI message (6 doubles a sphere, counted in an int).
     */
    MemoryEstimate
    elementary_memory_estimate(const AllParameters &p,
                               const unsigned int n_ranks)
    {
      MemoryEstimate e;
      const double fibres   = p.shared.yarn.n_fibres;
      const double sections = p.elementary.stations;
      e.n_elements          = fibres * sections;
      e.bytes               = (400. * n_ranks + 600.) * e.n_elements;
      e.element_name        = "spheres";
      e.parameter =
        (fibres / 400. >= sections / 4. ? "Yarn/Number of fibres"
                                        : "Elementary test/Cross-sections");
      if (6. * e.n_elements > double(std::numeric_limits<int>::max()))
        {
          std::ostringstream s;
          s.precision(3);
          s << "Parameter '" << e.parameter
            << "' makes the elementary test's segment " << e.n_elements
            << " spheres, more than one MPI message can exchange ("
            << std::numeric_limits<int>::max() / 6 << ").";
          throw InputError(s.str());
        }
      return e;
    }
  } // namespace


  void
  check_memory_of_models(const AllParameters &p,
                         const bool print,
                         std::ostream &out)
  {
    const auto model = p.model;
    std::vector<std::string> lines;
    if (p.elementary.loading != DEM::ElementaryLoading::none)
      {
        lines.push_back(check_memory(
          elementary_memory_estimate(p,
                                     dealii::Utilities::MPI::n_mpi_processes(
                                       MPI_COMM_WORLD)),
          "elementary",
          MPI_COMM_WORLD));
        if (print &&
            dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
          out << lines.back() << '\n';
        return;
      }
    if (model == ModelType::hybrid)
      lines.push_back(
        check_memory(Coupling::memory_estimate(p.shared, p.fe, p.dem, p.hybrid),
                     "hybrid",
                     MPI_COMM_WORLD));
    else if (model != ModelType::dem)
      lines.push_back(check_memory(FE::memory_estimate(p.shared, p.fe),
                                   "fe",
                                   MPI_COMM_WORLD));
    if (model != ModelType::fe && model != ModelType::hybrid)
      lines.push_back(check_memory(DEM::memory_estimate(p.shared, p.dem),
                                   "dem",
                                   MPI_COMM_WORLD));
    if (print && dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      for (const auto &line : lines)
        out << line << '\n';
  }
} // namespace YarnImpact
