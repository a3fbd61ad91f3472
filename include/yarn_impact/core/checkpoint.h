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
   * The format is the memory image of this build (no conversion): a
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
      /** Read the whole of @p file; @throws InputError if it cannot. */
      explicit Reader(const std::string &file);

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


    /** What `checkpoint_<model>.txt` says of the checkpoint it points to. */
    struct Info
    {
      /** Checkpoints written by this run so far, this one included. */
      unsigned long generation = 0;
      /** The slot (0 or 1) of the rank files. */
      unsigned int slot = 0;
      /** Number of MPI ranks that wrote it. */
      unsigned int n_ranks = 0;
      /** Simulated time [s] and step of the state. */
      double time        = 0.;
      unsigned long step = 0;
      /** Whether the model had finished its run (with Model = both, the FE
       * part is kept this way while the DEM part runs). */
      bool completed = false;
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
     * Write a checkpoint (collective): every rank's @p state into the slot
     * after @p previous's, then, once all are whole, rank 0's info file
     * pointing to it. A failed write on any rank throws an OutputError on
     * every rank and leaves the previous checkpoint as it was.
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
     * The info of the model's checkpoint in @p directory (collective: read
     * on rank 0 and broadcast); `generation == 0` if there is none.
     * @throws InputError if it is unreadable, or was written by another
     * number of ranks than @p communicator has
     */
    Info
    read_info(const std::string &directory,
              const std::string &model,
              const MPI_Comm communicator);

    /**
     * Ask a run to stop with a checkpoint at its next history row on
     * SIGTERM or SIGINT (a second signal ends the process at once, as
     * without the handler).
     */
    void
    install_signal_handlers();

    /** The signal received since install_signal_handlers() (SIGTERM,
     * SIGINT), or 0. */
    int
    signal_received();

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
