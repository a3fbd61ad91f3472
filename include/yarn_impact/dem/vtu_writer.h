#ifndef yarn_impact_dem_vtu_writer_h
#define yarn_impact_dem_vtu_writer_h

#include <mpi.h>

#include <cstdint>
#include <string>
#include <vector>

namespace YarnImpact
{
  namespace DEM
  {
    /**
     * A minimal writer of VTK XML unstructured grids (`.vtu`, inline base64
     * binary) and their parallel records (`.pvtu`), for points joined by
     * line cells: the DEM spheres and trusses.
     */
    namespace VTU
    {
      /** A named data array of Float32, Int32 or UInt8 values. */
      struct Array
      {
        std::string name;
        std::string type; ///< "Float32", "Int32" or "UInt8"
        unsigned int components = 1;
        std::vector<std::uint8_t> bytes;

        /** Append values (converted to the array's type). */
        template <typename T>
        void
        push(const T value);
      };

      /**
       * Write one piece, whole or not at all (an OutputError naming the file
       * and the cause if it cannot be written).
       * @param points point coordinates, 3 per point [m]
       * @param lines point indices, 2 per line cell
       */
      void
      write_piece(const std::string &file,
                  const std::vector<float> &points,
                  const std::vector<int32_t> &lines,
                  const std::vector<Array> &point_data,
                  const std::vector<Array> &cell_data);

      /** Write the `.pvtu` record of @p pieces (file names relative to the
       * record); the arrays give the names, types and components. Written
       * whole or not at all (an OutputError if it cannot be). */
      void
      write_record(const std::string &file,
                   const std::vector<std::string> &pieces,
                   const std::vector<Array> &point_data,
                   const std::vector<Array> &cell_data);

      /**
       * Write this rank's piece `<directory>/<base>_rR.vtu` (R its rank in
       * @p communicator) and, on rank 0, the record `<base>.pvtu` of every
       * rank's piece; collective (the record is complete when it returns).
       * @return the record's file name, relative to @p directory
       */
      std::string
      write_parallel(const std::string &directory,
                     const std::string &base,
                     const std::vector<float> &points,
                     const std::vector<int32_t> &lines,
                     const std::vector<Array> &point_data,
                     const std::vector<Array> &cell_data,
                     const MPI_Comm communicator);
    } // namespace VTU
  }   // namespace DEM
} // namespace YarnImpact

#endif
