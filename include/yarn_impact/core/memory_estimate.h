#ifndef yarn_impact_core_memory_estimate_h
#define yarn_impact_core_memory_estimate_h

#include <mpi.h>

#include <string>

namespace YarnImpact
{
  /**
   * What a model's set-up will allocate, estimated from its parameters
   * before anything is allocated, and which parameter makes it large.
   */
  struct MemoryEstimate
  {
    /** Bytes over all ranks, base process size excluded [B]. */
    double bytes = 0.;
    /** Number of cells or spheres the estimate counts [-]. */
    double n_elements = 0.;
    /** "cells" or "spheres". */
    std::string element_name;
    /** The parameter (`Subsection/Entry`) whose value contributes the
     * largest factor to the size, named in a refusal. */
    std::string parameter;
  };

  /** Number of ranks of @p communicator; 1 where MPI is not initialised
   * (a parameter check or a refused set-up runs without MPI: app/main.cc),
   * as MPI would give a run without a launcher. */
  unsigned int
  ranks_in(const MPI_Comm communicator);

  /** This process's rank in @p communicator; 0 where MPI is not
   * initialised (see ranks_in()). */
  unsigned int
  rank_in(const MPI_Comm communicator);

  /** Memory this machine has available now (MemAvailable of
   * /proc/meminfo, else the physical memory) [B]. */
  double
  available_memory();

  /**
   * Refuse (an InputError naming @p estimate.parameter) a set-up whose
   * estimate, with @p base_per_rank [B] for each rank of @p communicator
   * on this machine, exceeds the memory available on it; otherwise return
   * a one-line report "memory estimate: ... MB for N cells on R ranks".
   * Collective; needs no MPI on one rank.
   */
  std::string
  check_memory(const MemoryEstimate &estimate,
               const std::string &model_name,
               const MPI_Comm communicator);
} // namespace YarnImpact

#endif
