#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/fe/fe_model.h>

namespace YarnImpact
{
  namespace FE
  {
    void
    validate(const YarnImpact::Parameters::Shared &, const Parameters &)
    {}

    std::unique_ptr<ImpactModel>
    create_model(const YarnImpact::Parameters::Shared &,
                 const Parameters &,
                 const MPI_Comm)
    {
      throw InputError("the FE model is being written");
    }
  } // namespace FE
} // namespace YarnImpact
