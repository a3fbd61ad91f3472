#include <yarn_impact/app/application.h>

#include <deal.II/base/logstream.h>
#include <deal.II/base/mpi.h>

#include <cstdlib>
#include <exception>
#include <iostream>
#include <memory>

namespace
{
  /**
   * Whether an MPI launcher (OpenMPI's mpirun, MPICH's Hydra, a PMIx
   * launcher) started this process, one rank among possibly several.
   */
  bool
  started_by_mpi_launcher()
  {
    for (const char *variable :
         {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMI_RANK", "PMIX_RANK"})
      if (std::getenv(variable) != nullptr)
        return true;
    return false;
  }
} // namespace

int
main(int argc, char **argv)
{
  try
    {
      // Under a launcher every rank starts MPI at once, so that only rank 0
      // prints. Alone, the process starts it only once the parameters are
      // read and the run goes on: MPI's start-up is about 0.6 s of the 1.2 s
      // of a `--check` or a refused set-up, of which scripts and the test
      // suite make hundreds.
      std::unique_ptr<dealii::Utilities::MPI::MPI_InitFinalize> mpi;
      const auto start_mpi = [&]() {
        if (!mpi)
          mpi = std::make_unique<dealii::Utilities::MPI::MPI_InitFinalize>(argc,
                                                                           argv,
                                                                           1);
      };
      if (started_by_mpi_launcher())
        start_mpi();
      dealii::deallog.depth_console(0);
      return YarnImpact::run_application(argc, argv, start_mpi);
    }
  catch (const std::exception &e)
    {
      std::cerr << "yarn-impact: error: " << e.what() << std::endl;
      return 1;
    }
}
