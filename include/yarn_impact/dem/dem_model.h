#ifndef yarn_impact_dem_dem_model_h
#define yarn_impact_dem_dem_model_h

#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/parameters.h>

#include <mpi.h>

#include <memory>

namespace dealii
{
  class ParameterHandler;
}

namespace YarnImpact
{
  /** The microscopic discrete-element reference model (design.md section 6). */
  namespace DEM
  {
    /** Parameters of the DEM model (subsection `DEM`). */
    struct Parameters
    {
      static void
      declare_parameters(dealii::ParameterHandler &prm);
      void
      parse_parameters(dealii::ParameterHandler &prm);
    };

    /** Create the DEM model of the yarn described by @p shared. */
    std::unique_ptr<ImpactModel>
    create_model(const YarnImpact::Parameters::Shared &shared,
                 const Parameters &parameters,
                 const MPI_Comm communicator);
  } // namespace DEM
} // namespace YarnImpact

#endif
