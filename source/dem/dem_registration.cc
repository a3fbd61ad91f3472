// The DEM model's registration: `Model = dem` (core/model_registry.h).

#include <yarn_impact/core/model_registry.h>
#include <yarn_impact/dem/dem_model.h>

#include <deal.II/base/parameter_handler.h>

namespace YarnImpact
{
  namespace DEM
  {
    namespace
    {
      /** The DEM model with its parameters, as the application sees it. */
      class Plugin : public ModelPlugin
      {
      public:
        /** Subsection `DEM`. */
        static void
        declare_parameters(dealii::ParameterHandler &prm)
        {
          Parameters::declare_parameters(prm);
        }

        void
        parse_parameters(dealii::ParameterHandler &prm) override
        {
          parameters.parse_parameters(prm);
        }

        void
        validate(const YarnImpact::Parameters::Shared &shared) const override
        {
          DEM::validate(shared, parameters);
        }

        MemoryEstimate
        memory_estimate(
          const YarnImpact::Parameters::Shared &shared) const override
        {
          return DEM::memory_estimate(shared, parameters);
        }

        std::unique_ptr<ImpactModel>
        create(const YarnImpact::Parameters::Shared &shared,
               const MPI_Comm communicator) const override
        {
          return create_model(shared, parameters, communicator);
        }

      private:
        Parameters parameters;
      };
    } // namespace
  }   // namespace DEM
} // namespace YarnImpact

YARN_IMPACT_REGISTER_MODEL("dem", YarnImpact::DEM::Plugin)
