#include <yarn_impact/core/output_file.h>

#include <deal.II/base/mpi.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

namespace YarnImpact
{
  namespace internal
  {
    std::size_t
    injected_write_allowance(const std::size_t bytes)
    {
      static const long long limit = [] {
        const char *value = std::getenv("YARN_IMPACT_DISK_FULL_AFTER");
        return value != nullptr ? std::atoll(value) : -1LL;
      }();
      static long long written = 0;
      if (limit < 0)
        return bytes;
      const long long left  = std::max(0LL, limit - written);
      const std::size_t now = std::min<std::size_t>(bytes, left);
      written += now;
      return now;
    }
  } // namespace internal

  namespace
  {
    /** "no space left on device" for ENOSPC: strerror in lower case. */
    std::string
    cause(const int error)
    {
      std::string text = std::strerror(error);
      if (!text.empty())
        text[0] =
          static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
      return text;
    }

    [[noreturn]] void
    fail(const std::string &path, const int error)
    {
      throw OutputError("cannot write '" + path + "': " + cause(error) + ".");
    }

    /**
     * Write all of @p size bytes to @p fd, retrying short writes; returns 0
     * or the errno of the failure (the injected full disk included).
     */
    int
    write_all(const int fd, const char *data, std::size_t size)
    {
      while (size > 0)
        {
          const std::size_t allowed = internal::injected_write_allowance(size);
          if (allowed == 0)
            return ENOSPC;
          const ssize_t n = ::write(fd, data, allowed);
          if (n < 0)
            {
              if (errno == EINTR)
                continue;
              return errno;
            }
          data += n;
          size -= static_cast<std::size_t>(n);
        }
      return 0;
    }
  } // namespace


  AtomicFile::AtomicFile(std::string path)
    : path(std::move(path))
  {}

  void
  AtomicFile::commit()
  {
    const std::string temporary = path + ".tmp";
    const int fd =
      ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0)
      fail(path, errno);
    const std::string text = contents.str();
    int error              = write_all(fd, text.data(), text.size());
    if (::close(fd) != 0 && error == 0)
      error = errno;
    if (error == 0 && std::rename(temporary.c_str(), path.c_str()) != 0)
      error = errno;
    if (error != 0)
      {
        ::unlink(temporary.c_str());
        fail(path, error);
      }
  }

  void
  write_file_atomically(const std::string &path, const std::string &text)
  {
    AtomicFile file(path);
    file.stream() << text;
    file.commit();
  }


  AppendFile::~AppendFile()
  {
    if (descriptor >= 0)
      ::close(descriptor);
  }

  void
  AppendFile::open(const std::string &file)
  {
    path       = file;
    descriptor = ::open(path.c_str(),
                        O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_CLOEXEC,
                        0644);
    if (descriptor < 0)
      fail(path, errno);
    size = 0;
  }

  void
  AppendFile::append(const std::string &text)
  {
    if (descriptor < 0)
      return;
    const int error = write_all(descriptor, text.data(), text.size());
    if (error != 0)
      {
        // A partial row would be read as data: cut the file back to its
        // last whole row before reporting.
        if (::ftruncate(descriptor, size) != 0)
          {
            // Nothing better can be done; the message still names the
            // original cause.
          }
        fail(path, error);
      }
    size += static_cast<long>(text.size());
  }


  void
  collective_output(const MPI_Comm communicator,
                    const std::function<void()> &write)
  {
    std::string error;
    try
      {
        write();
      }
    catch (const OutputError &e)
      {
        error = e.what();
        if (error.empty())
          error = "an output file could not be written.";
      }
    // One small reduction when all went well (every history row passes
    // here); the message travels only on failure.
    const unsigned int n_ranks =
      dealii::Utilities::MPI::n_mpi_processes(communicator);
    const unsigned int failed_rank = dealii::Utilities::MPI::min(
      error.empty() ? n_ranks
                    : dealii::Utilities::MPI::this_mpi_process(communicator),
      communicator);
    if (failed_rank < n_ranks)
      throw OutputError(
        dealii::Utilities::MPI::broadcast(communicator, error, failed_rank));
  }
} // namespace YarnImpact
