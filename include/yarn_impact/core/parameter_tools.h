#ifndef yarn_impact_core_parameter_tools_h
#define yarn_impact_core_parameter_tools_h

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace YarnImpact
{
  /**
   * A user-input error: a wrong `.prm` entry, an impossible set-up, a missing
   * file. The message names the parameter (as `Subsection/Entry`) or the
   * cause; the program prints it on one line and exits with a non-zero code
   * before writing anything.
   */
  class InputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  namespace Parameters
  {
    /**
     * Throw an InputError "Parameter 'name' message" unless @p condition
     * holds.
     */
    void
    require(const bool condition,
            const std::string &name,
            const std::string &message);

    /** Read a double entry of the current subsection @p section and require
     * it to be strictly positive. */
    double
    get_positive_double(dealii::ParameterHandler &prm,
                        const std::string &section,
                        const std::string &entry);

    /** Read an integer entry and require it to be strictly positive. */
    unsigned int
    get_positive_integer(dealii::ParameterHandler &prm,
                         const std::string &section,
                         const std::string &entry);

    /**
     * A parameter file with its `include` lines expanded: the text handed to
     * deal.II, and for each of its lines the file and line it came from.
     */
    struct ExpandedFile
    {
      /** The text, one line of a file per line. */
      std::string text;
      /** For line i + 1 of text: (index into files, line in that file). */
      std::vector<std::pair<std::size_t, unsigned int>> origin;
      /** Every file read, the top-level one first (as named: relative
       * includes are joined to their including file's folder). */
      std::vector<std::string> files;

      /** "line N of FILE" of line @p line of text (1-based). */
      std::string
      where(const unsigned int line) const;
    };

    /** Largest parameter file, and largest expanded text, read (bytes). */
    constexpr std::size_t max_parameter_file_size = 16u << 20;
    /** Deepest chain of nested `include` lines followed. */
    constexpr unsigned int max_include_depth = 32;

    /**
     * Read the parameter file @p file and, unless @p expand_includes is
     * false, every file it includes (`include FILE` or `INCLUDE FILE`
     * lines, as deal.II's ParameterHandler reads them), in place. A relative
     * FILE is taken relative to the folder of the file that includes it.
     * Each file must be a readable regular file (not missing, a directory, a
     * fifo, a socket or a device) of at most max_parameter_file_size bytes,
     * opened without blocking; an include must not lead back to a file of
     * its own chain (a cycle) nor nest deeper than max_include_depth, an
     * included file must close each `subsection` it opens, and the expanded
     * text must stay within max_parameter_file_size. Otherwise throws an
     * InputError: for the top-level file "cannot open the parameter file
     * 'FILE': CAUSE.", for an included one a line naming the chain
     * "A includes B includes C: CAUSE".
     */
    ExpandedFile
    read_parameter_file(const std::string &file,
                        const bool expand_includes = true);
  } // namespace Parameters
} // namespace YarnImpact

#endif
