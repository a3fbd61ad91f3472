#include <yarn_impact/core/output_lock.h>
#include <yarn_impact/core/parameter_tools.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <sstream>
#include <sys/file.h>
#include <thread>
#include <unistd.h>

namespace YarnImpact
{
  namespace
  {
    /** strerror(@p error) with its first letter in lower case. */
    std::string
    cause(const int error)
    {
      std::string text = std::strerror(error);
      if (!text.empty() && text[0] >= 'A' && text[0] <= 'Z')
        text[0] = static_cast<char>(text[0] - 'A' + 'a');
      return text;
    }

    /** This machine's name ("unknown" if it has none). */
    std::string
    host_name()
    {
      char name[256] = {};
      if (gethostname(name, sizeof(name) - 1) != 0 || name[0] == '\0')
        return "unknown";
      return name;
    }

    /**
     * Who holds the lock of @p descriptor, from the file's text, for the
     * refusal. The holder writes its name just after locking: a process
     * that looks in between reads an empty file or, if the file is old,
     * the name of its dead previous owner. Both are read again for a
     * short while rather than named.
     */
    std::string
    holder(const int descriptor)
    {
      const std::string here = host_name();
      std::string found;
      for (unsigned int attempt = 0; attempt < 50; ++attempt)
        {
          char text[512]  = {};
          const ssize_t n = pread(descriptor, text, sizeof(text) - 1, 0);
          long pid        = 0;
          std::string host;
          if (n > 0)
            {
              std::istringstream in(std::string(text, n));
              in >> pid >> host;
              if (!in || pid <= 0)
                pid = 0;
            }
          if (pid > 0)
            {
              found = "process " + std::to_string(pid) + " on host " + host;
              // On this host a dead owner is known for sure; the name of a
              // live one, or of one on another host, is taken as it is.
              if (host != here || kill(static_cast<pid_t>(pid), 0) == 0 ||
                  errno == EPERM)
                return found;
            }
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
      return found.empty() ? std::string("a process that has not written "
                                         "its name")
                           : found;
    }
  } // namespace


  std::string
  OutputLock::file_name(const std::string &directory)
  {
    return directory + "/.yarn-impact.lock";
  }


  OutputLock::~OutputLock()
  {
    // Closing the last descriptor of the file releases the flock.
    if (descriptor >= 0)
      close(descriptor);
  }


  void
  OutputLock::acquire(const std::string &directory)
  {
    const std::string file = file_name(directory);
    const std::string quoted =
      "Parameter 'Output/Directory' = '" + directory + "'";
    // Close-on-exec: a program started by the run must not inherit it.
    const int fd = open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      throw InputError(quoted +
                       " cannot be used for output (cannot create "
                       "its lock file '" +
                       file + "': " + cause(errno) + ").");
    if (flock(fd, LOCK_EX | LOCK_NB) != 0)
      {
        const int error = errno;
        if (error == EWOULDBLOCK)
          {
            const std::string owner = holder(fd);
            close(fd);
            throw DirectoryInUse(quoted + " is in use by another run: " +
                                 owner + " holds its lock '" + file +
                                 "'; wait for that run to end, or choose "
                                 "another directory.");
          }
        close(fd);
        throw InputError(quoted + " cannot be used for output (cannot lock '" +
                         file + "': " + cause(error) + ").");
      }
    descriptor = fd;
    // The owner's name is for the refusal of others only: a full disk here
    // does not stop the run (its first output write will, naming its file).
    const std::string text =
      std::to_string(static_cast<long>(getpid())) + " " + host_name() + "\n";
    if (ftruncate(fd, 0) == 0)
      {
        [[maybe_unused]] const ssize_t written =
          pwrite(fd, text.data(), text.size(), 0);
      }
  }
} // namespace YarnImpact
