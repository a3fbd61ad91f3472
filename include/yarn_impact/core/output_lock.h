#ifndef yarn_impact_core_output_lock_h
#define yarn_impact_core_output_lock_h

#include <stdexcept>
#include <string>

namespace YarnImpact
{
  /**
   * Output/Directory is owned by another live run (OutputLock): the message
   * names the directory and the process and host that hold it. The
   * program prints it on one line and exits with code 7, on every rank.
   */
  class DirectoryInUse : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };


  /**
   * One owner per output directory (doc/user-guide.md, "One run, one
   * folder"): an exclusive lock on `<directory>/.yarn-impact.lock`, taken
   * before the directory is checked and held until the object is
   * destroyed, that is for the whole run or restart. The file holds the
   * owner's process id and host name, for the message of a process that
   * is refused.
   *
   * The lock is a flock(2) lock, not the file's existence: the kernel
   * releases it when its owner dies, however it dies (SIGKILL, a node
   * crash), so a lock file left behind never blocks a later run and no
   * stale-lock guessing is needed. For the same reason the file is never
   * removed: removing it while another process has it open would let two
   * processes lock two different files of the same name.
   *
   * Taken by one process (rank 0); the application broadcasts the outcome
   * so that every rank stops with the same exit code.
   */
  class OutputLock
  {
  public:
    /** Holds nothing. */
    OutputLock() = default;

    OutputLock(const OutputLock &) = delete;
    OutputLock &
    operator=(const OutputLock &) = delete;

    /** Releases the lock, if held. */
    ~OutputLock();

    /**
     * Take the lock of @p directory, which must exist, without waiting.
     * @throws DirectoryInUse if another process holds it
     * @throws InputError if the lock file cannot be created or locked
     */
    void
    acquire(const std::string &directory);

    /** Whether this object holds a lock. */
    bool
    held() const
    {
      return descriptor >= 0;
    }

    /** `<directory>/.yarn-impact.lock`: hidden, so that listings of the
     * results do not show it; Output/Overwrite leaves it alone. */
    static std::string
    file_name(const std::string &directory);

  private:
    int descriptor = -1;
  };
} // namespace YarnImpact

#endif
