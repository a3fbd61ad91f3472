#include <yarn_impact/analysis/model_comparison.h>
#include <yarn_impact/analysis/run_summary.h>
#include <yarn_impact/app/application.h>
#include <yarn_impact/app/model_factory.h>
#include <yarn_impact/app/output_directory.h>
#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/memory_estimate.h>
#include <yarn_impact/core/model_registry.h>
#include <yarn_impact/core/output_file.h>
#include <yarn_impact/core/output_lock.h>
#include <yarn_impact/core/parameter_tools.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <tuple>
#include <utility>
#include <vector>

namespace YarnImpact
{
  using namespace dealii;

  namespace
  {
    /** Collapse the white space of a deal.II message onto one line. */
    std::string
    one_line(const std::string &text)
    {
      std::string result;
      bool space = false;
      for (const char c : text)
        if (std::isspace(static_cast<unsigned char>(c)))
          space = !result.empty();
        else
          {
            if (space)
              result += ' ';
            result += c;
            space = false;
          }
      return result;
    }

    const char *usage =
      "Usage: yarn-impact [--check | --restart] FILE.prm | --print-parameters "
      "| --help\n"
      "\n"
      "Transverse impact of a rigid cylindrical projectile on a single yarn,\n"
      "with a mesoscopic hyperelastic finite-element model and a microscopic\n"
      "discrete-element fibre model.\n"
      "\n"
      "  FILE.prm             run the case (also under mpirun -np N)\n"
      "  --check FILE.prm     parse and validate FILE.prm, write nothing\n"
      "  --restart FILE.prm   continue the run of FILE.prm from its last\n"
      "                       checkpoint in its Output/Directory (same\n"
      "                       parameters, same number of MPI ranks)\n"
      "  --print-parameters   print every parameter with its default,\n"
      "                       unit and documentation\n"
      "  --help               this text\n";

  } // namespace


  void
  AllParameters::declare_parameters(ParameterHandler &prm)
  {
    declare_model_type(prm);
    Parameters::Shared::declare_parameters(prm);
    Analysis::Parameters::declare_parameters(prm);
    ModelRegistry::declare_parameters(prm);
  }

  void
  AllParameters::parse_parameters(ParameterHandler &prm)
  {
    model = parse_model_type(prm);
    shared.parse_parameters(prm);
    analysis.parse_parameters(prm, shared);
    models.clear();
    for (const std::string &name : ModelRegistry::names())
      {
        std::shared_ptr<ModelPlugin> plugin = ModelRegistry::make(name);
        plugin->parse_parameters(prm);
        models.emplace(name, std::move(plugin));
      }
    // Several models run one after the other on the same problem: each
    // once, all of the single yarn, none with a task of its own.
    const std::vector<std::string> names = run_models();
    Parameters::require(!names.empty(), "Model", "names no model");
    for (std::size_t i = 0; i < names.size() && names.size() > 1; ++i)
      {
        Parameters::require(std::count(names.begin(), names.end(), names[i]) ==
                              1,
                            "Model",
                            "names the model " + names[i] +
                              " twice (both is fe, dem)");
        Parameters::require(models.at(names[i])->single_yarn(),
                            "Model",
                            "= " + model + ": " + names[i] +
                              " runs alone, not with other models");
      }
    // A model's own task (the DEM's elementary tests) runs that model
    // alone.
    for (const auto &[name, plugin] : models)
      if (const auto task = plugin->own_task())
        Parameters::require(model == name,
                            task->parameter,
                            "asks for the " + task->description + " of the " +
                              name + " model: it needs Model = " + name);
    // The sphere's and the flat cylinder's contact is the FE's
    // (FE::ProjectileContact), given the node's z, and so is a contact off
    // x = z = 0; only the fabric's runs are tested with them.
    const auto shape = shared.projectile.shape;
    for (const std::string &name : run_models())
      {
        Parameters::require(shape == Parameters::ProjectileShape::cylinder ||
                              name == "fabric",
                            "Projectile/Shape",
                            std::string("= ") +
                              (shape == Parameters::ProjectileShape::sphere
                                 ? "sphere"
                                 : "flat cylinder") +
                              " runs with Model = fabric only, not " + name);
        Parameters::require(shared.projectile.offset_x == 0. ||
                              name == "fabric",
                            "Projectile/Impact offset x",
                            "must be 0 with Model = " + name +
                              ": only Model = fabric strikes off x = 0");
        Parameters::require(shared.projectile.offset_z == 0. ||
                              name == "fabric",
                            "Projectile/Impact offset z",
                            "must be 0 with Model = " + name +
                              ": only Model = fabric strikes off z = 0");
      }
    // Every set-up check that needs no MPI ranks is made here, so that
    // `--check` refuses what the run would, and a run refuses before it
    // writes anything (with Model = both, before the FE part runs).
    for (const std::string &name : run_models())
      models.at(name)->validate(shared);
  }

  std::optional<ModelPlugin::OwnTask>
  AllParameters::own_task() const
  {
    const auto plugin = models.find(model);
    return plugin == models.end() ? std::nullopt : plugin->second->own_task();
  }

  AllParameters
  read_parameters(const std::string &file,
                  ParameterHandler &prm,
                  std::vector<std::string> *files)
  {
    // Read here, not by deal.II: it reads a directory as an empty file (the
    // default case would run), opening a fifo blocks, and its `include`
    // follows cycles until the stack overflows. Every file, included ones
    // too, is checked and read by Parameters::read_parameter_file.
    std::string extension = std::filesystem::path(file).extension().string();
    for (char &c : extension)
      c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const bool prm_format = extension == ".prm";
    const Parameters::ExpandedFile input =
      Parameters::read_parameter_file(file, prm_format);
    if (files != nullptr)
      *files = input.files;
    if (!prm_format && extension != ".xml" && extension != ".json")
      throw InputError("the parameter file '" + file + "' has " +
                       (extension.empty()
                          ? std::string("no extension")
                          : "an unknown extension '" + extension + "'") +
                       ": name it .prm (or .xml, .json for deal.II's other "
                       "formats).");
    // deal.II names this file in its messages; each "Line <N> of file
    // <this>" is then replaced by the file and line that line came from.
    const std::string placeholder = "\x01expanded parameter text\x01";
    try
      {
        std::istringstream text(input.text);
        if (prm_format)
          prm.parse_input(text, placeholder, "", false);
        else if (extension == ".xml")
          prm.parse_input_from_xml(text, false);
        else
          prm.parse_input_from_json(text, false);
      }
    catch (const ExceptionBase &e)
      {
        std::ostringstream info;
        e.print_info(info);
        std::string message    = info.str();
        const std::string tail = "> of file <" + placeholder + ">";
        for (std::size_t at = message.find(tail); at != std::string::npos;
             at             = message.find(tail))
          {
                        const std::size_t open = message.rfind("Line <", at);
                        unsigned long line     = 0;
                        if (open != std::string::npos)
              line = std::strtoul(message.c_str() + open + 6, nullptr, 10);
            if (open == std::string::npos || line == 0)
              {
                            message.replace(at, tail.size(), "> of file <" + file + ">");
                            continue;
              }
            const auto &origin =
              line <= input.origin.size()
                            ? input.origin[line - 1]
                            : std::pair<std::size_t, unsigned int>(0, line);
                        message.replace(open,
                            at + tail.size() - open,
                            "Line <" + std::to_string(origin.second) +
                              "> of file <" + input.files[origin.first] + ">");
          }
        for (std::size_t at = message.find(placeholder);
             at != std::string::npos;
             at = message.find(placeholder))
          message.replace(at, placeholder.size(), file);
        throw InputError(one_line(message));
      }
    AllParameters parameters;
    try
      {
        parameters.parse_parameters(prm);
      }
    catch (const InputError &)
      {
        throw;
      }
    catch (const ExceptionBase &e)
      {
        std::ostringstream info;
        e.print_info(info);
        throw InputError(one_line(info.str()));
      }
    return parameters;
  }


  int
  run_application(int argc, char **argv, const std::function<void()> &start_mpi)
  {
    // Without MPI (app/main.cc) this is the only rank.
    const bool is_root = rank_in(MPI_COMM_WORLD) == 0;
    std::ostream &out  = std::cout;
    std::vector<std::string> args(argv + 1, argv + argc);

    ParameterHandler prm;
    AllParameters::declare_parameters(prm);

    if (args.size() == 1 && (args[0] == "--help" || args[0] == "-h"))
      {
        if (is_root)
          out << usage;
        return 0;
      }
    if (args.size() == 1 && args[0] == "--print-parameters")
      {
        if (is_root)
          prm.print_parameters(out, ParameterHandler::PRM);
        return 0;
      }
    const bool check_only = (args.size() == 2 && args[0] == "--check");
    const bool restart    = (args.size() == 2 && args[0] == "--restart");
    if (!(args.size() == 1 && args[0].size() > 0 && args[0][0] != '-') &&
        !check_only && !restart)
      {
        if (is_root)
          std::cerr << "yarn-impact: error: invalid command line (see "
                       "yarn-impact --help)\n";
        return 2;
      }
    const std::string file = args.back();

    try
      {
        std::vector<std::string> input_files;
        AllParameters parameters = read_parameters(file, prm, &input_files);
        check_memory_of_models(parameters,
                               !check_only &&
                                 parameters.shared.output.verbosity ==
                                   Parameters::Verbosity::normal,
                               out);
        if (check_only)
          {
            if (is_root)
              out << file << ": parameters are valid\n";
            return 0;
          }
        start_mpi();

        const auto &output = parameters.shared.output;
        // Held until the run returns: one owner per output directory.
        OutputLock lock;
        std::ostringstream resolved;
        prm.print_parameters(resolved, ParameterHandler::ShortPRM);
        if (restart)
          {
            if (const auto task = parameters.own_task())
              throw InputError("--restart: the " + task->description + " (" +
                               task->parameter +
                               ") write no checkpoints; run them again from "
                               "the start.");
            internal::check_restart(parameters, resolved.str(), lock);
          }
        else
          {
            internal::prepare_output_directory(output,
                                               input_files,
                                               is_root,
                                               out,
                                               lock);
            collective_output(MPI_COMM_WORLD, [&] {
              if (is_root)
                write_file_atomically(output.directory + "/parameters.prm",
                                      resolved.str());
            });
          }
        // From here a SIGTERM or SIGINT stops the run within a few steps,
        // an impact run with a checkpoint (exit code 6).
        Checkpoint::install_signal_handlers();

        if (parameters.own_task())
          {
            bool passed = false;
            try
              {
                passed =
                  parameters.models.at(parameters.model)
                    ->run_own_task(parameters.shared, MPI_COMM_WORLD, out);
              }
            catch (const Interrupted &e)
              {
                // No checkpoint, so no --restart to advise.
                if (is_root)
                  std::cerr << "yarn-impact: stopped: " << e.what()
                            << std::endl;
                return 6;
              }
            if (!passed)
              {
                if (is_root)
                  std::cerr
                    << "yarn-impact: error: a verification check failed\n";
                return 3;
              }
            return 0;
          }

        const std::vector<std::string> models = parameters.run_models();

        bool passed = true;
        std::ostringstream summary_text;
        std::vector<Analysis::ComparedRun> runs;
        std::string run_errors;
        for (const std::string &type : models)
          {
            // Each model's cost, its set-up included, for the comparison.
            const auto started = std::chrono::steady_clock::now();
            CheckpointOptions checkpoints;
            checkpoints.restart = restart;
            // With several models, the end state of each but the last
            // lets a restart in a later one compare with it.
            checkpoints.keep_final_state = (type != models.back());
            ImpactSimulation simulation(
              parameters.shared,
              create_model(type, parameters, MPI_COMM_WORLD),
              MPI_COMM_WORLD,
              out,
              Analysis::run_hooks(parameters.shared, parameters.analysis),
              checkpoints);
            try
              {
                const RunResult result = simulation.run();
                const RunSummary summary =
                  Analysis::summarise_run(result,
                                          simulation.history(),
                                          simulation.model().axial_properties(),
                                          parameters.shared,
                                          parameters.analysis);
                print_summary(summary, summary_text);
                passed = passed && summary.checks_passed;
              }
            catch (const RunError &e)
              {
                // With several models, a model that fails still leaves its
                // history up to the failure to the comparison.
                if (models.size() == 1)
                  throw;
                run_errors +=
                  std::string(run_errors.empty() ? "" : " ") + e.what();
                summary_text << "The " << simulation.model().name()
                             << " model stopped early: " << e.what() << '\n';
              }
            Analysis::ComparedRun run;
            run.label   = Analysis::model_label(type);
            run.history = simulation.history();
            run.mass_per_length =
              simulation.model().mass() / parameters.shared.yarn.length;
            run.axial_stiffness =
              simulation.model().axial_properties().axial_stiffness();
            if (!Parameters::deterministic(output.verbosity))
              run.wall_time = std::chrono::duration<double>(
                                std::chrono::steady_clock::now() - started)
                                .count();
            runs.push_back(std::move(run));
          }
        // Several models: each compared with the DEM, when it ran.
        const auto reference =
          std::find(models.begin(), models.end(), comparison_reference());
        const bool compare = runs.size() > 1 && reference != models.end();
        const auto r = static_cast<unsigned int>(reference - models.begin());
        std::vector<Analysis::ComparisonSummary> comparison;
        if (compare)
          collective_output(MPI_COMM_WORLD, [&] {
            if (is_root)
              comparison = Analysis::compare_models(runs, r, output.directory);
          });
        if (compare && is_root)
          {
            Analysis::print_comparison(comparison, runs, r, summary_text);
            // Plotting is the scripts' job (scripts/run_default.sh calls it),
            // not the library's.
            summary_text << "  plots: python3 scripts/plot_comparison.py "
                            "DIRECTORY draws velocity_comparison.png and "
                            "wave_fronts.png from comparison.csv\n";
          }
        if (is_root)
          Parameters::print_summary_text(summary_text.str(),
                                         output.verbosity,
                                         out);
        collective_output(MPI_COMM_WORLD, [&] {
          if (is_root)
            write_file_atomically(output.directory + "/summary.txt",
                                  summary_text.str());
        });
        if (is_root)
          internal::remove_checkpoints(output.directory);
        if (!run_errors.empty())
          throw RunError(run_errors);
        if (!passed)
          {
            if (is_root)
              std::cerr << "yarn-impact: error: a verification check failed\n";
            return 3;
          }
        return 0;
      }
    catch (const InputError &e)
      {
        if (is_root)
          std::cerr << "yarn-impact: error: " << e.what() << std::endl;
        return 1;
      }
    catch (const RunError &e)
      {
        if (is_root)
          std::cerr << "yarn-impact: error: " << e.what() << std::endl;
        return 4;
      }
    catch (const OutputError &e)
      {
        if (is_root)
          std::cerr << "yarn-impact: error: " << e.what() << std::endl;
        return 5;
      }
    catch (const DirectoryInUse &e)
      {
        if (is_root)
          std::cerr << "yarn-impact: error: " << e.what() << std::endl;
        return 7;
      }
    catch (const Interrupted &e)
      {
        if (is_root)
          std::cerr << "yarn-impact: stopped: " << e.what()
                    << "; continue it with: yarn-impact --restart " << file
                    << std::endl;
        return 6;
      }
  }
} // namespace YarnImpact
