// The run's Output/Directory: its lock, the check that it holds no earlier
// run (or its removal with Output/Overwrite), the checks of a --restart,
// and the removal of a finished run's checkpoints (doc/user-guide.md, "One
// run, one folder").

#include <yarn_impact/app/output_directory.h>
#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/model_registry.h>
#include <yarn_impact/core/output_file.h>
#include <yarn_impact/core/parameter_tools.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
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
    /** @p text with its first letter in lower case (system messages). */
    std::string
    lower_first(std::string text)
    {
      if (!text.empty())
        text[0] =
          static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
      return text;
    }

    /**
     * Whether @p name is one of the files a run writes into Output/Directory
     * (parameters, summary, history, fibre breaks, snapshots of any model
     * (the hybrid's multiblock `.vtm` too), the model comparison and its
     * plots, elementary-test curves). Only these are
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
             (starts("breaks_") && ends(".csv")) ||
             (starts("checkpoint_") && (ends(".txt") || ends(".bin"))) ||
             (starts("elementary_") &&
              (ends(".csv") || ends(".csv.partial"))) ||
             ends(".pvd") || ends(".pvtu") || ends(".vtu") || ends(".vtm") ||
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
     * The entries of a parameter text in deal.II's ShortPRM layout (as the
     * run writes parameters.prm): "Subsection/Entry" -> value.
     */
    std::map<std::string, std::string>
    entries_of(const std::string &text)
    {
      std::map<std::string, std::string> entries;
      std::vector<std::string> path;
      std::istringstream in(text);
      std::string line;
      const auto trim = [](const std::string &t) {
        const auto b = t.find_first_not_of(" \t\r");
        const auto e = t.find_last_not_of(" \t\r");
        return b == std::string::npos ? std::string() : t.substr(b, e - b + 1);
      };
      while (std::getline(in, line))
        {
          const std::size_t hash = line.find('#');
          if (hash != std::string::npos)
            line.erase(hash);
          line = trim(line);
          if (line.compare(0, 11, "subsection ") == 0)
            path.push_back(trim(line.substr(11)));
          else if (line == "end" && !path.empty())
            path.pop_back();
          else if (line.compare(0, 4, "set ") == 0)
            {
              const std::size_t eq = line.find('=');
              std::string name;
              for (const auto &section : path)
                name += section + "/";
              name +=
                trim(line.substr(4,
                                 eq == std::string::npos ? std::string::npos
                                                         : eq - 4));
              entries[name] =
                eq == std::string::npos ? "" : trim(line.substr(eq + 1));
            }
        }
      return entries;
    }

    /**
     * The parameters whose values differ between @p earlier and @p now
     * (ShortPRM texts), Output/Directory left out (a run's folder may be
     * moved): "Time/End time ('4e-6' there, '8e-6' here)", the first few.
     */
    std::string
    differing_parameters(const std::string &earlier, const std::string &now)
    {
      const auto a = entries_of(earlier), b = entries_of(now);
      std::vector<std::string> differ;
      for (const auto &[name, value] : b)
        {
          if (name == "Output/Directory")
            continue;
          const auto it = a.find(name);
          if (it == a.end())
            differ.push_back(name + " (not in its parameters.prm)");
          else if (it->second != value)
            differ.push_back(name + " ('" + it->second + "' there, '" + value +
                             "' here)");
        }
      for (const auto &[name, value] : a)
        if (name != "Output/Directory" && b.find(name) == b.end())
          differ.push_back(name + " (unknown to this version)");
      std::string text;
      for (std::size_t i = 0; i < differ.size() && i < 4; ++i)
        text += (i > 0 ? ", " : "") + differ[i];
      if (differ.size() > 4)
        text += " and " + std::to_string(differ.size() - 4) + " more";
      return text;
    }
  } // namespace


  namespace internal
  {
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
                             const std::vector<std::string> &input_files,
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
          for (const auto &input_file : input_files)
            if (error.empty() && fs::equivalent(input_file, resolved, ec))
              error = quoted + " would overwrite the parameter file '" +
                      input_file +
                      "' with the run's parameters.prm: move the file or "
                      "choose another directory.";
          if (error.empty())
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
              if (error.empty() && !Parameters::deterministic(output.verbosity))
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
     * Output/Directory: its parameters.prm must hold the parameters of
     * @p resolved (whatever the file's layout), Output/Directory aside (a
     * run's folder may be moved and continued there), and at least one
     * model must have a checkpoint there. Its @p lock is taken first: a run
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
      if (error.empty() &&
          Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        {
          namespace fs = std::filesystem;
          std::error_code ec;
          const std::string earlier_file = dir + "/parameters.prm";
          std::string earlier, why;
          bool any = false;
          for (const std::string &name : ModelRegistry::names())
            any = any || fs::exists(Checkpoint::info_file(dir, name), ec);
          const bool finished = fs::exists(dir + "/summary.txt", ec);
          if (!fs::is_directory(dir, ec))
            why = "missing";
          else if (!fs::exists(earlier_file, ec))
            why = "missing";
          else
            {
              try
                {
                  earlier =
                    Parameters::read_parameter_file(earlier_file, false).text;
                }
              catch (const InputError &e)
                {
                  why = e.what();
                }
            }
          if (why == "missing")
            error = "--restart: Output/Directory = '" + dir +
                    "' holds no parameters.prm of an earlier run to continue.";
          else if (!why.empty())
            error = "--restart: the run in Output/Directory = '" + dir +
                    "' cannot be continued: " + why;
          else if (earlier != resolved &&
                   !differing_parameters(earlier, resolved).empty())
            error = "--restart: the parameters differ from those of the run "
                    "in Output/Directory = '" +
                    dir + "' (its parameters.prm): " +
                    differing_parameters(earlier, resolved) +
                    "; a restart must continue the same run: restore them, "
                    "or start a new run in another Output/Directory.";
          else if (!any && finished)
            error = "--restart: the run in Output/Directory = '" + dir +
                    "' has finished (its summary.txt is written): there is "
                    "nothing to continue, and its results are kept. To run "
                    "it again, choose another Output/Directory.";
          else if (!any)
            error = "--restart: Output/Directory = '" + dir +
                    "' holds no checkpoint (checkpoint_fe.txt, "
                    "checkpoint_dem.txt or checkpoint_hybrid.txt): the run "
                    "stopped before writing one; start it again without "
                    "--restart in another Output/Directory (its partial "
                    "output there is kept).";
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
  } // namespace internal
} // namespace YarnImpact
