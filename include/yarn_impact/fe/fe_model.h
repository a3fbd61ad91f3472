#ifndef yarn_impact_fe_fe_model_h
#define yarn_impact_fe_fe_model_h

#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/memory_estimate.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/fe/parameters.h>

#include <mpi.h>

#include <array>
#include <memory>
#include <vector>

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

    /**
     * What a coupling (coupling/hybrid_model.h) reads and writes of an FE
     * model between its compute_forces() and its kick: this rank's owned
     * nodes with the local indices of their x, y, z degrees of freedom, and
     * the local arrays of the owned degrees of freedom. Valid for the
     * model's lifetime.
     */
    struct CouplingView
    {
      /** Owned nodes: local indices of their x, y, z dofs. */
      const std::vector<std::array<unsigned int, 3>> *nodes = nullptr;
      /** Reference coordinate of each local dof (its own component) [m]. */
      const std::vector<double> *reference_coordinate = nullptr;
      /** Displacement [m], velocity [m/s], force [N], lumped (weighted)
       * mass [kg] and the inverse mass the kick applies (0 on a fixed dof)
       * [1/kg] of the owned dofs, by local index. */
      double *displacement = nullptr, *velocity = nullptr, *force = nullptr;
      const double *mass = nullptr, *inverse_mass = nullptr;
    };

    /** The coupling view of @p model, which must be an FE impact model. */
    CouplingView
    coupling_view(ImpactModel &model);

    /** Create the FE model of the yarn described by @p shared. */
    std::unique_ptr<ImpactModel>
    create_model(const YarnImpact::Parameters::Shared &shared,
                 const Parameters &parameters,
                 const MPI_Comm communicator);
  } // namespace FE
} // namespace YarnImpact

#endif
