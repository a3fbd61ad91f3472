#ifndef yarn_impact_dem_dem_model_h
#define yarn_impact_dem_dem_model_h

#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/dem/parameters.h>

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

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

    /**
     * What a coupling (coupling/hybrid_model.h) reads and writes of a DEM
     * model between its compute_forces() and its kick: the layout (fibres
     * and stations, the same on every rank), the stations this rank owns,
     * and this rank's sphere arrays (3 values per sphere: x, y, z). Valid
     * until the model's next step: the arrays may move when the ghost
     * layers grow.
     */
    struct CouplingView
    {
      /** Modelled fibres and stations [-]. */
      unsigned int n_fibres = 0, n_stations = 0;
      /** The stations this rank owns: [station_begin, station_end). */
      unsigned int station_begin = 0, station_end = 0;
      /** Reference x of each station [m]; reference y and z of each fibre
       * [m]. */
      const std::vector<double> *station_x = nullptr, *fibre_y = nullptr,
                                *fibre_z = nullptr;
      /** Positions [m], velocities [m/s] and forces [N] of this rank's
       * spheres, indexed by local_index(). */
      double *position = nullptr, *velocity = nullptr, *force = nullptr;
      /** Whether the truss from the sphere of local_index() to the next
       * station's is broken (1) [-]. */
      const std::uint8_t *broken = nullptr;
      /** Local index of the sphere of fibre @p f at station @p s (owned
       * stations only). */
      std::function<std::size_t(unsigned int s, unsigned int f)> local_index;
      /** The inverse mass the kick applies to that sphere's force
       * [1/kg]. */
      std::function<double(unsigned int s, unsigned int f)> inverse_mass;
      /** The spheres' radius [m], and the law and constants of their
       * contact with the projectile. */
      double sphere_radius            = 0.;
      Contact::LawType projectile_law = Contact::LawType::cundall_strack;
      Contact::ContactConstants projectile_constants;
    };

    /** The coupling view of @p model, which must be a DEM impact model. */
    CouplingView
    coupling_view(ImpactModel &model);
  } // namespace DEM
} // namespace YarnImpact

#endif
