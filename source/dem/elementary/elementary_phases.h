#ifndef yarn_impact_source_dem_elementary_elementary_phases_h
#define yarn_impact_source_dem_elementary_elementary_phases_h

// The phases of a DEM elementary test, which run_elementary_test()
// (elementary_test.cc) chains: the loadings and the rows they record
// (elementary_loading.cc), then what is measured on the rows and checked
// (elementary_checks.cc). Not part of the public interface, which is
// dem/elementary/elementary_test.h.

#include <yarn_impact/core/checkpoint.h>
#include <yarn_impact/core/output_file.h>
#include <yarn_impact/dem/elementary/periodic_segment.h>
#include <yarn_impact/mechanics/kinematics.h>

#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      /** One row of the CSV and what the checks need of it. */
      struct Row
      {
        /** "load", "unload" or "consolidation". */
        std::string phase;
        /** Confining pressure [Pa], time [s] and imposed strain [-]. */
        double pressure = 0., time = 0., strain = 0.;
        /** Affine deformation gradient of the segment [-]. */
        Mechanics::Matrix3 F;
        /** Charmetant's invariants of F [-]. */
        Mechanics::Invariants inv;
        /** Height and width of the section (4 sqrt of its second moments)
         * [m]. */
        double height = 0., width = 0.;
        /** Kirchhoff stress of the virial, xx yy zz yz [Pa]. */
        double tau[4] = {0., 0., 0., 0.};
        /** Kirchhoff stress of the walls' forces, yy zz [Pa]. */
        double tau_boundary[2] = {0., 0.};
        /** Mean load of the plates and of the side walls per length
         * [N/m]. */
        double plate_load = 0., wall_load = 0.;
        /** Gaps between the plates and between the side walls [m]. */
        double plate_gap = 0., wall_gap = 0.;
        /** The segment's sums (virial [N m], energies [J]). */
        Sums sums;
        /** Fibres broken so far. */
        unsigned int broken_fibres = 0;
      };


      /** Drives the segment through the steps of one test and records the
       * rows: in memory on every rank, in the CSV on rank 0. */
      class Recorder
      {
      public:
        /**
         * Records the steps of @p segment into @p csv (nullptr: in memory
         * only) under the test's @p name; @p partial is the CSV's file
         * while the test runs, named in the message of an interruption.
         */
        Recorder(PeriodicSegment &segment,
                 AppendFile *csv,
                 const std::string &name,
                 const std::string &partial);

        /** One step of the segment; a SIGTERM or SIGINT (agreed by the
         * ranks within a few steps) stops the test between two steps, its
         * rows so far kept in the .partial file.
         * @throw Interrupted on such a signal */
        void
        step();

        /** Measure the segment now, in the phase @p phase at the confining
         * pressure @p pressure [Pa] and the imposed strain @p strain [-];
         * the row is kept, written and returned. Collective.
         * @throw RunError if a checked quantity is not finite */
        Row
        record(const std::string &phase,
               const double pressure,
               const double strain);

        /** The segment. */
        PeriodicSegment &seg;
        /** The CSV (rank 0), or nullptr. */
        AppendFile *csv;
        /** The test's name (the loading). */
        std::string name;
        /** The CSV's file while the test runs. */
        std::string partial;
        /** Polls SIGTERM and SIGINT across the ranks. */
        Checkpoint::SignalPoll signal_poll;
        /** The rows recorded so far. */
        std::vector<Row> rows;
      };

      /** The CSV's header line (without the newline). */
      extern const char *const elementary_csv_header;

      /** Loading: tension along the fibres, to failure (or to the largest
       * strain), a row at each output increment of the strain. */
      void
      run_tension(PeriodicSegment &seg, Recorder &rec);

      /** Loading: plates normal to y close at the strain rate, then reopen;
       * with @p pressure > 0 [Pa], side walls normal to z hold the yarn at
       * that pressure, after a consolidation in which the plates do too. */
      void
      run_plates(PeriodicSegment &seg, Recorder &rec, const double pressure);


      /** The summary of a test: its lines and whether every check passed. */
      struct Report
      {
        /** The summary's lines. */
        std::ostringstream text;
        /** Whether every check so far passed. */
        bool passed = true;

        /** A check line for @p what, passed if @p ok. */
        void
        check(const std::string &what, const bool ok);
      };

      /** Measurement of a tension test on its rows. */
      struct TensionMeasures
      {
        /** Largest relative deviation of tau_xx from the closed form
         * E phi (lambda - 1) lambda before the first break [-]. */
        double deviation = 0.;
        /** Peak axial Kirchhoff stress [Pa]. */
        double peak = 0.;
        /** k_e fitted to tau_xx = k_e I_e before the first break [Pa]. */
        double k_fit = 0.;
        /** Broken fibres. */
        unsigned int n_broken = 0;
        /** Smallest, mean and largest break strain and its standard
         * deviation [-] (of the broken fibres). */
        double break_min = 1e300, break_max = -1e300, break_mean = 0.,
               break_std = 0.;
        /** Axial Kirchhoff stress of the last row [Pa]. */
        double last_tau_xx = 0.;
      };

      /** Measures a tension test on @p rows, with the break strains of the
       * fibres @p breaks (negative: unbroken) and the closed-form modulus
       * @p E_phi [Pa]. */
      TensionMeasures
      measure_tension(const std::vector<Row> &rows,
                      const std::vector<double> &breaks,
                      const double E_phi);

      /** Reports the tension measures @p m of the segment @p seg (fibre
       * area fraction @p phi [-], closed-form modulus @p E_phi [Pa]) and
       * checks them against the closed form and the failure strain. */
      void
      check_tension(const TensionMeasures &m,
                    const PeriodicSegment &seg,
                    const double phi,
                    const double E_phi,
                    Report &report);

      /** Measurement of one confining pressure of a plate test. */
      struct PlateMeasures
      {
        /** Peak of -tau_yy on the loading branch [Pa]. */
        double peak_yy = 0.;
        /** Largest gap between the virial's tau_yy and the plates' one,
         * relative to peak_yy [-] (loading, beyond a quarter of the
         * largest strain). */
        double virial_gap = 0.;
        /** Largest kinetic over stored energy there [-]. */
        double ke_ratio = 0.;
        /** Peak ratio sigma_yy / sigma_zz of the box of walls where the side
         * walls hold the pressure [-]. */
        double ratio_peak = 0.;
        /** Largest and mean relative side-wall pressure, and its largest
         * error [-]. */
        double servo_err = 0., servo_mean = 0.;
        /** The row at the peak of -tau_yy (nullptr: none). */
        const Row *at_peak = nullptr;
        /** The first row of the pressure, and the last. */
        const Row *first = nullptr, *end = nullptr;
      };

      /** Measures the rows of @p rows from @p first on, of the confining
       * pressure @p pc [Pa] and the largest strain @p max_strain [-]. */
      PlateMeasures
      measure_plates(const std::vector<Row> &rows,
                     const std::size_t first,
                     const double pc,
                     const double max_strain);

      /** Reports the plate measures @p m of the confining pressure @p pc
       * [Pa] and checks them (side walls, quasi-static balance); with
       * @p friction [-] the closed-form sliding ratio of a hexagonal
       * packing; @p testing: the deterministic form. */
      void
      check_plates(const PlateMeasures &m,
                   const double pc,
                   const double friction,
                   const bool testing,
                   Report &report);
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
