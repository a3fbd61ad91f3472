#ifndef yarn_impact_app_output_directory_h
#define yarn_impact_app_output_directory_h

#include <yarn_impact/app/application.h>
#include <yarn_impact/core/output_lock.h>
#include <yarn_impact/core/parameters.h>

#include <ostream>
#include <string>
#include <vector>

namespace YarnImpact
{
  namespace internal
  {
    /**
     * Take @p lock of Output/Directory for this run (a directory in use is
     * refused), refuse a directory that holds an earlier run's output, or
     * with Output/Overwrite remove that output, and make sure it is
     * writable; none of @p input_files may be overwritten. Decided on rank
     * 0 (@p is_root) and broadcast; throws DirectoryInUse or InputError on
     * every rank.
     */
    void
    prepare_output_directory(const Parameters::Output &output,
                             const std::vector<std::string> &input_files,
                             const bool is_root,
                             std::ostream &out,
                             OutputLock &lock);

    /**
     * The checks of a --restart of @p p: @p lock taken first, the earlier
     * run's parameters the same as @p resolved (Output/Directory aside), a
     * checkpoint there. Decided on rank 0 and broadcast; throws
     * DirectoryInUse or InputError on every rank.
     */
    void
    check_restart(const AllParameters &p,
                  const std::string &resolved,
                  OutputLock &lock);

    /** Remove the checkpoints of a run that has ended (rank 0). */
    void
    remove_checkpoints(const std::string &dir);
  } // namespace internal
} // namespace YarnImpact

#endif
