#ifndef yarn_impact_app_application_h
#define yarn_impact_app_application_h

#include <yarn_impact/analysis/parameters.h>
#include <yarn_impact/app/model_factory.h>
#include <yarn_impact/core/model_registry.h>
#include <yarn_impact/core/parameters.h>

#include <functional>
#include <iosfwd>
#include <map>
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
  /** Every parameter of a run: the shared ones and those of each model. */
  struct AllParameters
  {
    /** Model(s) to run (entry `Model`): a registered model or `both`. */
    std::string model = "fe";
    Parameters::Shared shared;
    /** Wave fronts and verification (analysis/). */
    Analysis::Parameters analysis;
    /** Every registered model with its parameters, by name
     * (ModelRegistry); each parses its own, whichever model runs, so that
     * a bad entry is refused whatever `Model` says. */
    std::map<std::string, std::shared_ptr<ModelPlugin>> models;

    /** The chosen model's task of its own, if its parameters ask for one
     * (ModelPlugin::own_task(): the DEM's elementary tests) instead of an
     * impact run. */
    std::optional<ModelPlugin::OwnTask>
    own_task() const;

    /** The models a run drives, in order (model_names()). */
    std::vector<std::string>
    run_models() const
    {
      return model_names(model);
    }

    /** Declare every entry. */
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Parse every entry and validate the set-up; throws InputError. */
    void
    parse_parameters(dealii::ParameterHandler &prm);
  };

  /**
   * Read @p file into @p prm (declared with AllParameters) and parse it.
   * Parse errors of deal.II are turned into one-line InputError messages
   * that name the file line and the entry. A @p file that is not a readable
   * regular file (missing, a directory, a fifo, unreadable) is refused with
   * an InputError naming it and the cause, before anything is read. The
   * same holds for every file it includes (`include FILE`, FILE relative to
   * the including file's folder; cycles refused): see
   * Parameters::read_parameter_file. The files read, @p file first, are
   * stored in @p files if given.
   */
  AllParameters
  read_parameters(const std::string &file,
                  dealii::ParameterHandler &prm,
                  std::vector<std::string> *files = nullptr);

  /**
   * The command line: `yarn-impact file.prm`, `--check file.prm`,
   * `--restart file.prm`, `--print-parameters`, `--help`.
   *
   * MPI may be initialised or not on entry. If it is not, the process is
   * the only rank, and @p start_mpi, which must initialise MPI (once, its
   * later calls doing nothing), is called once the parameters are read and
   * valid and the run is to go on: `--help`, `--print-parameters`,
   * `--check` and a refused set-up need no MPI (app/main.cc).
   * @return the process exit code
   */
  int
  run_application(int argc,
                  char **argv,
                  const std::function<void()> &start_mpi);
} // namespace YarnImpact

#endif
