#ifndef yarn_impact_core_model_registry_h
#define yarn_impact_core_model_registry_h

#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/memory_estimate.h>
#include <yarn_impact/core/parameters.h>

#include <mpi.h>

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace YarnImpact
{
  /**
   * A model as the application sees it, with its own parameters: the one
   * interface through which a run reads, checks, sizes and creates a
   * model, so that the application names none (in the manner of ASPECT's
   * plugins). Each model implements it in its own folder and registers it
   * with YARN_IMPACT_REGISTER_MODEL under its value of the entry `Model`.
   */
  class ModelPlugin
  {
  public:
    /**
     * A task of a model's own that its parameters can ask for instead of
     * an impact run (the DEM's elementary tests): it writes into
     * `Output/Directory` but no checkpoints.
     */
    struct OwnTask
    {
      /** Short name, for the memory line ("elementary"). */
      std::string name;
      /** What it is, in the plural, for messages ("elementary tests"). */
      std::string description;
      /** The entry that asks for it ("Elementary test/Loading"). */
      std::string parameter;
    };

    virtual ~ModelPlugin() = default;

    /** Parse the model's parameters (declared by its registration). */
    virtual void
    parse_parameters(dealii::ParameterHandler &prm) = 0;

    /** The set-up checks of the model's parameters against @p shared that
     * need no MPI ranks, so that `--check` refuses what a run would;
     * throws InputError naming the parameter. */
    virtual void
    validate(const Parameters::Shared &shared) const = 0;

    /** What the model's set-up would allocate, before anything is. */
    virtual MemoryEstimate
    memory_estimate(const Parameters::Shared &shared) const = 0;

    /** The model of the yarn of @p shared on @p communicator, not set up
     * yet. */
    virtual std::unique_ptr<ImpactModel>
    create(const Parameters::Shared &shared,
           const MPI_Comm communicator) const = 0;

    /** The task of the model's own that the parsed parameters ask for, if
     * any (then validate() and memory_estimate() are the task's, and the
     * run is run_own_task(), not an impact); none by default. */
    virtual std::optional<OwnTask>
    own_task() const
    {
      return std::nullopt;
    }

    /** Whether the model is of the single yarn of `Yarn` (the FE, the DEM
     * and the hybrid are; a woven patch is not): only such models run
     * together in one `Model` list, on the same problem. */
    virtual bool
    single_yarn() const
    {
      return true;
    }

    /** Run the task of own_task() on @p communicator (collective), its
     * report to @p out; @return whether its checks passed. Throws
     * Interrupted when a signal stops it. */
    virtual bool
    run_own_task(const Parameters::Shared &shared,
                 const MPI_Comm communicator,
                 std::ostream &out) const;
  };


  /** The registered models. A registration runs while the library loads
   * (a static initialiser, YARN_IMPACT_REGISTER_MODEL). */
  namespace ModelRegistry
  {
    /** Declares the entries of a model's own subsections. */
    using DeclareFunction = void (*)(dealii::ParameterHandler &);
    /** Makes a plugin with default parameters. */
    using MakeFunction = std::unique_ptr<ModelPlugin> (*)();

    /** Register the model @p name (its value of `Model`), with @p help, what
     * it is in a few words for the help of `Model`; @return true, to
     * initialise a static. A name registered twice is a programming error
     * (std::logic_error). */
    bool
    add(const std::string &name,
        const std::string &help,
        const DeclareFunction declare,
        const MakeFunction make);

    /** The registered names, sorted. */
    std::vector<std::string>
    names();

    /** What the model @p name is, as registered. */
    std::string
    help(const std::string &name);

    /** Declare the parameters of every registered model. */
    void
    declare_parameters(dealii::ParameterHandler &prm);

    /** A plugin of the model @p name with default parameters; a name not
     * registered is a programming error (std::logic_error). */
    std::unique_ptr<ModelPlugin>
    make(const std::string &name);
  } // namespace ModelRegistry
} // namespace YarnImpact

/**
 * Register @p Plugin, a ModelPlugin with a static
 * `declare_parameters(dealii::ParameterHandler &)` and a static
 * `std::string help()` (what it is, in a few words, for the help of the
 * entry `Model`), as the model @p name (a string literal: its value of the
 * entry `Model`). Once per model, in a source file of its folder.
 */
#define YARN_IMPACT_REGISTER_MODEL(name, Plugin)             \
  namespace                                                  \
  {                                                          \
    const bool yarn_impact_model_registered =                \
      ::YarnImpact::ModelRegistry::add(                      \
        name,                                                \
        Plugin::help(),                                      \
        &Plugin::declare_parameters,                         \
        []() -> std::unique_ptr<::YarnImpact::ModelPlugin> { \
          return std::make_unique<Plugin>();                 \
        });                                                  \
  }

#endif
