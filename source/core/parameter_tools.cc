#include <yarn_impact/core/parameter_tools.h>

#include <deal.II/base/parameter_handler.h>

#include <cmath>
#include <sstream>

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
  } // namespace Parameters
} // namespace YarnImpact
