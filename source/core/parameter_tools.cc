#include <yarn_impact/core/parameter_tools.h>

#include <deal.II/base/parameter_handler.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace YarnImpact
{
  namespace Parameters
  {
    void
    require(const bool condition,
            const std::string &name,
            const std::string &message)
    {
      if (!condition)
        throw InputError("Parameter '" + name + "' " + message + ".");
    }

    double
    get_positive_double(dealii::ParameterHandler &prm,
                        const std::string &section,
                        const std::string &entry)
    {
      const double value = prm.get_double(entry);
      std::ostringstream got;
      got << "must be positive (got " << prm.get(entry) << ")";
      require(std::isfinite(value) && value > 0.,
              section.empty() ? entry : section + "/" + entry,
              got.str());
      return value;
    }

    unsigned int
    get_positive_integer(dealii::ParameterHandler &prm,
                         const std::string &section,
                         const std::string &entry)
    {
      const long value = prm.get_integer(entry);
      require(value > 0,
              section.empty() ? entry : section + "/" + entry,
              "must be a positive integer (got " + prm.get(entry) + ")");
      return static_cast<unsigned int>(value);
    }

    namespace
    {
      /** @p text with its first letter in lower case (system messages). */
      std::string
      lower_first(std::string text)
      {
        if (!text.empty())
          text[0] = static_cast<char>(
            std::tolower(static_cast<unsigned char>(text[0])));
        return text;
      }

      /** @p text without white space at either end. */
      std::string
      trim(const std::string &text)
      {
        std::size_t begin = 0, end = text.size();
        while (begin < end &&
               std::isspace(static_cast<unsigned char>(text[begin])))
          ++begin;
        while (end > begin &&
               std::isspace(static_cast<unsigned char>(text[end - 1])))
          --end;
        return text.substr(begin, end - begin);
      }

      /** Whether @p line starts with @p prefix. */
      bool
      starts_with(const std::string &line, const char *prefix)
      {
        return line.compare(0, std::strlen(prefix), prefix) == 0;
      }

      /** A file read whole, and what identifies it on its file system. */
      struct FileContents
      {
        std::string text;
        dev_t device = 0;
        ino_t inode  = 0;
      };

      /**
       * Read @p name if it is a regular file of at most @p limit bytes,
       * else return why not ("it is a directory", ...). Opened without
       * blocking (a fifo would block an ordinary open) and checked on the
       * open descriptor, so what is checked is what is read.
       */
      std::string
      read_regular_file(const std::string &name,
                        const std::size_t limit,
                        FileContents &contents)
      {
        const std::string not_regular =
          "it is not a regular file (a fifo, socket or device)";
        const int fd = ::open(name.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
        struct stat st;
        if (fd < 0)
          {
            const int error = errno;
            if (::stat(name.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
              return "it is a directory";
            if (::stat(name.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
              return not_regular;
            return lower_first(std::strerror(error));
          }
        std::string why;
        if (::fstat(fd, &st) != 0)
          why = lower_first(std::strerror(errno));
        else if (S_ISDIR(st.st_mode))
          why = "it is a directory";
        else if (!S_ISREG(st.st_mode))
          why = not_regular;
        else if (static_cast<std::size_t>(st.st_size) > limit)
          why = "it is larger than " + std::to_string(limit >> 20) + " MiB (" +
                std::to_string(st.st_size) + " bytes)";
        if (why.empty())
          {
            contents.device = st.st_dev;
            contents.inode  = st.st_ino;
            char buffer[65536];
            while (true)
              {
                const ssize_t n = ::read(fd, buffer, sizeof(buffer));
                if (n < 0 && errno == EINTR)
                  continue;
                if (n < 0)
                  {
                    why = lower_first(std::strerror(errno));
                    break;
                  }
                if (n == 0)
                  break;
                contents.text.append(buffer, static_cast<std::size_t>(n));
                if (contents.text.size() > limit)
                  {
                    why = "it is larger than " + std::to_string(limit >> 20) +
                          " MiB";
                    break;
                  }
              }
          }
        ::close(fd);
        return why;
      }

      /** Expands the includes of one top-level file into an ExpandedFile. */
      class Expander
      {
      public:
        explicit Expander(ExpandedFile &result)
          : result(result)
        {}

        /** Append @p name (read as @p contents), included through the
         * current chain, its includes expanded. */
        void
        expand(const std::string &name, const FileContents &contents)
        {
          chain.push_back({name, contents.device, contents.inode});
          const std::size_t index = result.files.size();
          result.files.push_back(name);
          const bool top = chain.size() == 1;

          std::vector<std::string> lines;
          {
            std::size_t begin       = 0;
            const std::string &text = contents.text;
            while (begin < text.size())
              {
                std::size_t end = text.find('\n', begin);
                if (end == std::string::npos)
                  end = text.size();
                lines.push_back(text.substr(begin, end - begin));
                begin = end + 1;
              }
          }

          int depth = 0;
          std::string logical;
          unsigned int first = 0; // first physical line of logical
          for (unsigned int i = 0; i < lines.size(); ++i)
            {
              std::string line = trim(lines[i]);
              if (logical.empty() && first == 0)
                first = i + 1;
              if (!line.empty() && line.back() == '\\')
                {
                  line.pop_back();
                  logical += line;
                  if (i + 1 < lines.size())
                    continue;
                }
              else
                logical += line;
              // The line as deal.II's scan_line sees it.
              const std::size_t comment = logical.find('#');
              if (comment != std::string::npos)
                logical.erase(comment);
              for (char &c : logical)
                if (c == '\t')
                  c = ' ';
              logical = trim(logical);
              if (starts_with(logical, "include ") ||
                  starts_with(logical, "INCLUDE "))
                include(trim(logical.substr(8)), name, first);
              else
                {
                  if (starts_with(logical, "subsection ") ||
                      starts_with(logical, "SUBSECTION "))
                    ++depth;
                  else if (logical == "end" || logical == "END")
                    --depth;
                  if (depth < 0 && !top)
                    fail("an 'end' on line " + std::to_string(i + 1) + " of " +
                         quote(name) + " closes a subsection it did not open");
                  for (unsigned int j = first; j <= i + 1; ++j)
                    add_line(lines[j - 1], index, j);
                }
              logical.clear();
              first = 0;
            }
          if (!top && depth != 0)
            fail("'subsection' and 'end' lines of " + quote(name) +
                 " do not match (an included file must close every "
                 "subsection it opens)");
          // A last line ending in '\' must not join the includer's next.
          if (!top && !lines.empty() && !trim(lines.back()).empty() &&
              trim(lines.back()).back() == '\\')
            add_line("", index, lines.size());
          chain.pop_back();
        }

      private:
        struct Link
        {
          std::string name;
          dev_t device;
          ino_t inode;
        };

        ExpandedFile &result;
        std::vector<Link> chain;
        std::size_t size = 0;

        static std::string
        quote(const std::string &name)
        {
          return "'" + name + "'";
        }

        /** "A includes B includes C" of the chain (and @p next). */
        std::string
        chain_text(const std::string &next = "") const
        {
          std::string text;
          for (const auto &link : chain)
            text += (text.empty() ? "" : " includes ") + link.name;
          if (!next.empty())
            text += " includes " + next;
          return text;
        }

        [[noreturn]] void
        fail(const std::string &why, const std::string &next = "") const
        {
          throw InputError(chain_text(next) + ": " + why + ".");
        }

        void
        add_line(const std::string &line,
                 const std::size_t file,
                 const unsigned int number)
        {
          size += line.size() + 1;
          if (size > max_parameter_file_size)
            fail("the expanded parameter text is larger than " +
                 std::to_string(max_parameter_file_size >> 20) + " MiB");
          result.text += line;
          result.text += '\n';
          result.origin.emplace_back(file, number);
        }

        void
        include(const std::string &target,
                const std::string &from,
                const unsigned int line)
        {
          namespace fs        = std::filesystem;
          const fs::path path = target;
          const std::string name =
            path.is_absolute() ? target
                               : (fs::path(from).parent_path() / path).string();
          const std::string at =
            " (line " + std::to_string(line) + " of " + quote(from) + ")";
          if (chain.size() >= max_include_depth)
            fail("includes nested more than " +
                   std::to_string(max_include_depth) + " files deep" + at,
                 name);
          FileContents contents;
          const std::string why =
            read_regular_file(name, max_parameter_file_size, contents);
          if (!why.empty())
            fail("cannot include " + quote(name) + ": " + why + at, name);
          for (const auto &link : chain)
            if (link.device == contents.device && link.inode == contents.inode)
              fail("an include cycle" + at, name);
          expand(name, contents);
        }
      };
    } // namespace


    std::string
    ExpandedFile::where(const unsigned int line) const
    {
      if (line == 0 || line > origin.size())
        return "line " + std::to_string(line) + " of '" +
               (files.empty() ? std::string() : files[0]) + "'";
      const auto &o = origin[line - 1];
      return "line " + std::to_string(o.second) + " of '" + files[o.first] +
             "'";
    }


    ExpandedFile
    read_parameter_file(const std::string &file, const bool expand_includes)
    {
      FileContents contents;
      const std::string why =
        read_regular_file(file, max_parameter_file_size, contents);
      if (!why.empty())
        throw InputError("cannot open the parameter file '" + file +
                         "': " + why + ".");
      ExpandedFile result;
      if (!expand_includes)
        {
          result.text = contents.text;
          result.files.push_back(file);
          return result;
        }
      Expander(result).expand(file, contents);
      return result;
    }
  } // namespace Parameters
} // namespace YarnImpact
