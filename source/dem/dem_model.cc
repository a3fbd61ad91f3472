#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/dem/dem_model.h>

#include <deal.II/base/parameter_handler.h>

namespace YarnImpact
{
  namespace DEM
  {
    void
    Parameters::declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("DEM");
      prm.leave_subsection();
    }

    void
    Parameters::parse_parameters(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("DEM");
      prm.leave_subsection();
    }

    std::unique_ptr<ImpactModel>
    create_model(const YarnImpact::Parameters::Shared &,
                 const Parameters &,
                 const MPI_Comm)
    {
      throw InputError("Parameter 'Model' = dem: the DEM model is not "
                       "available in this build yet.");
    }
  } // namespace DEM
} // namespace YarnImpact
