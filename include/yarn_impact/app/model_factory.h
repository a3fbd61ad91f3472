#ifndef yarn_impact_app_model_factory_h
#define yarn_impact_app_model_factory_h

#include <yarn_impact/core/impact_model.h>

#include <mpi.h>

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace YarnImpact
{
  struct AllParameters;

  /** Declare the entry `Model` (top level): a registered model's name
   * (ModelRegistry), `both` (the FE and the DEM on the same problem, then
   * compared), or a comma-separated list of single-yarn models
   * (`fe, dem, hybrid`), run in that order on the same problem. */
  void
  declare_model_type(dealii::ParameterHandler &prm);

  /** The value of the entry `Model`. */
  std::string
  parse_model_type(dealii::ParameterHandler &prm);

  /** The registered models that a run of `Model = ` @p model drives, in
   * order: the names of the list @p model, `both` read as the FE, then
   * the DEM. */
  std::vector<std::string>
  model_names(const std::string &model);

  /** The model the others of a run of several are compared with: the DEM,
   * the reference of the single yarn. */
  std::string
  comparison_reference();

  /**
   * The registered impact model @p name with its parameters in
   * @p parameters, on @p communicator, not set up yet.
   */
  std::unique_ptr<ImpactModel>
  create_model(const std::string &name,
               const AllParameters &parameters,
               const MPI_Comm communicator);

  /**
   * The memory guard: refuse (InputError naming the parameter that makes it
   * large) a set-up of the models of @p parameters that would not fit in
   * this machine's memory, before anything is allocated; with @p print,
   * rank 0 writes the estimates to @p out. Elementary tests are not
   * covered.
   */
  void
  check_memory_of_models(const AllParameters &parameters,
                         const bool print,
                         std::ostream &out);
} // namespace YarnImpact

#endif
