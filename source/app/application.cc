#include <yarn_impact/analysis/model_comparison.h>
#include <yarn_impact/analysis/run_summary.h>
#include <yarn_impact/app/application.h>
#include <yarn_impact/app/model_factory.h>
#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/output_file.h>
#include <yarn_impact/core/output_lock.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
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

    /** @p text with its first letter in lower case (system messages). */
    std::string
    lower_first(std::string text)
    {
      if (!text.empty())
        text[0] =
          static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
      return text;
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

    /**
     * Whether @p name is one of the files a run writes into Output/Directory
     * (parameters, summary, history, snapshots of either model, the model
     * comparison and its plots, elementary-test curves). Only these are
     * taken as an earlier run's output, and only these are removed with
     * Output/Overwrite: a user's own files in the directory are left alone.
     */
    bool
    is_run_output(const std::string &name)
    {
      const auto starts = [&](const std::string &prefix) {
        return name.compare(0, prefix.size(), prefix) == 0;
      };
      const auto ends = [&](const std::string &suffix) {
        return name.size() >= suffix.size() &&
               name.compare(name.size() - suffix.size(),
                            suffix.size(),
                            suffix) == 0;
      };
      return name == "parameters.prm" || name == "summary.txt" ||
             name == "comparison.csv" || name == "velocity_comparison.png" ||
             name == "wave_fronts.png" ||
             (starts("history_") && ends(".csv")) ||
             (starts("checkpoint_") && (ends(".txt") || ends(".bin"))) ||
             (starts("elementary_") &&
              (ends(".csv") || ends(".csv.partial"))) ||
             ends(".pvd") || ends(".pvtu") || ends(".vtu") ||
             // A write that was interrupted (AtomicFile's temporary name).
             (ends(".tmp") && is_run_output(name.substr(0, name.size() - 4)));
    }

    /**
     * Take @p lock of Output/Directory @p dir on rank 0 (OutputLock),
     * creating the directory first if @p create. Without @p create a
     * missing directory is left to the caller's checks. Returns the
     * refusal, if any, and whether it is a DirectoryInUse.
     */
    std::pair<std::string, bool>
    lock_directory(OutputLock &lock, const std::string &dir, const bool create)
    {
      std::error_code ec;
      if (create)
        std::filesystem::create_directories(dir, ec);
      else if (!std::filesystem::is_directory(dir, ec))
        return {"", false};
      if (ec)
        return {"Parameter 'Output/Directory' = '" + dir +
                  "' cannot be used for output (" + lower_first(ec.message()) +
                  ").",
                false};
      try
        {
          lock.acquire(dir);
        }
      catch (const DirectoryInUse &e)
        {
          return {e.what(), true};
        }
      catch (const InputError &e)
        {
          return {e.what(), false};
        }
      return {"", false};
    }

    /** Throw rank 0's refusal @p error (empty: none) on every rank, as a
     * DirectoryInUse if @p in_use, else as an InputError. */
    void
    throw_collectively(std::string error, bool in_use)
    {
      error  = Utilities::MPI::broadcast(MPI_COMM_WORLD, error, 0);
      in_use = Utilities::MPI::broadcast(MPI_COMM_WORLD, in_use, 0);
      if (error.empty())
        return;
      if (in_use)
        throw DirectoryInUse(error);
      throw InputError(error);
    }

    /**
     * Make Output/Directory ready for a run before anything is written:
     * refuse an input file the run would overwrite with its parameters.prm;
     * create the directory and take its @p lock, so that no other run
     * checks or writes it from here on (a directory in use is refused);
     * refuse a directory that holds an earlier run's output (runs must not
     * mix), or with Output/Overwrite remove that output; make sure it is
     * writable. Decided on rank 0 (one file system view, one message) and
     * broadcast; throws DirectoryInUse or InputError on every rank.
     */
    void
    prepare_output_directory(const Parameters::Output &output,
                             const std::string &input_file,
                             const bool is_root,
                             std::ostream &out,
                             OutputLock &lock)
    {
      namespace fs             = std::filesystem;
      const std::string &dir   = output.directory;
      const std::string quoted = "Parameter 'Output/Directory' = '" + dir + "'";
      std::string error;
      bool in_use = false;
      if (is_root)
        {
          std::error_code ec;
          const std::string resolved = dir + "/parameters.prm";
          std::vector<std::string> earlier;
          if (fs::equivalent(input_file, resolved, ec))
            error = quoted + " would overwrite the parameter file '" +
                    input_file +
                    "' with the run's parameters.prm: move the file or "
                    "choose another directory.";
          else
            std::tie(error, in_use) = lock_directory(lock, dir, true);
          if (error.empty())
            {
              for (fs::directory_iterator it(dir, ec), last; !ec && it != last;
                   it.increment(ec))
                if (!it->is_directory(ec) &&
                    is_run_output(it->path().filename().string()))
                  earlier.push_back(it->path().filename().string());
              if (ec)
                error = quoted + " cannot be used for output (" +
                        lower_first(ec.message()) + ").";
            }
          // The files that tell which run it was first.
          const auto rank = [](const std::string &name) {
            return name == "parameters.prm"              ? 0
                   : name == "summary.txt"               ? 1
                   : name.compare(0, 8, "history_") == 0 ? 2
                                                         : 3;
          };
          std::sort(earlier.begin(),
                    earlier.end(),
                    [&](const std::string &a, const std::string &b) {
                      return std::make_pair(rank(a), a) <
                             std::make_pair(rank(b), b);
                    });
          if (error.empty() && !earlier.empty() && !output.overwrite)
            {
              std::string found;
              for (unsigned int i = 0; i < earlier.size() && i < 3; ++i)
                found += (i > 0 ? ", " : "") + earlier[i];
              if (earlier.size() > 3)
                found += " and " + std::to_string(earlier.size() - 3) + " more";
              error = quoted + " holds the output of an earlier run (" +
                      std::to_string(earlier.size()) + " files: " + found +
                      "): choose another directory, remove it, or set "
                      "Output/Overwrite = true to replace that output.";
            }
          else if (error.empty() && !earlier.empty())
            {
              for (const auto &name : earlier)
                if (!fs::remove(dir + "/" + name, ec) && ec)
                  {
                    error = quoted + ": cannot remove '" + dir + "/" + name +
                            "' of an earlier run (" +
                            lower_first(ec.message()) + ").";
                    break;
                  }
              // Test verbosity prints only what every run prints alike.
              if (error.empty() &&
                  output.verbosity != Parameters::Verbosity::test)
                out << "Output/Overwrite: removed the " << earlier.size()
                    << " output files of an earlier run from '" << dir << "'\n";
            }
          if (error.empty())
            {
              const std::string probe = dir + "/.yarn-impact-probe";
              std::ofstream f(probe);
              const bool ok = static_cast<bool>(f << "probe");
              f.close();
              fs::remove(probe, ec);
              if (!ok)
                error = quoted + " cannot be used for output (not writable).";
            }
        }
      throw_collectively(error, in_use);
    }

    /**
     * Make sure a restart continues the run that wrote the checkpoints in
     * Output/Directory: its parameters.prm must be @p resolved (the same
     * parameters, whatever the file's layout), and at least one model
     * must have a checkpoint there. Its @p lock is taken first: a run
     * still writing there is not continued by a second process. Decided
     * on rank 0 and broadcast; throws DirectoryInUse or InputError on
     * every rank.
     */
    void
    check_restart(const AllParameters &p,
                  const std::string &resolved,
                  OutputLock &lock)
    {
      const std::string &dir = p.shared.output.directory;
      std::string error;
      bool in_use = false;
      if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        std::tie(error, in_use) = lock_directory(lock, dir, false);
      if (error.empty() && Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        {
          std::ifstream in(dir + "/parameters.prm");
          std::ostringstream earlier;
          earlier << in.rdbuf();
          bool any = false;
          for (const std::string name : {"fe", "dem", "hybrid"})
            any =
              any || std::filesystem::exists(Checkpoint::info_file(dir, name));
          if (!in)
            error = "--restart: Output/Directory = '" + dir +
                    "' holds no parameters.prm of an earlier run to continue.";
          else if (earlier.str() != resolved)
            error = "--restart: the parameters differ from those of the run "
                    "in Output/Directory = '" +
                    dir +
                    "' (its parameters.prm): a restart must continue the "
                    "same run; start a new one without --restart.";
          else if (!any)
            error = "--restart: Output/Directory = '" + dir +
                    "' holds no checkpoint (checkpoint_fe.txt, "
                    "checkpoint_dem.txt or checkpoint_hybrid.txt): the run "
                    "stopped before writing one; "
                    "start it again without --restart (Output/Overwrite = "
                    "true).";
        }
      throw_collectively(error, in_use);
    }

    /** Remove the checkpoints of a run that has ended (rank 0): they are
     * large, and there is nothing left to continue. */
    void
    remove_checkpoints(const std::string &dir)
    {
      namespace fs = std::filesystem;
      std::error_code ec;
      for (fs::directory_iterator it(dir, ec), last; !ec && it != last;
           it.increment(ec))
        {
          const std::string name = it->path().filename().string();
          if (name.compare(0, 11, "checkpoint_") == 0 && is_run_output(name))
            fs::remove(it->path(), ec);
        }
    }
  } // namespace


  void
  AllParameters::declare_parameters(ParameterHandler &prm)
  {
    declare_model_type(prm);
    Parameters::Shared::declare_parameters(prm);
    FE::Parameters::declare_parameters(prm);
    DEM::Parameters::declare_parameters(prm);
    Coupling::HybridParameters::declare_parameters(prm);
    DEM::ElementaryTestParameters::declare_parameters(prm);
  }

  void
  AllParameters::parse_parameters(ParameterHandler &prm)
  {
    model = parse_model_type(prm);
    shared.parse_parameters(prm);
    fe.parse_parameters(prm);
    dem.parse_parameters(prm);
    hybrid.parse_parameters(prm);
    elementary.parse_parameters(prm);
    Parameters::require(elementary.loading == DEM::ElementaryLoading::none ||
                          model == ModelType::dem,
                        "Elementary test/Loading",
                        "is a loading of the DEM model: it needs Model = dem");
    // Every set-up check that needs no MPI ranks is made here, so that
    // `--check` refuses what the run would, and a run refuses before it
    // writes anything (with Model = both, before the FE part runs).
    if (elementary.loading != DEM::ElementaryLoading::none)
      DEM::validate(shared, dem, true);
    else if (model == ModelType::hybrid)
      Coupling::validate(shared, fe, dem, hybrid);
    else
      {
        if (model != ModelType::dem)
          FE::validate(shared, fe);
        if (model != ModelType::fe)
          DEM::validate(shared, dem);
      }
  }

  AllParameters
  read_parameters(const std::string &file, ParameterHandler &prm)
  {
    {
      // Checked before opening: deal.II reads a directory as an empty file
      // (the default case would run), and opening a fifo blocks.
      const std::string what = "cannot open the parameter file '" + file + "'";
      std::error_code ec;
      const auto status = std::filesystem::status(file, ec);
      if (ec)
        throw InputError(what + ": " + lower_first(ec.message()) + ".");
      if (std::filesystem::is_directory(status))
        throw InputError(what + ": it is a directory.");
      if (!std::filesystem::is_regular_file(status))
        throw InputError(what + ": it is not a regular file (a fifo, socket or "
                                "device).");
      std::ifstream in(file);
      if (!in)
        throw InputError(what + ": " + lower_first(std::strerror(errno)) + ".");
    }
    try
      {
        prm.parse_input(file, "", false, false);
      }
    catch (const ExceptionBase &e)
      {
        std::ostringstream info;
        e.print_info(info);
        throw InputError(one_line(info.str()));
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
  run_application(int argc, char **argv)
  {
    const bool is_root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
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
        AllParameters parameters = read_parameters(file, prm);
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

        const auto &output = parameters.shared.output;
        // Held until the run returns: one owner per output directory.
        OutputLock lock;
        std::ostringstream resolved;
        prm.print_parameters(resolved, ParameterHandler::ShortPRM);
        if (restart)
          {
            if (parameters.elementary.loading != DEM::ElementaryLoading::none)
              throw InputError("--restart: the elementary tests (Elementary "
                               "test/Loading) write no checkpoints; run them "
                               "again from the start.");
            check_restart(parameters, resolved.str(), lock);
          }
        else
          {
            prepare_output_directory(output, file, is_root, out, lock);
            collective_output(MPI_COMM_WORLD, [&] {
              if (is_root)
                write_file_atomically(output.directory + "/parameters.prm",
                                      resolved.str());
            });
          }
        // From here a SIGTERM or SIGINT stops the run at its next history
        // row with a checkpoint (exit code 6).
        Checkpoint::install_signal_handlers();

        if (parameters.elementary.loading != DEM::ElementaryLoading::none)
          {
            const bool passed = DEM::run_elementary_test(parameters.shared,
                                                         parameters.dem,
                                                         parameters.elementary,
                                                         MPI_COMM_WORLD,
                                                         out);
            if (!passed)
              {
                if (is_root)
                  std::cerr
                    << "yarn-impact: error: a verification check failed\n";
                return 3;
              }
            return 0;
          }

        std::vector<ModelType> models;
        if (parameters.model == ModelType::both)
          models = {ModelType::fe, ModelType::dem};
        else
          models = {parameters.model};

        bool passed = true;
        std::ostringstream summary_text;
        std::vector<std::vector<HistoryRow>> histories;
        std::string run_errors;
        double mass_per_length[2] = {0., 0.}, axial_stiffness[2] = {0., 0.};
        for (const auto type : models)
          {
            CheckpointOptions checkpoints;
            checkpoints.restart = restart;
            // With both models, the FE's end state lets a restart in the
            // DEM part compare with it.
            checkpoints.keep_final_state = (type != models.back());
            ImpactSimulation simulation(parameters.shared,
                                        create_model(type,
                                                     parameters,
                                                     MPI_COMM_WORLD),
                                        MPI_COMM_WORLD,
                                        out,
                                        Analysis::run_hooks(parameters.shared),
                                        checkpoints);
            try
              {
                const RunResult result = simulation.run();
                const RunSummary summary =
                  Analysis::summarise_run(result,
                                          simulation.history(),
                                          simulation.model().axial_properties(),
                                          parameters.shared);
                print_summary(summary, summary_text);
                passed = passed && summary.checks_passed;
              }
            catch (const RunError &e)
              {
                // With both models, a model that fails still leaves its
                // history up to the failure to the comparison.
                if (models.size() == 1)
                  throw;
                run_errors +=
                  std::string(run_errors.empty() ? "" : " ") + e.what();
                summary_text << "The " << simulation.model().name()
                             << " model stopped early: " << e.what() << '\n';
              }
            mass_per_length[histories.size()] =
              simulation.model().mass() / parameters.shared.yarn.length;
            axial_stiffness[histories.size()] =
              simulation.model().axial_properties().axial_stiffness();
            histories.push_back(simulation.history());
          }
        Analysis::ComparisonSummary comparison;
        if (histories.size() == 2)
          collective_output(MPI_COMM_WORLD, [&] {
            if (is_root)
              comparison = Analysis::compare_models(histories[0],
                                                    histories[1],
                                                    output.directory);
          });
        if (histories.size() == 2 && is_root)
          {
            Analysis::print_comparison(comparison,
                                       mass_per_length,
                                       axial_stiffness,
                                       histories[0],
                                       histories[1],
                                       summary_text);
            // Plotting is the scripts' job (scripts/run_default.sh calls it),
            // not the library's.
            summary_text << "  plots: python3 scripts/plot_comparison.py "
                            "DIRECTORY draws velocity_comparison.png and "
                            "wave_fronts.png from comparison.csv\n";
          }
        if (is_root)
          out << summary_text.str();
        collective_output(MPI_COMM_WORLD, [&] {
          if (is_root)
            write_file_atomically(output.directory + "/summary.txt",
                                  summary_text.str());
        });
        if (is_root)
          remove_checkpoints(output.directory);
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
