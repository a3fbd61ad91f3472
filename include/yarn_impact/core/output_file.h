#ifndef yarn_impact_core_output_file_h
#define yarn_impact_core_output_file_h

#include <mpi.h>

#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>

namespace YarnImpact
{
  /**
   * An output file could not be written: disk full, permission, a file
   * system error. The message names the file and the cause; the program
   * prints it on one line and exits with code 5. What was written before
   * stays whole: the history up to its last complete row, the earlier
   * snapshots, no half-written summary or snapshot under its final name.
   */
  class OutputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /**
   * A file written whole or not at all. The text is assembled in memory
   * (stream()); commit() writes it under a temporary name in the same
   * directory, checks every write and the close, and renames it to its
   * final name. A failed commit removes the temporary file, leaves any
   * earlier file of that name untouched and throws an OutputError.
   */
  class AtomicFile
  {
  public:
    /** A file that will be @p path once committed. */
    explicit AtomicFile(std::string path);

    /** Where to write the contents. */
    std::ostream &
    stream()
    {
      return contents;
    }

    /** Write the contents to the final path (see the class). */
    void
    commit();

  private:
    std::string path;
    std::ostringstream contents;
  };

  /** Write @p text to @p path with an AtomicFile. */
  void
  write_file_atomically(const std::string &path, const std::string &text);

  /**
   * A file that grows by whole records (the history CSV): each append()
   * writes one or more complete rows; if a write fails part-way, the file
   * is cut back to its size before that append and an OutputError is
   * thrown, so the file always ends with a whole row.
   */
  class AppendFile
  {
  public:
    AppendFile()                   = default;
    AppendFile(const AppendFile &) = delete;
    AppendFile &
    operator=(const AppendFile &) = delete;
    ~AppendFile();

    /** Create (or truncate) @p path; throws an OutputError if it cannot. */
    void
    open(const std::string &path);

    /** Whether open() was called on this process. */
    bool
    is_open() const
    {
      return descriptor >= 0;
    }

    /** Append @p text (whole rows) or throw, leaving the file as it was. */
    void
    append(const std::string &text);

  private:
    std::string path;
    int descriptor = -1;
    /** Bytes in the file after the last successful append. */
    long size = 0;
  };

  /**
   * Run @p write (a write of output files, possibly on some ranks only) on
   * every rank of @p communicator and make its failure collective: if it
   * throws an OutputError on any rank, every rank throws an OutputError
   * with the message of the lowest failing rank. Without this a rank that
   * fails alone would leave the others waiting in the next collective call.
   */
  void
  collective_output(const MPI_Comm communicator,
                    const std::function<void()> &write);

  namespace internal
  {
    /**
     * The fault injection used by the tests (doc/user-guide.md): if the
     * environment variable `YARN_IMPACT_DISK_FULL_AFTER` holds a number N,
     * every write of output after the first N bytes of this process fails
     * as on a full disk (ENOSPC). Returns how many of @p bytes may still
     * be written.
     */
    std::size_t
    injected_write_allowance(const std::size_t bytes);
  } // namespace internal
} // namespace YarnImpact

#endif
