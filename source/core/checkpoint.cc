#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/output_file.h>

#include <deal.II/base/mpi.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iterator>

namespace YarnImpact
{
  namespace Checkpoint
  {
    namespace
    {
      volatile std::sig_atomic_t received = 0;

      extern "C" void
      on_signal(int signal)
      {
        // A second signal while the first is still being handled ends the
        // process as it would without the handler.
        if (received != 0)
          {
            std::signal(signal, SIG_DFL);
            std::raise(signal);
            return;
          }
        received = signal;
      }
    } // namespace


    Reader::Reader(const std::string &file)
      : file(file)
    {
      std::ifstream in(file, std::ios::binary);
      if (!in)
        throw InputError("cannot read the checkpoint file '" + file + "'.");
      data.assign(std::istreambuf_iterator<char>(in),
                  std::istreambuf_iterator<char>());
      if (in.bad())
        throw InputError("cannot read the checkpoint file '" + file + "'.");
    }

    void
    Reader::fail(const std::string &what) const
    {
      throw InputError("the checkpoint file '" + file +
                       "' does not fit this run (" + what +
                       "): it is damaged, or was written by another version "
                       "of the program or another set-up.");
    }

    const char *
    Reader::take(const std::size_t n)
    {
      if (n > remaining())
        fail("it ends early");
      const char *p = data.data() + position;
      position += n;
      return p;
    }

    void
    Reader::tag(const std::string &name)
    {
      std::string found;
      get(found);
      if (found != name)
        fail("section '" + found + "' where '" + name + "' was expected");
    }

    void
    Reader::get(std::string &text)
    {
      std::uint64_t n = 0;
      get(n);
      if (n > remaining())
        fail("it ends early");
      text.assign(take(n), n);
    }

    void
    Reader::expect_end()
    {
      if (remaining() != 0)
        fail(std::to_string(remaining()) + " bytes left over");
    }


    std::string
    info_file(const std::string &directory, const std::string &model)
    {
      return directory + "/checkpoint_" + model + ".txt";
    }

    std::string
    rank_file(const std::string &directory,
              const std::string &model,
              const unsigned int slot,
              const unsigned int rank)
    {
      return directory + "/checkpoint_" + model + "_" + std::to_string(slot) +
             "_rank" + std::to_string(rank) + ".bin";
    }


    Info
    write(const std::string &directory,
          const std::string &model,
          const MPI_Comm communicator,
          const Info &previous,
          const double time,
          const unsigned long step,
          const bool completed,
          const std::string &state)
    {
      Info info;
      info.generation = previous.generation + 1;
      info.slot       = previous.generation == 0 ? 0 : 1 - previous.slot;
      info.n_ranks    = dealii::Utilities::MPI::n_mpi_processes(communicator);
      info.time       = time;
      info.step       = step;
      info.completed  = completed;
      const unsigned int rank =
        dealii::Utilities::MPI::this_mpi_process(communicator);
      // Every rank's file whole first: only then may the info point to it.
      collective_output(communicator, [&] {
        write_file_atomically(rank_file(directory, model, info.slot, rank),
                              state);
      });
      collective_output(communicator, [&] {
        if (rank == 0)
          {
            AtomicFile f(info_file(directory, model));
            f.stream().precision(17);
            f.stream() << "# yarn-impact checkpoint of the " << model
                       << " model: restart with yarn-impact --restart\n"
                       << "generation = " << info.generation << '\n'
                       << "slot = " << info.slot << '\n'
                       << "ranks = " << info.n_ranks << '\n'
                       << "time = " << info.time << '\n'
                       << "step = " << info.step << '\n'
                       << "completed = " << (info.completed ? 1 : 0) << '\n';
            f.commit();
          }
      });
      return info;
    }


    Info
    read_info(const std::string &directory,
              const std::string &model,
              const MPI_Comm communicator)
    {
      const std::string file = info_file(directory, model);
      std::string error;
      Info info;
      if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
        {
          std::ifstream in(file);
          if (in)
            {
              std::string line;
              unsigned int found = 0;
              while (std::getline(in, line))
                {
                  if (line.empty() || line[0] == '#')
                    continue;
                  const auto eq = line.find(" = ");
                  if (eq == std::string::npos)
                    break;
                  const std::string key   = line.substr(0, eq);
                  const std::string value = line.substr(eq + 3);
                  char *end               = nullptr;
                  const double x          = std::strtod(value.c_str(), &end);
                  if (end == value.c_str() || *end != '\0')
                    break;
                  if (key == "generation")
                    info.generation = static_cast<unsigned long>(x);
                  else if (key == "slot")
                    info.slot = static_cast<unsigned int>(x);
                  else if (key == "ranks")
                    info.n_ranks = static_cast<unsigned int>(x);
                  else if (key == "time")
                    info.time = x;
                  else if (key == "step")
                    info.step = static_cast<unsigned long>(x);
                  else if (key == "completed")
                    info.completed = x != 0.;
                  else
                    break;
                  ++found;
                }
              if (found != 6 || info.generation == 0 || info.slot > 1)
                error = "the checkpoint file '" + file +
                        "' is damaged (it must hold generation, slot, "
                        "ranks, time, step and completed).";
            }
        }
      error = dealii::Utilities::MPI::broadcast(communicator, error, 0);
      if (!error.empty())
        throw InputError(error);
      info = dealii::Utilities::MPI::broadcast(communicator, info, 0);
      const unsigned int n_ranks =
        dealii::Utilities::MPI::n_mpi_processes(communicator);
      if (info.generation > 0 && info.n_ranks != n_ranks)
        throw InputError("the checkpoint '" + file + "' was written by " +
                         std::to_string(info.n_ranks) +
                         " MPI ranks: restart it on " +
                         std::to_string(info.n_ranks) + ", not " +
                         std::to_string(n_ranks) + ".");
      return info;
    }


    void
    install_signal_handlers()
    {
      received = 0;
      std::signal(SIGTERM, on_signal);
      std::signal(SIGINT, on_signal);
    }

    int
    signal_received()
    {
      return received;
    }


    namespace internal
    {
      void
      inject_signal()
      {
        static const long long at = [] {
          const char *value = std::getenv("YARN_IMPACT_SIGNAL_AT_ROW");
          return value != nullptr ? std::atoll(value) : -1LL;
        }();
        static long long rows = 0;
        if (++rows == at)
          std::raise(SIGTERM);
      }
    } // namespace internal
  }   // namespace Checkpoint
} // namespace YarnImpact
