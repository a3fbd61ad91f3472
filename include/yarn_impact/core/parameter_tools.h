#ifndef yarn_impact_core_parameter_tools_h
#define yarn_impact_core_parameter_tools_h

#include <stdexcept>
#include <string>

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
  } // namespace Parameters
} // namespace YarnImpact

#endif
