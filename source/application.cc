#include <yarn_impact/analysis/model_comparison.h>
#include <yarn_impact/application.h>
#include <yarn_impact/core/impact_simulation.h>
#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace YarnImpact
{
  using namespace dealii;

  namespace
  {
    /** Collapse the white space of a deal.II message onto one line. */
    std::string
    one_line(const std::string &text)
    {
      std::string result;
      bool space = false;
      for (const char c : text)
        if (std::isspace(static_cast<unsigned char>(c)))
          space = !result.empty();
        else
          {
            if (space)
              result += ' ';
            result += c;
            space = false;
          }
      return result;
    }

    const char *usage =
      "Usage: yarn-impact [--check] FILE.prm | --print-parameters | --help\n"
      "\n"
      "Transverse impact of a rigid cylindrical projectile on a single yarn,\n"
      "with a mesoscopic hyperelastic finite-element model and a microscopic\n"
      "discrete-element fibre model.\n"
      "\n"
      "  FILE.prm             run the case (also under mpirun -np N)\n"
      "  --check FILE.prm     parse and validate FILE.prm, write nothing\n"
      "  --print-parameters   print every parameter with its default,\n"
      "                       unit and documentation\n"
      "  --help               this text\n";

    /** Create the output directory and make sure it is writable. */
    void
    prepare_output_directory(const std::string &directory, const bool is_root)
    {
      bool ok = true;
      std::string reason;
      if (is_root)
        {
          std::error_code ec;
          std::filesystem::create_directories(directory, ec);
          if (ec)
            {
              ok     = false;
              reason = ec.message();
            }
          else
            {
              const std::string probe = directory + "/.yarn-impact-probe";
              std::ofstream f(probe);
              ok = static_cast<bool>(f << "probe");
              f.close();
              std::filesystem::remove(probe, ec);
              if (!ok)
                reason = "not writable";
            }
        }
      const bool all_ok = Utilities::MPI::min(ok ? 1 : 0, MPI_COMM_WORLD) == 1;
      Parameters::require(all_ok,
                          "Output/Directory",
                          "= '" + directory + "' cannot be used for output (" +
                            (reason.empty() ? "failed on rank 0" : reason) +
                            ")");
    }

    std::unique_ptr<ImpactModel>
    create_model(const Parameters::ModelType type, const AllParameters &p)
    {
      if (type == Parameters::ModelType::dem)
        return DEM::create_model(p.shared, p.dem, MPI_COMM_WORLD);
      return FE::create_model(p.shared, p.fe, MPI_COMM_WORLD);
    }
  } // namespace


  void
  AllParameters::declare_parameters(ParameterHandler &prm)
  {
    Parameters::Shared::declare_parameters(prm);
    FE::Parameters::declare_parameters(prm);
    DEM::Parameters::declare_parameters(prm);
    DEM::ElementaryTestParameters::declare_parameters(prm);
  }

  void
  AllParameters::parse_parameters(ParameterHandler &prm)
  {
    shared.parse_parameters(prm);
    fe.parse_parameters(prm);
    dem.parse_parameters(prm);
    elementary.parse_parameters(prm);
    Parameters::require(
      elementary.loading == DEM::ElementaryLoading::none ||
        shared.general.model == Parameters::ModelType::dem,
      "Elementary test/Loading",
      "is a loading of the DEM model: it needs Model = dem");
    if (shared.general.model != Parameters::ModelType::dem)
      FE::validate(shared, fe);
  }

  AllParameters
  read_parameters(const std::string &file, ParameterHandler &prm)
  {
    {
      std::ifstream in(file);
      if (!in)
        throw InputError("cannot open the parameter file '" + file + "'.");
    }
    try
      {
        prm.parse_input(file, "", false, false);
      }
    catch (const ExceptionBase &e)
      {
        std::ostringstream info;
        e.print_info(info);
        throw InputError(one_line(info.str()));
      }
    AllParameters parameters;
    try
      {
        parameters.parse_parameters(prm);
      }
    catch (const InputError &)
      {
        throw;
      }
    catch (const ExceptionBase &e)
      {
        std::ostringstream info;
        e.print_info(info);
        throw InputError(one_line(info.str()));
      }
    return parameters;
  }


  int
  run_application(int argc, char **argv)
  {
    const bool is_root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    std::ostream &out  = std::cout;
    std::vector<std::string> args(argv + 1, argv + argc);

    ParameterHandler prm;
    AllParameters::declare_parameters(prm);

    if (args.size() == 1 && (args[0] == "--help" || args[0] == "-h"))
      {
        if (is_root)
          out << usage;
        return 0;
      }
    if (args.size() == 1 && args[0] == "--print-parameters")
      {
        if (is_root)
          prm.print_parameters(out, ParameterHandler::PRM);
        return 0;
      }
    const bool check_only = (args.size() == 2 && args[0] == "--check");
    if (!(args.size() == 1 && args[0].size() > 0 && args[0][0] != '-') &&
        !check_only)
      {
        if (is_root)
          std::cerr << "yarn-impact: error: invalid command line (see "
                       "yarn-impact --help)\n";
        return 2;
      }
    const std::string file = args.back();

    try
      {
        AllParameters parameters = read_parameters(file, prm);
        if (check_only)
          {
            if (is_root)
              out << file << ": parameters are valid\n";
            return 0;
          }

        const auto &output = parameters.shared.output;
        prepare_output_directory(output.directory, is_root);
        if (is_root)
          {
            std::ofstream resolved(output.directory + "/parameters.prm");
            prm.print_parameters(resolved, ParameterHandler::ShortPRM);
          }

        if (parameters.elementary.loading != DEM::ElementaryLoading::none)
          {
            const bool passed =
              DEM::run_elementary_test(parameters.shared,
                                       parameters.dem,
                                       parameters.elementary,
                                       MPI_COMM_WORLD,
                                       out);
            if (!passed)
              {
                if (is_root)
                  std::cerr
                    << "yarn-impact: error: a verification check failed\n";
                return 3;
              }
            return 0;
          }

        std::vector<Parameters::ModelType> models;
        if (parameters.shared.general.model == Parameters::ModelType::both)
          models = {Parameters::ModelType::fe, Parameters::ModelType::dem};
        else
          models = {parameters.shared.general.model};

        bool passed = true;
        std::ostringstream summary_text;
        std::vector<std::vector<HistoryRow>> histories;
        std::string run_errors;
        double mass_per_length[2] = {0., 0.}, axial_stiffness[2] = {0., 0.};
        for (const auto type : models)
          {
            ImpactSimulation simulation(parameters.shared,
                                        create_model(type, parameters),
                                        MPI_COMM_WORLD,
                                        out);
            try
              {
                const RunSummary summary = simulation.run();
                print_summary(summary, summary_text);
                passed = passed && summary.checks_passed;
              }
            catch (const RunError &e)
              {
                // With both models, a model that fails still leaves its
                // history up to the failure to the comparison.
                if (models.size() == 1)
                  throw;
                run_errors +=
                  std::string(run_errors.empty() ? "" : " ") + e.what();
                summary_text << "The " << simulation.model().name()
                             << " model stopped early: " << e.what() << '\n';
              }
            mass_per_length[histories.size()] =
              simulation.model().mass() / parameters.shared.yarn.length;
            axial_stiffness[histories.size()] =
              simulation.model().axial_properties().axial_stiffness();
            histories.push_back(simulation.history());
          }
        if (histories.size() == 2 && is_root)
          {
            const auto comparison = Analysis::compare_models(histories[0],
                                                             histories[1],
                                                             output.directory);
            Analysis::print_comparison(comparison,
                                       mass_per_length,
                                       axial_stiffness,
                                       histories[0],
                                       histories[1],
                                       summary_text);
            const std::string command =
              "/usr/bin/python3 " YARN_IMPACT_SCRIPT_DIR
              "/plot_comparison.py '" +
              output.directory + "' > /dev/null 2>&1";
            if (std::system(command.c_str()) != 0)
              summary_text << "  (plots skipped: " << command
                           << " failed; python3-matplotlib missing?)\n";
            else
              summary_text << "  plots: velocity_comparison.png, "
                              "wave_fronts.png\n";
          }
        if (is_root)
          {
            out << summary_text.str();
            std::ofstream f(output.directory + "/summary.txt");
            f << summary_text.str();
          }
        if (!run_errors.empty())
          throw RunError(run_errors);
        if (!passed)
          {
            if (is_root)
              std::cerr << "yarn-impact: error: a verification check failed\n";
            return 3;
          }
        return 0;
      }
    catch (const InputError &e)
      {
        if (is_root)
          std::cerr << "yarn-impact: error: " << e.what() << std::endl;
        return 1;
      }
    catch (const RunError &e)
      {
        if (is_root)
          std::cerr << "yarn-impact: error: " << e.what() << std::endl;
        return 4;
      }
  }
} // namespace YarnImpact
