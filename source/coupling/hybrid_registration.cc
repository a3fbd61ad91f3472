// The hybrid yarn's registration: `Model = hybrid` (core/model_registry.h).

#include <yarn_impact/core/model_registry.h>
#include <yarn_impact/coupling/hybrid_model.h>

#include <deal.II/base/parameter_handler.h>

namespace YarnImpact
{
  namespace Coupling
  {
    namespace
    {
      /** The hybrid yarn with its parameters and those of its two parts,
       * as the application sees it. */
      class Plugin : public ModelPlugin
      {
      public:
        /** What the model is, for the help of `Model`. */
        static std::string
        help()
        {
          return "the hybrid yarn (subsection Hybrid, doc/hybrid.md): the DEM "
                 "fibres near the impact, the FE continuum elsewhere, "
                 "coupled in an overlap";
        }

        /** Subsection `Hybrid`; the parts' own subsections are declared by
         * their models' registrations. */
        static void
        declare_parameters(dealii::ParameterHandler &prm)
        {
          HybridParameters::declare_parameters(prm);
        }

        void
        parse_parameters(dealii::ParameterHandler &prm) override
        {
          fe.parse_parameters(prm);
          dem.parse_parameters(prm);
          hybrid.parse_parameters(prm);
          // The hybrid's FE part on its own mesh, if it has one.
          if (hybrid.fe_axial_cells > 0)
            fe.n_axial_cells = hybrid.fe_axial_cells;
        }

        void
        validate(const YarnImpact::Parameters::Shared &shared) const override
        {
          Coupling::validate(shared, fe, dem, hybrid);
        }

        MemoryEstimate
        memory_estimate(
          const YarnImpact::Parameters::Shared &shared) const override
        {
          return Coupling::memory_estimate(shared, fe, dem, hybrid);
        }

        std::unique_ptr<ImpactModel>
        create(const YarnImpact::Parameters::Shared &shared,
               const MPI_Comm communicator) const override
        {
          return create_hybrid_model(shared, fe, dem, hybrid, communicator);
        }

      private:
        FE::Parameters fe;
        DEM::Parameters dem;
        HybridParameters hybrid;
      };
    } // namespace
  }   // namespace Coupling
} // namespace YarnImpact

YARN_IMPACT_REGISTER_MODEL("hybrid", YarnImpact::Coupling::Plugin)
