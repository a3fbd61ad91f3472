// The FE model's registration: `Model = fe` (core/model_registry.h).

#include <yarn_impact/core/model_registry.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/parameter_handler.h>

namespace YarnImpact
{
  namespace FE
  {
    namespace
    {
      /** The FE model with its parameters, as the application sees it. */
      class Plugin : public ModelPlugin
      {
      public:
        /** What the model is, for the help of `Model`. */
        static std::string
        help()
        {
          return "the mesoscopic finite-element yarn";
        }

        /** Subsection `FE` and the FE's failure entries of `Yarn`. */
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
          FE::validate(shared, parameters);
        }

        MemoryEstimate
        memory_estimate(
          const YarnImpact::Parameters::Shared &shared) const override
        {
          return FE::memory_estimate(shared, parameters);
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
  }   // namespace FE
} // namespace YarnImpact

YARN_IMPACT_REGISTER_MODEL("fe", YarnImpact::FE::Plugin)
