#include <yarn_impact/core/memory_estimate.h>
#include <yarn_impact/core/parameter_tools.h>

#include <deal.II/base/mpi.h>

#include <fstream>
#include <sstream>
#include <unistd.h>

namespace YarnImpact
{
  namespace
  {
    /** Resident size of one rank before the model allocates: MPI, deal.II,
     * Trilinos and p4est loaded (150-160 MB measured at set-up). */
    constexpr double base_per_rank = 160e6;
  } // namespace

  double
  available_memory()
  {
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    double kilobytes = 0.;
    std::string unit;
    while (meminfo >> key >> kilobytes >> unit)
      if (key == "MemAvailable:")
        return kilobytes * 1024.;
    return double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  }

  unsigned int
  ranks_in(const MPI_Comm communicator)
  {
    return dealii::Utilities::MPI::job_supports_mpi()
             ? dealii::Utilities::MPI::n_mpi_processes(communicator)
             : 1;
  }


  unsigned int
  rank_in(const MPI_Comm communicator)
  {
    return dealii::Utilities::MPI::job_supports_mpi()
             ? dealii::Utilities::MPI::this_mpi_process(communicator)
             : 0;
  }


  std::string
  check_memory(const MemoryEstimate &estimate,
               const std::string &model_name,
               const MPI_Comm communicator)
  {
    const unsigned int n_ranks = ranks_in(communicator);
    // The ranks that share this machine's memory. One rank needs no MPI
    // call (it may run without MPI: app/main.cc).
    unsigned int ranks_here = 1;
    if (n_ranks > 1)
      {
        MPI_Comm node;
        MPI_Comm_split_type(communicator,
                            MPI_COMM_TYPE_SHARED,
                            0,
                            MPI_INFO_NULL,
                            &node);
        ranks_here = dealii::Utilities::MPI::n_mpi_processes(node);
        MPI_Comm_free(&node);
      }
    const double here =
      estimate.bytes * ranks_here / n_ranks + base_per_rank * ranks_here;
    // One view of the machine: rank 0's.
    const double available =
      n_ranks > 1
        ? dealii::Utilities::MPI::broadcast(communicator, available_memory(), 0)
        : available_memory();
    std::ostringstream s;
    s.precision(3);
    if (here > available)
      {
        s << "Parameter '" << estimate.parameter << "' makes the " << model_name
          << " set-up need about " << here / 1e9 << " GB ("
          << estimate.n_elements << " " << estimate.element_name << " on "
          << ranks_here << " rank(s) of this machine), more than the "
          << available / 1e9 << " GB of memory available here.";
        throw InputError(s.str());
      }
    s << "[" << model_name << "] memory estimate: " << here / 1e6 << " MB for "
      << estimate.n_elements << " " << estimate.element_name << " on "
      << ranks_here << " rank(s) of this machine (" << available / 1e9
      << " GB available)";
    return s.str();
  }
} // namespace YarnImpact
