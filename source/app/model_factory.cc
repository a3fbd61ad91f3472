#include <yarn_impact/app/application.h>
#include <yarn_impact/app/model_factory.h>
#include <yarn_impact/core/model_registry.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <limits>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace YarnImpact
{
  void
  declare_model_type(dealii::ParameterHandler &prm)
  {
    // A new model adds its value and a sentence here; a registered model
    // that `Model` cannot name is a programming error.
    const std::string values = "fe|dem|both|hybrid";
    for (const std::string &name : ModelRegistry::names())
      if (("|" + values + "|").find("|" + name + "|") == std::string::npos)
        throw std::logic_error("the registered model '" + name +
                               "' is not a value of the entry Model");
    prm.declare_entry("Model",
                      "fe",
                      dealii::Patterns::Selection(values),
                      "Model to run: the mesoscopic finite-element yarn "
                      "(fe), the microscopic discrete-element fibres (dem), "
                      "both on the same problem (both), or the hybrid yarn: "
                      "the DEM fibres near the impact, the FE continuum "
                      "elsewhere, coupled in an overlap (hybrid, subsection "
                      "Hybrid, doc/hybrid.md).");
  }


  std::string
  parse_model_type(dealii::ParameterHandler &prm)
  {
    return prm.get("Model");
  }


  std::vector<std::string>
  model_names(const std::string &model)
  {
    if (model == "both")
      return {"fe", "dem"};
    return {model};
  }


  std::unique_ptr<ImpactModel>
  create_model(const std::string &name,
               const AllParameters &p,
               const MPI_Comm communicator)
  {
    return p.models.at(name)->create(p.shared, communicator);
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
    for (const std::string &name : p.run_models())
      lines.push_back(check_memory(p.models.at(name)->memory_estimate(p.shared),
                                   name,
                                   MPI_COMM_WORLD));
    if (print && dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      for (const auto &line : lines)
        out << line << '\n';
  }
} // namespace YarnImpact
