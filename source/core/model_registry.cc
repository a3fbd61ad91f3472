#include <yarn_impact/core/model_registry.h>

#include <map>
#include <stdexcept>

namespace YarnImpact
{
  bool
  ModelPlugin::run_own_task(const Parameters::Shared &,
                            const MPI_Comm,
                            std::ostream &) const
  {
    throw std::logic_error("run_own_task() of a model without a task of its "
                           "own");
  }


  namespace ModelRegistry
  {
    namespace
    {
      /** A registered model. */
      struct Entry
      {
        std::string help;
        DeclareFunction declare;
        MakeFunction make;
      };

      /** The registry, built on first use: registrations run as static
       * initialisers of other files, in no set order. Sorted by name, so
       * that declarations and parses run in one order. */
      std::map<std::string, Entry> &
      registry()
      {
        static std::map<std::string, Entry> entries;
        return entries;
      }
    } // namespace


    bool
    add(const std::string &name,
        const std::string &help,
        const DeclareFunction declare,
        const MakeFunction make)
    {
      if (!registry().emplace(name, Entry{help, declare, make}).second)
        throw std::logic_error("the model '" + name + "' is registered twice");
      return true;
    }


    std::vector<std::string>
    names()
    {
      std::vector<std::string> result;
      for (const auto &entry : registry())
        result.push_back(entry.first);
      return result;
    }


    std::string
    help(const std::string &name)
    {
      const auto entry = registry().find(name);
      if (entry == registry().end())
        throw std::logic_error("no model '" + name + "' is registered");
      return entry->second.help;
    }


    void
    declare_parameters(dealii::ParameterHandler &prm)
    {
      for (const auto &entry : registry())
        entry.second.declare(prm);
    }


    std::unique_ptr<ModelPlugin>
    make(const std::string &name)
    {
      const auto entry = registry().find(name);
      if (entry == registry().end())
        throw std::logic_error("no model '" + name + "' is registered");
      return entry->second.make();
    }
  } // namespace ModelRegistry
} // namespace YarnImpact
