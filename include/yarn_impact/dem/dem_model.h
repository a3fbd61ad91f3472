#ifndef yarn_impact_dem_dem_model_h
#define yarn_impact_dem_dem_model_h

#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/dem/parameters.h>

#include <mpi.h>

#include <memory>
#include <string>

namespace YarnImpact
{

  namespace DEM
  {
    /** Create the DEM model of the yarn described by @p shared. */
    std::unique_ptr<ImpactModel>
    create_model(const YarnImpact::Parameters::Shared &shared,
                 const Parameters &parameters,
                 const MPI_Comm communicator);

    /** Neighbour-list statistics of a DEM model (rebuilds and listed pairs
     * of every rank), for the benchmark; empty for another model. Collective
     * for a DEM model. */
    std::string
    statistics(const ImpactModel &model);
  } // namespace DEM
} // namespace YarnImpact

#endif
