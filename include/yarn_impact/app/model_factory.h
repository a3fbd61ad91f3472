#ifndef yarn_impact_app_model_factory_h
#define yarn_impact_app_model_factory_h

#include <yarn_impact/core/impact_model.h>

#include <mpi.h>

#include <iosfwd>
#include <memory>

namespace dealii
{
  class ParameterHandler;
}

namespace YarnImpact
{
  struct AllParameters;

  /** Which model(s) a run drives (the top-level entry `Model`). */
  enum class ModelType
  {
    fe,     ///< the mesoscopic finite-element yarn
    dem,    ///< the microscopic discrete-element fibres
    both,   ///< both on the same problem, then compared
    hybrid, ///< the DEM where the yarn breaks, the FE elsewhere, coupled
  };

  /** Declare the entry `Model` (top level). */
  void
  declare_model_type(dealii::ParameterHandler &prm);

  /** The value of the entry `Model`. */
  ModelType
  parse_model_type(dealii::ParameterHandler &prm);

  /**
   * The impact model of kind @p type (fe or dem) with the parameters
   * @p parameters, on @p communicator, not set up yet: the one place that
   * knows every model.
   */
  std::unique_ptr<ImpactModel>
  create_model(const ModelType type,
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
