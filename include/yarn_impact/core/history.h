#ifndef yarn_impact_core_history_h
#define yarn_impact_core_history_h

#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/observables.h>
#include <yarn_impact/core/output_file.h>

#include <string>
#include <vector>

namespace YarnImpact
{
  /** One row of the history (doc/user-guide.md), in SI units. */
  struct HistoryRow
  {
    /** Simulated time [s]. */
    double time = 0.;
    /** Time step number [-]. */
    unsigned long step = 0;
    /** Current time step [s]. */
    double time_step = 0.;
    /** Projectile displacement in the impact direction [m]. */
    double projectile_displacement = 0.;
    /** Projectile speed in the impact direction [m/s]. */
    double projectile_velocity = 0.;
    /** Force of the yarn on the projectile, opposing the impact [N]. */
    double contact_force = 0.;
    /** Projectile kinetic energy [J]. */
    double projectile_kinetic_energy = 0.;
    /** Work done by the driver of a prescribed projectile [J]. */
    double external_work = 0.;
    /** Energy balance error: (current total + dissipated - external work -
     * initial total) / initial total [-]. */
    double energy_error = 0.;
    /** The model's observables (their station profile emptied once the
     * fronts are measured on it). */
    Observables model;
    /** Wave fronts and section widths measured on the model's station
     * profile (zero where the run measures none). */
    WaveFrontPositions fronts;
  };

  /**
   * The history CSV `history_<model>.csv` (written by rank 0) and the rows
   * kept in memory for the end-of-run summary. Column names carry their
   * (scaled) units.
   */
  class History
  {
  public:
    /** Open `<directory>/history_<model_name>.csv` on rank 0 and write the
     * header (an OutputError if it cannot): the common column_names(), then
     * @p extra_columns, the model's own (ImpactModel::extra_column_names()),
     * whose values each row's Observables::extra_columns holds. */
    History(const std::string &directory,
            const std::string &model_name,
            const bool is_root,
            const std::vector<std::string> &extra_columns = {});

    /** Open the history of a restarted run:
     * `<directory>/history_<model_name>.csv` written anew on rank 0 with the
     * header and the rows @p rows of the checkpoint, as the uninterrupted run
     * had written them; @p extra_columns as in the other constructor. */
    History(const std::string &directory,
            const std::string &model_name,
            const bool is_root,
            std::vector<HistoryRow> rows,
            const std::vector<std::string> &extra_columns = {});

    /** Append a row, written at once and whole (a crashed run keeps what it
     * had; a failed write throws an OutputError and leaves the file ending
     * with its last whole row). */
    void
    add(const HistoryRow &row);

    /** All rows so far. */
    const std::vector<HistoryRow> &
    rows() const
    {
      return all_rows;
    }

    /** Write every row kept (profiles excepted) to a checkpoint. */
    void
    save(Checkpoint::Writer &out) const;

    /** The rows of a checkpoint, for the constructor of a restarted run. */
    static std::vector<HistoryRow>
    load_rows(Checkpoint::Reader &in);

    /** The CSV column names, in order. */
    static std::vector<std::string>
    column_names();

  private:
    /** The CSV line of @p row. */
    static std::string
    format(const HistoryRow &row);
    /** Create the file and write the header (rank 0). */
    void
    open(const std::string &directory,
         const std::string &model_name,
         const bool is_root,
         const std::vector<std::string> &extra_columns);

    AppendFile file;
    std::vector<HistoryRow> all_rows;
  };
} // namespace YarnImpact

#endif
