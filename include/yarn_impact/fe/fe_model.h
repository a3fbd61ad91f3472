#ifndef yarn_impact_fe_fe_model_h
#define yarn_impact_fe_fe_model_h

#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/memory_estimate.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/fe/parameters.h>

#include <mpi.h>

#include <memory>

namespace YarnImpact
{
  /** The mesoscopic finite-element yarn model (doc/fe-model.md). */
  namespace FE
  {
    /**
     * @p given with what `Density from fibres` and `Axial modulus from
     * fibres` ask resolved: the density rho_f n_f A_f / A and the law's
     * axial modulus (Charmetant k_e, linear E_L) E_f n_f A_f / A, with A the
     * ellipse's area, so that the FE yarn has the DEM yarn's mass per
     * length and axial stiffness. The other entries are @p given's.
     */
    Parameters
    with_fibre_data(const YarnImpact::Parameters::Shared &shared,
                    const Parameters &given);

    /**
     * Check the FE parameters against the shared ones (a set-up that cannot
     * be meshed, an unstable contact penalty); throws InputError.
     */
    void
    validate(const YarnImpact::Parameters::Shared &shared,
             const Parameters &parameters);

    /**
     * Memory the FE set-up will need (6.5 kB per cell, measured: 6.1 kB at
     * set-up between 4 800 and 76 800 cells), and the mesh parameter that
     * makes it large.
     */
    MemoryEstimate
    memory_estimate(const YarnImpact::Parameters::Shared &shared,
                    const Parameters &parameters);

    /** Create the FE model of the yarn described by @p shared. */
    std::unique_ptr<ImpactModel>
    create_model(const YarnImpact::Parameters::Shared &shared,
                 const Parameters &parameters,
                 const MPI_Comm communicator);
  } // namespace FE
} // namespace YarnImpact

#endif
