#include <yarn_impact/app/application.h>
#include <yarn_impact/app/model_factory.h>
#include <yarn_impact/core/memory_estimate.h>
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
    // The registered models, each with its own words, and `both`; several
    // models of the single yarn run one after the other on the same
    // problem and are compared with the DEM.
    std::string values, help = "Model to run: ";
    for (const std::string &name : ModelRegistry::names())
      {
        values += name + "|";
        help += ModelRegistry::help(name) + " (" + name + "), ";
      }
    values += "both";
    help += "or fe and dem on the same problem, compared (both). Several "
            "models of the single yarn, comma-separated (fe, dem, hybrid), "
            "run one after the other on the same problem in that order, "
            "each compared with the DEM (comparison.csv).";
    prm.declare_entry("Model",
                      "fe",
                      dealii::Patterns::MultipleSelection(values),
                      help);
  }


  std::string
  parse_model_type(dealii::ParameterHandler &prm)
  {
    return prm.get("Model");
  }


  std::vector<std::string>
  model_names(const std::string &model)
  {
    std::vector<std::string> names;
    std::istringstream list(model);
    for (std::string name; std::getline(list, name, ',');)
      {
        const auto first = name.find_first_not_of(" \t");
        const auto last  = name.find_last_not_of(" \t");
        name             = first == std::string::npos
                             ? std::string()
                             : name.substr(first, last - first + 1);
        if (name == "both")
          names.insert(names.end(), {"fe", "dem"});
        else if (!name.empty())
          names.push_back(name);
      }
    return names;
  }


  std::string
  comparison_reference()
  {
    return "dem";
  }


  std::unique_ptr<ImpactModel>
  create_model(const std::string &name,
               const AllParameters &p,
               const MPI_Comm communicator)
  {
    return p.models.at(name)->create(p.shared, communicator);
  }


  void
  check_memory_of_models(const AllParameters &p,
                         const bool print,
                         std::ostream &out)
  {
    std::vector<std::string> lines;
    if (const auto task = p.own_task())
      {
        lines.push_back(
          check_memory(p.models.at(p.model)->memory_estimate(p.shared),
                       task->name,
                       MPI_COMM_WORLD));
        if (print && rank_in(MPI_COMM_WORLD) == 0)
          out << lines.back() << '\n';
        return;
      }
    for (const std::string &name : p.run_models())
      lines.push_back(check_memory(p.models.at(name)->memory_estimate(p.shared),
                                   name,
                                   MPI_COMM_WORLD));
    if (print && rank_in(MPI_COMM_WORLD) == 0)
      for (const auto &line : lines)
        out << line << '\n';
  }
} // namespace YarnImpact
