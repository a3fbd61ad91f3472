#ifndef yarn_impact_core_checkpoint_h
#define yarn_impact_core_checkpoint_h

#include <yarn_impact/core/parameter_tools.h>

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace YarnImpact
{
  /**
   * Checkpoints (doc/user-guide.md, "Checkpoint and restart"): the whole
   * state of a run between two steps, written so that a restarted run
   * makes exactly the steps the uninterrupted one would have made.
   *
   * A model's checkpoint in Output/Directory is
   * - `checkpoint_<model>_<slot>_rank<r>.bin`, one binary file per MPI
   *   rank (what that rank holds: its part of the model, and on every rank
   *   the clock, the projectile and the history), in one of two slots
   *   0 and 1 used in turn;
   * - `checkpoint_<model>.txt`, written by rank 0 only after every rank's
   *   file of the new slot is whole: it names the slot, so it always
   *   points to a complete checkpoint. A run killed while writing one
   *   keeps the previous one.
   *
   * Every checkpoint proves that it is whole before anything is restored
   * (format 4): a rank file is a header (magic, format, rank, ranks,
   * generation, length), the state and a CRC-32 of both; the info file
   * records, for the newest checkpoint and the older one in the other
   * slot, a CRC-32 over the rank files' checksums, and the CRC-32 of
   * parameters.prm, and ends with a CRC-32 of itself. A restart whose
   * newest checkpoint is damaged continues from the older one, saying so;
   * a flipped bit is never restored.
   *
   * The state is the memory image of this build (no conversion): a
   * checkpoint is read back by the same program on the same number of
   * ranks, which the restart checks.
   */
  namespace Checkpoint
  {
    /**
     * The state of a run, written into a memory buffer field by field.
     * Sections are marked with a tag, so that a reader of another layout
     * stops at the first difference with a clear message instead of
     * reading garbage.
     */
    class Writer
    {
    public:
      /** Mark the start of a section named @p name. */
      void
      tag(const std::string &name)
      {
        put(name);
      }

      /** A value of a trivially copyable type, as its bytes. */
      template <class T>
      void
      put(const T &value)
      {
        static_assert(std::is_trivially_copyable_v<T>,
                      "only plain values are written as bytes");
        buffer.write(reinterpret_cast<const char *>(&value), sizeof(T));
      }

      /** A vector of plain values: its size, then its elements. */
      template <class T>
      void
      put(const std::vector<T> &values)
      {
        static_assert(std::is_trivially_copyable_v<T>,
                      "only vectors of plain values are written as bytes");
        put(static_cast<std::uint64_t>(values.size()));
        buffer.write(reinterpret_cast<const char *>(values.data()),
                     values.size() * sizeof(T));
      }

      /** A string: its length, then its characters. */
      void
      put(const std::string &text)
      {
        put(static_cast<std::uint64_t>(text.size()));
        buffer.write(text.data(), text.size());
      }

      /** Everything written so far. */
      std::string
      contents() const
      {
        return buffer.str();
      }

    private:
      std::ostringstream buffer;
    };


    /**
     * Reads what a Writer wrote, in the same order. Any mismatch (a
     * truncated file, another section, a vector of another size where the
     * size is fixed) throws an InputError naming the file.
     */
    class Reader
    {
    public:
      /** Read @p state, the verified contents of @p file (read()); the
       * file is named in the messages. */
      Reader(const std::string &file, std::string state);

      /** Expect the section @p name here. */
      void
      tag(const std::string &name);

      /** A value of a trivially copyable type. */
      template <class T>
      void
      get(T &value)
      {
        static_assert(std::is_trivially_copyable_v<T>,
                      "only plain values are read as bytes");
        std::memcpy(&value, take(sizeof(T)), sizeof(T));
      }

      /** A vector of plain values, resized to what was written. */
      template <class T>
      void
      get(std::vector<T> &values)
      {
        static_assert(std::is_trivially_copyable_v<T>,
                      "only vectors of plain values are read as bytes");
        std::uint64_t n = 0;
        get(n);
        if (n > remaining() / std::max<std::size_t>(sizeof(T), 1))
          fail("a vector longer than the file");
        values.resize(n);
        if (n > 0)
          std::memcpy(values.data(), take(n * sizeof(T)), n * sizeof(T));
      }

      /** A vector of plain values that must have the size it has now (the
       * set-up made it): a restart of another set-up is refused. */
      template <class T>
      void
      get_same_size(std::vector<T> &values, const char *what)
      {
        const std::size_t expected = values.size();
        get(values);
        if (values.size() != expected)
          fail(std::string("the ") + what + " has " +
               std::to_string(values.size()) + " entries, this set-up " +
               std::to_string(expected));
      }

      /** A string. */
      void
      get(std::string &text);

      /** Whether every byte was read (checked at the end). */
      void
      expect_end();

    private:
      const char *
      take(const std::size_t n);
      std::size_t
      remaining() const
      {
        return data.size() - position;
      }
      [[noreturn]] void
      fail(const std::string &what) const;

      std::string file;
      std::string data;
      std::size_t position = 0;
    };


    /** The version of the checkpoint files this build writes and reads:
     * 4, with checksums, history rows with the yarn's momentum and a
     * model's own columns, and the energy of each touching contact of a
     * fabric's yarn contact (1, without checksums, 2, with the shorter
     * rows, and 3, without the yarn contact's energies, are refused with a
     * message naming their format). */
    constexpr unsigned int format = 4;

    /** One checkpoint as `checkpoint_<model>.txt` records it. */
    struct Record
    {
      /** Checkpoints written by this run so far, this one included; 0: no
       * checkpoint. */
      unsigned long generation = 0;
      /** Simulated time [s] and step of the state. */
      double time        = 0.;
      unsigned long step = 0;
      /** Whether the model had finished its run (with Model = both, the FE
       * part is kept this way while the DEM part runs). */
      bool completed = false;
      /** CRC-32 over the CRC-32 and length of every rank's file, in rank
       * order. */
      std::uint32_t checksum = 0;
    };

    /** What `checkpoint_<model>.txt` says of the checkpoint it points to
     * (the Record fields), and of the one before it. */
    struct Info : Record
    {
      /** The slot (0 or 1) of the rank files. */
      unsigned int slot = 0;
      /** Number of MPI ranks that wrote it. */
      unsigned int n_ranks = 0;
      /** The checkpoint before this one, in the other slot (generation 0:
       * none): where a restart goes on if this one is damaged. */
      Record older;
    };

    /** `<directory>/checkpoint_<model>.txt`. */
    std::string
    info_file(const std::string &directory, const std::string &model);

    /** `<directory>/checkpoint_<model>_<slot>_rank<rank>.bin`. */
    std::string
    rank_file(const std::string &directory,
              const std::string &model,
              const unsigned int slot,
              const unsigned int rank);

    /**
     * Write a checkpoint (collective): every rank's @p state, with its
     * header and checksum, into the slot after @p previous's, then, once
     * all are whole, rank 0's info file pointing to it and recording
     * @p previous as the older checkpoint. A failed write on any rank
     * throws an OutputError on every rank and leaves the previous
     * checkpoint as it was.
     * @return the info of the checkpoint written
     */
    Info
    write(const std::string &directory,
          const std::string &model,
          const MPI_Comm communicator,
          const Info &previous,
          const double time,
          const unsigned long step,
          const bool completed,
          const std::string &state);

    /**
     * The newest whole checkpoint of the model in @p directory
     * (collective), verified before anything is restored: the info file's
     * own checksum and format, the checksum of parameters.prm, and every
     * rank's file of the slot (header, length, checksum, generation, and
     * the checksum over all of them). If the newest checkpoint fails, the
     * older one is verified the same way and, if whole, returned, with
     * one line on the standard error saying so.
     * @param state set to this rank's state of the checkpoint returned
     * @return its info; `generation == 0` if the model has none
     * @throws InputError naming the file and the cause if no checkpoint is
     * whole, the info file is damaged or of another format, or it was
     * written by another number of ranks than @p communicator has
     */
    Info
    read(const std::string &directory,
         const std::string &model,
         const MPI_Comm communicator,
         std::string &state);

    /**
     * Ask a run to stop on SIGTERM or SIGINT: an impact run within a few
     * steps, with a checkpoint (SignalPoll); an elementary test within a
     * few steps, without. A second signal more than a second after the
     * first ends the process at once, as without the handler; one within
     * a second is the same request delivered twice (mpirun forwards a
     * Ctrl-C that also reached the ranks) and is ignored.
     */
    void
    install_signal_handlers();

    /** The signal received since install_signal_handlers() (SIGTERM,
     * SIGINT), or 0. */
    int
    signal_received();

    /**
     * The signal received by any rank of a communicator, agreed by all
     * ranks at the same step without a blocking reduction per step. Each
     * rank calls poll() once per step. One rank: the signal flag, read at
     * every call. Several ranks: every `period` calls a non-blocking
     * MPI_Iallreduce of the ranks' flags is started and the one started
     * `period` calls before is completed, so that a signal is agreed at
     * most 2 `period` steps after it came, on every rank at the same call,
     * at the cost of one small reduction that has had `period` steps to
     * complete.
     */
    class SignalPoll
    {
    public:
      explicit SignalPoll(const MPI_Comm communicator,
                          const unsigned int period = 4);
      ~SignalPoll();
      SignalPoll(const SignalPoll &) = delete;
      SignalPoll &
      operator=(const SignalPoll &) = delete;

      /** The agreed signal (SIGTERM, SIGINT), or 0; the same on every rank
       * at the same call. Collective every `period` calls. */
      int
      poll();

    private:
      MPI_Comm comm = MPI_COMM_NULL; ///< own duplicate; none on one rank
      unsigned int period;
      unsigned long calls = 0;
      MPI_Request request = MPI_REQUEST_NULL;
      bool pending        = false;
      int local = 0, reduced = 0;
    };

    namespace internal
    {
      /**
       * The signal injection used by the tests (doc/user-guide.md): if the
       * environment variable `YARN_IMPACT_SIGNAL_AT_ROW` holds a number N,
       * the process sends itself SIGTERM at the N-th history row its time
       * loops write (counted over the models of the process, the rows at
       * t = 0 excepted), as a job scheduler would. Called at every such
       * row.
       */
      void
      inject_signal();
    } // namespace internal
  }   // namespace Checkpoint
} // namespace YarnImpact

#endif
