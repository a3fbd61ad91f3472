#include <yarn_impact/app/application.h>
#include <yarn_impact/app/model_factory.h>
#include <yarn_impact/coupling/hybrid_model.h>
#include <yarn_impact/dem/dem_model.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <ostream>
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


  void
  check_memory_of_models(const AllParameters &p,
                         const bool print,
                         std::ostream &out)
  {
    if (p.elementary.loading != DEM::ElementaryLoading::none)
      return;
    const auto model = p.model;
    std::vector<std::string> lines;
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
