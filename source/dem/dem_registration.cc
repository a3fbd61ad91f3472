// The DEM model's registration: `Model = dem` (core/model_registry.h).

#include <yarn_impact/core/model_registry.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/dem/dem_model.h>
#include <yarn_impact/dem/elementary/elementary_test.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <limits>
#include <sstream>

namespace YarnImpact
{
  namespace DEM
  {
    namespace
    {
      /**
       * What the periodic segment of an elementary test allocates: every
       * rank holds the positions, velocities, accelerations and exchange
       * buffers of all spheres (about 400 B each, counted once per rank) and
       * the neighbour lists and contact histories of its own (about 600 B
       * each, measured: 0.8 GB for 800 000 spheres on one rank). Refused
       * with the parameter that makes it large, also where the segment
       * would not fit an MPI message (6 doubles a sphere, counted in an
       * int).
       */
      MemoryEstimate
      elementary_memory_estimate(const YarnImpact::Parameters::Shared &shared,
                                 const ElementaryTestParameters &elementary,
                                 const unsigned int n_ranks)
      {
        MemoryEstimate e;
        const double fibres   = shared.yarn.n_fibres;
        const double sections = elementary.stations;
        e.n_elements          = fibres * sections;
        e.bytes               = (400. * n_ranks + 600.) * e.n_elements;
        e.element_name        = "spheres";
        e.parameter =
          (fibres / 400. >= sections / 4. ? "Yarn/Number of fibres"
                                          : "Elementary test/Cross-sections");
        if (6. * e.n_elements > double(std::numeric_limits<int>::max()))
          {
            std::ostringstream s;
            s.precision(3);
            s << "Parameter '" << e.parameter
              << "' makes the elementary test's segment " << e.n_elements
              << " spheres, more than one MPI message can exchange ("
              << std::numeric_limits<int>::max() / 6 << ").";
            throw InputError(s.str());
          }
        return e;
      }


      /** The DEM model with its parameters, as the application sees it, and
       * its elementary tests (`Elementary test/Loading` not none): they
       * drive a periodic segment, not the impact model. */
      class Plugin : public ModelPlugin
      {
      public:
        /** What the model is, for the help of `Model`. */
        static std::string
        help()
        {
          return "the microscopic discrete-element fibres";
        }

        /** Subsections `DEM` and `Elementary test`. */
        static void
        declare_parameters(dealii::ParameterHandler &prm)
        {
          Parameters::declare_parameters(prm);
          ElementaryTestParameters::declare_parameters(prm);
        }

        void
        parse_parameters(dealii::ParameterHandler &prm) override
        {
          parameters.parse_parameters(prm);
          elementary.parse_parameters(prm);
        }

        void
        validate(const YarnImpact::Parameters::Shared &shared) const override
        {
          DEM::validate(shared, parameters, own_task().has_value());
        }

        MemoryEstimate
        memory_estimate(
          const YarnImpact::Parameters::Shared &shared) const override
        {
          if (own_task())
            return elementary_memory_estimate(shared,
                                              elementary,
                                              ranks_in(MPI_COMM_WORLD));
          return DEM::memory_estimate(shared, parameters);
        }

        std::optional<OwnTask>
        own_task() const override
        {
          if (elementary.loading == ElementaryLoading::none)
            return std::nullopt;
          return OwnTask{"elementary",
                         "elementary tests",
                         "Elementary test/Loading"};
        }

        bool
        run_own_task(const YarnImpact::Parameters::Shared &shared,
                     const MPI_Comm communicator,
                     std::ostream &out) const override
        {
          return run_elementary_test(shared,
                                     parameters,
                                     elementary,
                                     communicator,
                                     out);
        }

        std::unique_ptr<ImpactModel>
        create(const YarnImpact::Parameters::Shared &shared,
               const MPI_Comm communicator) const override
        {
          return create_model(shared, parameters, communicator);
        }

      private:
        Parameters parameters;
        ElementaryTestParameters elementary;
      };
    } // namespace
  }   // namespace DEM
} // namespace YarnImpact

YARN_IMPACT_REGISTER_MODEL("dem", YarnImpact::DEM::Plugin)
