#include <yarn_impact/app/application.h>

#include <deal.II/base/logstream.h>
#include <deal.II/base/mpi.h>

#include <exception>
#include <iostream>

int
main(int argc, char **argv)
{
  try
    {
      dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
      dealii::deallog.depth_console(0);
      return YarnImpact::run_application(argc, argv);
    }
  catch (const std::exception &e)
    {
      std::cerr << "yarn-impact: error: " << e.what() << std::endl;
      return 1;
    }
}
