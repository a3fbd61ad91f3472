// Stopping a run on SIGTERM or SIGINT (doc/user-guide.md, "Checkpoint and
// restart"): the handler, SignalPoll, which lets every rank agree on a
// signal without a blocking reduction per step, and the tests' injected
// signal.

#include <yarn_impact/core/checkpoint.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <ctime>

namespace YarnImpact
{
  namespace Checkpoint
  {
    namespace
    {
      volatile std::sig_atomic_t received = 0;
      /** When the first signal came (CLOCK_MONOTONIC) [s]. */
      volatile double received_at = 0.;

      double
      monotonic_seconds()
      {
        // clock_gettime is async-signal-safe (POSIX.1-2008).
        timespec now{};
        clock_gettime(CLOCK_MONOTONIC, &now);
        return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
      }

      extern "C" void
      on_signal(int signal)
      {
        // A second signal while the first is still being handled ends the
        // process as it would without the handler; one within a second of
        // the first is the same request delivered twice (Ctrl-C reaches
        // mpirun and the ranks, and mpirun forwards it as SIGTERM; a
        // scheduler signals mpirun and the ranks) and is ignored.
        if (received != 0)
          {
            if (monotonic_seconds() - received_at < 1.)
              return;
            std::signal(signal, SIG_DFL);
            std::raise(signal);
            return;
          }
        received_at = monotonic_seconds();
        received    = signal;
      }
    } // namespace


    void
    install_signal_handlers()
    {
      received = 0;
      std::signal(SIGTERM, on_signal);
      std::signal(SIGINT, on_signal);
    }

    int
    signal_received()
    {
      return received;
    }


    SignalPoll::SignalPoll(const MPI_Comm communicator,
                           const unsigned int period)
      : period(std::max(1u, period))
    {
      int size = 1;
      MPI_Comm_size(communicator, &size);
      if (size > 1)
        MPI_Comm_dup(communicator, &comm);
    }


    SignalPoll::~SignalPoll()
    {
      if (comm == MPI_COMM_NULL)
        return;
      // Every rank destroys its poll at the same point of the run (its
      // end, or an exception thrown on every rank): the reduction in
      // flight completes on all.
      if (pending)
        MPI_Wait(&request, MPI_STATUS_IGNORE);
      MPI_Comm_free(&comm);
    }


    int
    SignalPoll::poll()
    {
      if (comm == MPI_COMM_NULL)
        return received;
      if (++calls % period != 0)
        return 0;
      // The reduction started `period` calls ago has had that long to
      // complete: waiting for it costs nothing, and every rank gets its
      // result at the same call.
      int agreed = 0;
      if (pending)
        {
          MPI_Wait(&request, MPI_STATUS_IGNORE);
          agreed = reduced;
        }
      local = received;
      MPI_Iallreduce(&local, &reduced, 1, MPI_INT, MPI_MAX, comm, &request);
      pending = true;
      return agreed;
    }


    namespace internal
    {
      void
      inject_signal()
      {
        static const long long at = [] {
          const char *value = std::getenv("YARN_IMPACT_SIGNAL_AT_ROW");
          return value != nullptr ? std::atoll(value) : -1LL;
        }();
        static long long rows = 0;
        if (++rows == at)
          std::raise(SIGTERM);
      }
    } // namespace internal
  }   // namespace Checkpoint
} // namespace YarnImpact
