#include <yarn_impact/core/output_file.h>
#include <yarn_impact/dem/vtu_writer.h>

#include <cstring>
#include <fstream>
#include <stdexcept>

namespace YarnImpact
{
  namespace DEM
  {
    namespace VTU
    {
      template <typename T>
      void
      Array::push(const T value)
      {
        std::uint8_t raw[4];
        if (type == "Float32")
          {
            const float v = static_cast<float>(value);
            std::memcpy(raw, &v, 4);
            bytes.insert(bytes.end(), raw, raw + 4);
          }
        else if (type == "Int32")
          {
            const std::int32_t v = static_cast<std::int32_t>(value);
            std::memcpy(raw, &v, 4);
            bytes.insert(bytes.end(), raw, raw + 4);
          }
        else
          bytes.push_back(static_cast<std::uint8_t>(value));
      }

      template void
      Array::push<double>(const double);
      template void
      Array::push<float>(const float);
      template void
      Array::push<int>(const int);
      template void
      Array::push<unsigned int>(const unsigned int);

      namespace
      {
        void
        base64(std::ostream &out, const std::uint8_t *data, std::size_t n)
        {
          static const char table[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijk"
                                      "lmnopqrstuvwxyz0123456789+/";
          std::string s;
          s.reserve(4 * (n / 3 + 1));
          for (std::size_t i = 0; i < n; i += 3)
            {
              const unsigned int b0 = data[i];
              const unsigned int b1 = (i + 1 < n ? data[i + 1] : 0);
              const unsigned int b2 = (i + 2 < n ? data[i + 2] : 0);
              s += table[b0 >> 2];
              s += table[((b0 & 3) << 4) | (b1 >> 4)];
              s += (i + 1 < n ? table[((b1 & 15) << 2) | (b2 >> 6)] : '=');
              s += (i + 2 < n ? table[b2 & 63] : '=');
            }
          out << s;
        }

        void
        write_array(std::ostream &out,
                    const std::string &name,
                    const std::string &type,
                    const unsigned int components,
                    const std::uint8_t *data,
                    const std::size_t n)
        {
          out << "<DataArray type=\"" << type << "\"";
          if (!name.empty())
            out << " Name=\"" << name << "\"";
          out << " NumberOfComponents=\"" << components
              << "\" format=\"binary\">\n";
          const std::uint32_t header = static_cast<std::uint32_t>(n);
          std::uint8_t h[4];
          std::memcpy(h, &header, 4);
          base64(out, h, 4);
          base64(out, data, n);
          out << "\n</DataArray>\n";
        }
      } // namespace

      void
      write_piece(const std::string &file,
                  const std::vector<float> &points,
                  const std::vector<int32_t> &lines,
                  const std::vector<Array> &point_data,
                  const std::vector<Array> &cell_data)
      {
        AtomicFile atomic(file);
        std::ostream &out          = atomic.stream();
        const std::size_t n_points = points.size() / 3;
        const std::size_t n_cells  = lines.size() / 2;
        out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" "
               "version=\"0.1\" byte_order=\"LittleEndian\" "
               "header_type=\"UInt32\">\n<UnstructuredGrid>\n<Piece "
               "NumberOfPoints=\""
            << n_points << "\" NumberOfCells=\"" << n_cells << "\">\n";
        const auto write_all = [&out](const auto &arrays) {
          for (const auto &a : arrays)
            write_array(out,
                        a.name,
                        a.type,
                        a.components,
                        a.bytes.data(),
                        a.bytes.size());
        };
        out << "<PointData>\n";
        write_all(point_data);
        out << "</PointData>\n<CellData>\n";
        write_all(cell_data);
        out << "</CellData>\n<Points>\n";
        write_array(out,
                    "",
                    "Float32",
                    3,
                    reinterpret_cast<const std::uint8_t *>(points.data()),
                    4 * points.size());
        out << "</Points>\n<Cells>\n";
        write_array(out,
                    "connectivity",
                    "Int32",
                    1,
                    reinterpret_cast<const std::uint8_t *>(lines.data()),
                    4 * lines.size());
        std::vector<std::int32_t> offsets(n_cells);
        for (std::size_t c = 0; c < n_cells; ++c)
          offsets[c] = 2 * (c + 1);
        write_array(out,
                    "offsets",
                    "Int32",
                    1,
                    reinterpret_cast<const std::uint8_t *>(offsets.data()),
                    4 * offsets.size());
        std::vector<std::uint8_t> types(n_cells, 3); // VTK_LINE
        write_array(out, "types", "UInt8", 1, types.data(), types.size());
        out << "</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
        atomic.commit();
      }

      void
      write_record(const std::string &file,
                   const std::vector<std::string> &pieces,
                   const std::vector<Array> &point_data,
                   const std::vector<Array> &cell_data)
      {
        AtomicFile atomic(file);
        std::ostream &out = atomic.stream();
        out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" "
               "version=\"0.1\" byte_order=\"LittleEndian\" "
               "header_type=\"UInt32\">\n<PUnstructuredGrid "
               "GhostLevel=\"0\">\n<PPointData>\n";
        for (const auto &a : point_data)
          out << "<PDataArray type=\"" << a.type << "\" Name=\"" << a.name
              << "\" NumberOfComponents=\"" << a.components << "\"/>\n";
        out << "</PPointData>\n<PCellData>\n";
        for (const auto &a : cell_data)
          out << "<PDataArray type=\"" << a.type << "\" Name=\"" << a.name
              << "\" NumberOfComponents=\"" << a.components << "\"/>\n";
        out << "</PCellData>\n<PPoints>\n<PDataArray type=\"Float32\" "
               "NumberOfComponents=\"3\"/>\n</PPoints>\n";
        for (const auto &p : pieces)
          out << "<Piece Source=\"" << p << "\"/>\n";
        out << "</PUnstructuredGrid>\n</VTKFile>\n";
        atomic.commit();
      }


      std::string
      write_parallel(const std::string &directory,
                     const std::string &base,
                     const std::vector<float> &points,
                     const std::vector<int32_t> &lines,
                     const std::vector<Array> &point_data,
                     const std::vector<Array> &cell_data,
                     const MPI_Comm communicator)
      {
        int rank = 0, n_ranks = 1;
        MPI_Comm_rank(communicator, &rank);
        MPI_Comm_size(communicator, &n_ranks);
        const auto piece = [&](const int q) {
          return base + "_r" + std::to_string(q) + ".vtu";
        };
        write_piece(directory + "/" + piece(rank),
                    points,
                    lines,
                    point_data,
                    cell_data);
        if (rank == 0)
          {
            std::vector<std::string> pieces;
            for (int q = 0; q < n_ranks; ++q)
              pieces.push_back(piece(q));
            write_record(directory + "/" + base + ".pvtu",
                         pieces,
                         point_data,
                         cell_data);
          }
        MPI_Barrier(communicator);
        return base + ".pvtu";
      }
    } // namespace VTU
  }   // namespace DEM
} // namespace YarnImpact
