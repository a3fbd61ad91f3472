#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/output_file.h>

#include <deal.II/base/mpi.h>

#include <boost/crc.hpp>

#include <climits>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <map>

namespace YarnImpact
{
  namespace Checkpoint
  {


    Reader::Reader(const std::string &file, std::string state)
      : file(file)
      , data(std::move(state))
    {}

    void
    Reader::fail(const std::string &what) const
    {
      throw InputError("the checkpoint file '" + file +
                       "' does not fit this run (" + what +
                       "): it was written by another build of the program "
                       "or another set-up.");
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


    namespace
    {
      /**
       * The start of a rank file (format 2 and later). Its length lets a cut or
       * over-long file be told from a damaged one; generation, rank and
       * ranks tell a whole file of another checkpoint. The file ends with
       * the CRC-32 of this header and the state.
       */
      struct Header
      {
        char magic[8];
        std::uint32_t format;
        std::uint32_t rank;
        std::uint32_t n_ranks;
        std::uint32_t unused;
        std::uint64_t generation;
        std::uint64_t length;
      };
      static_assert(sizeof(Header) == 40, "the header is written as bytes");

      constexpr char magic[8] = {'Y', 'I', 'C', 'K', 'P', 'T', '\r', '\n'};

      /** The CRC-32 of @p n bytes at @p data. */
      std::uint32_t
      crc32(const char *data, const std::size_t n)
      {
        boost::crc_32_type crc;
        crc.process_bytes(data, n);
        return crc.checksum();
      }

      /** The checksum of a slot: over every rank's file checksum and
       * length, in rank order (@p records holds both, rank by rank). */
      std::uint32_t
      slot_checksum(const std::vector<std::uint64_t> &records)
      {
        return crc32(reinterpret_cast<const char *>(records.data()),
                     records.size() * sizeof(std::uint64_t));
      }

      /** The whole of @p file, or why it cannot be read. */
      bool
      read_file(const std::string &file, std::string &data, std::string &why)
      {
        std::error_code ec;
        if (std::filesystem::is_directory(file, ec))
          {
            why = "it is a directory";
            return false;
          }
        std::ifstream in(file, std::ios::binary);
        if (!in)
          {
            why = "it cannot be opened: " + std::string(std::strerror(errno));
            return false;
          }
        data.assign(std::istreambuf_iterator<char>(in),
                    std::istreambuf_iterator<char>());
        if (in.bad())
          {
            why = "it cannot be read";
            return false;
          }
        return true;
      }

      /** CRC-32 of parameters.prm in @p directory (of nothing if there is
       * none: a test program may write checkpoints without it). */
      std::uint32_t
      parameters_checksum(const std::string &directory)
      {
        std::string text, why;
        read_file(directory + "/parameters.prm", text, why);
        return crc32(text.data(), text.size());
      }

      /**
       * Check this rank's file of a slot: header, length, checksum, and
       * that it is the file of @p generation, @p rank of @p n_ranks. On
       * success @p data is left holding the state alone and @p record its
       * checksum and length; otherwise the cause is returned.
       */
      std::string
      verify_rank_file(const std::string &file,
                       const unsigned long generation,
                       const unsigned int rank,
                       const unsigned int n_ranks,
                       std::string &data,
                       std::uint64_t record[2])
      {
        std::string why;
        if (!read_file(file, data, why))
          return why;
        static const std::string format_1 =
          std::string("\x16\0\0\0\0\0\0\0yarn-impact checkpoint", 30);
        if (data.compare(0, format_1.size(), format_1) == 0)
          return "it is of checkpoint format 1, written by an earlier "
                 "version of yarn-impact without checksums; this version "
                 "reads format " +
                 std::to_string(format) + " only";
        Header h;
        if (data.size() < sizeof(Header) + sizeof(std::uint32_t))
          return "it is cut (" + std::to_string(data.size()) +
                 " bytes, shorter than its header)";
        std::memcpy(&h, data.data(), sizeof(Header));
        if (std::memcmp(h.magic, magic, sizeof(magic)) != 0)
          return "it does not start as a yarn-impact checkpoint";
        // The length before the checksum, to tell a cut file; the format
        // after it, so that a damaged header is called damaged.
        if (h.length != data.size() - sizeof(Header) - sizeof(std::uint32_t))
          return "its length does not match its header (" +
                 std::to_string(data.size()) + " bytes, the header says " +
                 std::to_string(h.length + sizeof(Header) +
                                sizeof(std::uint32_t)) +
                 "): it is cut or damaged";
        std::uint32_t stored = 0;
        std::memcpy(&stored,
                    data.data() + data.size() - sizeof(stored),
                    sizeof(stored));
        const std::uint32_t computed =
          crc32(data.data(), data.size() - sizeof(stored));
        if (stored != computed)
          return "its checksum does not match its contents";
        if (h.format != format)
          return "it is of checkpoint format " + std::to_string(h.format) +
                 "; this version reads format " + std::to_string(format);
        if (h.generation != generation || h.rank != rank ||
            h.n_ranks != n_ranks)
          return "it holds checkpoint " + std::to_string(h.generation) +
                 " of rank " + std::to_string(h.rank) + " of " +
                 std::to_string(h.n_ranks) + ", not checkpoint " +
                 std::to_string(generation) + " of rank " +
                 std::to_string(rank) + " of " + std::to_string(n_ranks);
        record[0] = computed;
        record[1] = data.size();
        data.resize(data.size() - sizeof(stored));
        data.erase(0, sizeof(Header));
        return "";
      }

      /** The message of the lowest rank with a non-empty @p local one, on
       * every rank ("" if none). */
      std::string
      first_message(const MPI_Comm communicator, const std::string &local)
      {
        int failing =
          local.empty()
            ? INT_MAX
            : static_cast<int>(
                dealii::Utilities::MPI::this_mpi_process(communicator));
        MPI_Allreduce(MPI_IN_PLACE,
                      &failing,
                      1,
                      MPI_INT,
                      MPI_MIN,
                      communicator);
        if (failing == INT_MAX)
          return "";
        return dealii::Utilities::MPI::broadcast(communicator, local, failing);
      }

      /**
       * Verify the slot of @p record (collective): every rank's file, then
       * on rank 0 the checksum over all of them against @p record's. On
       * success @p state holds this rank's state; otherwise returns why,
       * naming the file.
       */
      std::string
      verify_slot(const std::string &directory,
                  const std::string &model,
                  const MPI_Comm communicator,
                  const Record &record,
                  const unsigned int slot,
                  std::string &state)
      {
        const unsigned int rank =
          dealii::Utilities::MPI::this_mpi_process(communicator);
        const unsigned int n_ranks =
          dealii::Utilities::MPI::n_mpi_processes(communicator);
        const std::string file = rank_file(directory, model, slot, rank);
        std::uint64_t mine[2]  = {0, 0};
        std::string why =
          verify_rank_file(file, record.generation, rank, n_ranks, state, mine);
        if (!why.empty())
          why = "'" + file + "': " + why;
        why = first_message(communicator, why);
        if (!why.empty())
          return why;
        std::vector<std::uint64_t> all(rank == 0 ? 2 * n_ranks : 0);
        MPI_Gather(mine,
                   2,
                   MPI_UINT64_T,
                   all.data(),
                   2,
                   MPI_UINT64_T,
                   0,
                   communicator);
        if (rank == 0 && slot_checksum(all) != record.checksum)
          why = "'" + rank_file(directory, model, slot, 0) + "' to '" +
                rank_file(directory, model, slot, n_ranks - 1) +
                "': whole, but not the files that " +
                info_file(directory, model) + " records";
        return dealii::Utilities::MPI::broadcast(communicator, why, 0);
      }

      /**
       * Parse and check the text of an info file (rank 0); returns why it
       * cannot be used, or "".
       */
      std::string
      parse_info(const std::string &text, Info &info, std::uint32_t &parameters)
      {
        std::map<std::string, std::string> values;
        std::size_t end_of_text = std::string::npos;
        for (std::size_t pos = 0; pos < text.size();)
          {
            std::size_t next = text.find('\n', pos);
            if (next == std::string::npos)
              next = text.size();
            const std::string line = text.substr(pos, next - pos);
            if (!line.empty() && line[0] != '#')
              {
                const auto eq = line.find(" = ");
                if (eq == std::string::npos)
                  return "a line without ' = '";
                const std::string key = line.substr(0, eq);
                if (key == "info checksum")
                  end_of_text = pos;
                values[key] = line.substr(eq + 3);
              }
            pos = next + 1;
          }
        if (values.count("format") == 0 && values.count("info checksum") == 0)
          return values.count("generation") > 0
                   ? "it is of checkpoint format 1, written by an earlier "
                     "version of yarn-impact without checksums; this version "
                     "reads format " +
                       std::to_string(format) + " only"
                   : "it holds no checkpoint record";
        // Every field is a whole number but the times.
        const auto number =
          [&](const std::string &key, auto &value, const bool real = false) {
            const auto it = values.find(key);
            if (it == values.end() || it->second.empty())
              return false;
            char *end = nullptr;
            errno     = 0;
            if (real)
              value = std::strtod(it->second.c_str(), &end);
            else
              {
                if (it->second[0] == '-')
                  return false;
                value = std::strtoull(it->second.c_str(), &end, 10);
              }
            return *end == '\0' && errno == 0;
          };
        unsigned long long checksum = 0;
        if (end_of_text == std::string::npos ||
            !number("info checksum", checksum))
          return "its own checksum is missing";
        if (checksum != crc32(text.data(), end_of_text))
          return "its checksum does not match its contents";
        unsigned long long fmt = 0, generation = 0, slot = 0, ranks = 0,
                           step = 0, completed = 0, sum = 0,
                           older_generation = 0, older_step = 0,
                           older_completed = 0, older_sum = 0,
                           parameter_sum = 0;
        double time = 0., older_time = 0.;
        if (!number("format", fmt))
          return "its format is missing";
        if (fmt != format)
          return "it is of checkpoint format " + std::to_string(fmt) +
                 "; this version reads format " + std::to_string(format);
        if (!number("generation", generation) || !number("slot", slot) ||
            !number("ranks", ranks) || !number("time", time, true) ||
            !number("step", step) || !number("completed", completed) ||
            !number("checksum", sum) ||
            !number("older generation", older_generation) ||
            !number("older time", older_time, true) ||
            !number("older step", older_step) ||
            !number("older completed", older_completed) ||
            !number("older checksum", older_sum) ||
            !number("parameters checksum", parameter_sum))
          return "a field is missing or not a number";
        if (generation == 0 || slot > 1 || ranks == 0 || completed > 1 ||
            older_completed > 1 ||
            (older_generation != 0 && older_generation + 1 != generation) ||
            sum > UINT32_MAX || older_sum > UINT32_MAX ||
            parameter_sum > UINT32_MAX)
          return "its fields do not fit together";
        info.generation       = generation;
        info.slot             = slot;
        info.n_ranks          = ranks;
        info.time             = time;
        info.step             = step;
        info.completed        = completed != 0;
        info.checksum         = sum;
        info.older.generation = older_generation;
        info.older.time       = older_time;
        info.older.step       = older_step;
        info.older.completed  = older_completed != 0;
        info.older.checksum   = older_sum;
        parameters            = parameter_sum;
        return "";
      }
    } // namespace


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
      if (previous.generation > 0)
        info.older = previous;
      const unsigned int rank =
        dealii::Utilities::MPI::this_mpi_process(communicator);

      Header h;
      std::memcpy(h.magic, magic, sizeof(magic));
      h.format     = format;
      h.rank       = rank;
      h.n_ranks    = info.n_ranks;
      h.unused     = 0;
      h.generation = info.generation;
      h.length     = state.size();
      std::string file(reinterpret_cast<const char *>(&h), sizeof(h));
      file.reserve(sizeof(h) + state.size() + sizeof(std::uint32_t));
      file += state;
      const std::uint32_t crc = crc32(file.data(), file.size());
      file.append(reinterpret_cast<const char *>(&crc), sizeof(crc));
      // Every rank's file whole first: only then may the info point to it.
      collective_output(communicator, [&] {
        write_file_atomically(rank_file(directory, model, info.slot, rank),
                              file);
      });
      const std::uint64_t mine[2] = {crc, file.size()};
      std::vector<std::uint64_t> all(rank == 0 ? 2 * info.n_ranks : 0);
      MPI_Gather(mine,
                 2,
                 MPI_UINT64_T,
                 all.data(),
                 2,
                 MPI_UINT64_T,
                 0,
                 communicator);
      if (rank == 0)
        info.checksum = slot_checksum(all);
      MPI_Bcast(&info.checksum, 1, MPI_UINT32_T, 0, communicator);

      collective_output(communicator, [&] {
        if (rank == 0)
          {
            std::ostringstream text;
            text.precision(17);
            text << "# yarn-impact checkpoint of the " << model
                 << " model: restart with yarn-impact --restart\n"
                 << "format = " << format << '\n'
                 << "generation = " << info.generation << '\n'
                 << "slot = " << info.slot << '\n'
                 << "ranks = " << info.n_ranks << '\n'
                 << "time = " << info.time << '\n'
                 << "step = " << info.step << '\n'
                 << "completed = " << (info.completed ? 1 : 0) << '\n'
                 << "checksum = " << info.checksum << '\n'
                 << "older generation = " << info.older.generation << '\n'
                 << "older time = " << info.older.time << '\n'
                 << "older step = " << info.older.step << '\n'
                 << "older completed = " << (info.older.completed ? 1 : 0)
                 << '\n'
                 << "older checksum = " << info.older.checksum << '\n'
                 << "parameters checksum = " << parameters_checksum(directory)
                 << '\n';
            const std::string body = text.str();
            write_file_atomically(
              info_file(directory, model),
              body + "info checksum = " +
                std::to_string(crc32(body.data(), body.size())) + '\n');
          }
      });
      return info;
    }


    Info
    read(const std::string &directory,
         const std::string &model,
         const MPI_Comm communicator,
         std::string &state)
    {
      const std::string file = info_file(directory, model);
      const bool is_root =
        dealii::Utilities::MPI::this_mpi_process(communicator) == 0;
      std::string error;
      Info info;
      if (is_root && std::filesystem::exists(file))
        {
          std::string text, why;
          std::uint32_t parameters = 0;
          if (!read_file(file, text, why) ||
              !(why = parse_info(text, info, parameters)).empty())
            error = "the checkpoint file '" + file + "' cannot be used (" +
                    why + "): there is no checkpoint to continue from.";
          else if (parameters != parameters_checksum(directory))
            error = "the checkpoint '" + file + "' was written with another '" +
                    directory +
                    "/parameters.prm' (its checksum differs): the "
                    "parameters were changed or damaged since.";
        }
      error = dealii::Utilities::MPI::broadcast(communicator, error, 0);
      if (!error.empty())
        throw InputError(error);
      info = dealii::Utilities::MPI::broadcast(communicator, info, 0);
      if (info.generation == 0)
        return info;
      const unsigned int n_ranks =
        dealii::Utilities::MPI::n_mpi_processes(communicator);
      if (info.n_ranks != n_ranks)
        throw InputError("the checkpoint '" + file + "' was written by " +
                         std::to_string(info.n_ranks) +
                         " MPI ranks: restart it on " +
                         std::to_string(info.n_ranks) + ", not " +
                         std::to_string(n_ranks) + ".");

      const std::string newest =
        verify_slot(directory, model, communicator, info, info.slot, state);
      if (newest.empty())
        return info;
      const std::string damaged = "the newest checkpoint of the " + model +
                                  " model is damaged: " + newest;
      if (info.older.generation == 0)
        throw InputError(damaged +
                         "; there is no older checkpoint to continue from.");
      const std::string older = verify_slot(directory,
                                            model,
                                            communicator,
                                            info.older,
                                            1 - info.slot,
                                            state);
      if (!older.empty())
        throw InputError(damaged + "; so is the older one: " + older + ".");
      if (is_root)
        std::cerr << "yarn-impact: warning: " << damaged
                  << "; continuing from the older checkpoint at t = "
                  << info.older.time * 1e6 << " us (step " << info.older.step
                  << ")." << std::endl;
      Info whole;
      static_cast<Record &>(whole) = info.older;
      whole.slot                   = 1 - info.slot;
      whole.n_ranks                = info.n_ranks;
      return whole;
    }
  } // namespace Checkpoint
} // namespace YarnImpact
