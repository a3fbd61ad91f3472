#ifndef yarn_impact_fabric_mesh_file_h
#define yarn_impact_fabric_mesh_file_h

#include <yarn_impact/core/parameters.h>
#include <yarn_impact/fe/parameters.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/grid/tria.h>

#include <array>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace YarnImpact
{
  namespace Fabric
  {
    /** Physical surface tags of a mesh file (doc/fabric.md section 8): a
     * boundary face tagged so keeps its role; an untagged one (tag 0) is
     * classified by its normal against its cell's fibre direction. */
    namespace MeshFileTags
    {
      /** The lateral (contact) surface of a yarn. */
      constexpr unsigned int lateral = 1;
      /** A clamped end section. */
      constexpr unsigned int clamped_end = 2;
      /** A free end section. */
      constexpr unsigned int free_end = 3;
    } // namespace MeshFileTags

    /** A mesh or orientation file that cannot be used: what() is the
     * message, parameter the entry it belongs to. */
    struct MeshFileError : public std::invalid_argument
    {
      /** @param parameter `Fabric/Mesh file` or `Fabric/Orientation file`
       * @param message one line naming the file */
      MeshFileError(const std::string &parameter, const std::string &message)
        : std::invalid_argument(message)
        , parameter(parameter)
      {}
      /** The entry, e.g. `Fabric/Mesh file`. */
      std::string parameter;
    };

    /**
     * A fabric's mesh read from a Gmsh file (`Fabric/Mesh file`,
     * doc/fabric.md section 8) by deal.II's GridIn: hexahedra whose
     * physical group g >= 1 makes them cells of yarn g - 1 (the material
     * id), the fibre direction of every cell read from an orientation
     * file (one line per cell in the file's order: one unit direction
     * [-], or one per Gauss point of the 2 x 2 x 2 Gauss rule) or
     * estimated from the mesh (the cell's local axis along which its
     * yarn's cells form the longest chain of face neighbours), the
     * boundary faces' roles from the file's physical surfaces or from
     * their normals, and each cell's section (the layer of cells across
     * its yarn at one position along it).
     *
     * Every failure throws MeshFileError, one line naming the parameter
     * and the file.
     */
    class MeshFile
    {
    public:
      /**
       * Read @p mesh_file and, if not empty, @p orientation_file.
       * @param clamp_warp_ends whether the end sections of yarns running
       * mostly along x are clamped (those the file leaves untagged)
       * @param clamp_weft_ends the same for yarns running mostly along z
       */
      MeshFile(const std::string &mesh_file,
               const std::string &orientation_file,
               const bool clamp_warp_ends,
               const bool clamp_weft_ends);

      /** The mesh as read, material id = yarn id, boundary ids those of
       * BoundaryIds (lateral, end) and free_end_boundary_id. */
      void
      create_mesh(dealii::Triangulation<3, 3> &mesh) const;

      /** Number of cells [-]. */
      unsigned int
      n_cells() const
      {
        return cell_yarn.size();
      }

      /** Number of yarns [-]: the largest yarn id plus one. */
      unsigned int
      n_yarns() const
      {
        return yarns;
      }

      /** The most sections of one yarn [-]. */
      unsigned int
      sections_per_yarn() const
      {
        return max_sections;
      }

      /** Whether the directions came from an orientation file (false:
       * estimated). */
      bool
      directions_read() const
      {
        return read_directions;
      }

      /** The cell [-], in the file's order, that holds the reference
       * point @p X [m]: the candidate whose unit coordinates are the
       * deepest inside it. Throws if none is within 1e-6 of its unit
       * cube. */
      unsigned int
      locate(const dealii::Point<3> &X) const;

      /** The unit fibre direction [-] at the reference point @p X [m]: its
       * cell's, or that of the nearest of its Gauss points where the
       * orientation file gives one per Gauss point. */
      dealii::Tensor<1, 3>
      fibre_direction(const dealii::Point<3> &X) const;

      /** The mean unit fibre direction [-] of cell @p c. */
      const dealii::Tensor<1, 3> &
      cell_direction(const unsigned int c) const
      {
        return mean_direction[c];
      }

      /** The section [-] of cell @p c, below sections_per_yarn(). */
      unsigned int
      section(const unsigned int c) const
      {
        return cell_section[c];
      }

      /** The height [m] of @p X across its yarn towards +y: along the
       * unit vector normal to its cell's fibre direction nearest +y, from
       * the mean centre of the cells of its cell's section. */
      double
      section_height(const dealii::Point<3> &X) const;

      /** Whether yarn @p id runs mostly along x (a warp yarn) [-]. */
      bool
      is_warp(const unsigned int id) const
      {
        return warp[id];
      }

      /** The span [m] of yarn @p id along its mean fibre direction (its
       * vertices' extent). */
      double
      yarn_span(const unsigned int id) const
      {
        return span[id];
      }

      /** The mesh as read (serial; its cells in the file's order, their
       * material ids the physical groups). */
      const dealii::Triangulation<3, 3> &
      triangulation() const
      {
        return tria;
      }

      /** The yarn id of cell @p c [-]. */
      unsigned int
      yarn(const unsigned int c) const
      {
        return cell_yarn[c];
      }

      /**
       * The estimated unit fibre direction [-] of every cell of @p mesh,
       * by active cell index: of the cell's three local axes, the one
       * along which the chain of face neighbours of the same material id
       * through opposite faces is longest (a yarn's cells line up along
       * it, a few across its section), ties going to the longer axis; the
       * direction from the centre of the cell's face at the axis's start
       * to that of its face at the end.
       */
      static std::vector<dealii::Tensor<1, 3>>
      estimate_directions(const dealii::Triangulation<3, 3> &mesh);

    private:
      unsigned int
      locate(const dealii::Point<3> &X, dealii::Point<3> &unit) const;
      void
      read_mesh(const std::string &file);
      void
      read_orientation(const std::string &file);
      void
      find_sections();
      void
      make_bins();
      void
      classify_faces(const bool clamp_warp_ends, const bool clamp_weft_ends);

      /** Fabric/Mesh file, for the messages. */
      std::string file_name;
      dealii::Triangulation<3, 3> tria;
      std::vector<unsigned int> cell_yarn;
      unsigned int yarns = 0, max_sections = 0;
      bool read_directions = false;
      /** Each cell's directions [-]: 1, or 8 for its Gauss points. */
      std::vector<std::vector<dealii::Tensor<1, 3>>> directions;
      std::vector<dealii::Tensor<1, 3>> mean_direction;
      std::vector<unsigned int> cell_section;
      /** Each cell's section's mean cell centre [m]. */
      std::vector<dealii::Point<3>> section_centre;
      std::vector<bool> warp;
      std::vector<double> span;
      /** The boundary id of each boundary face, by its sorted vertex
       * indices. */
      std::map<std::array<unsigned int, 4>, unsigned int> face_ids;
      /** Bins of cells by their bounding boxes: origin [m], width [m],
       * counts [-], cells of each bin [-]. */
      dealii::Point<3> bin_origin;
      double bin_width                   = 1.;
      std::array<unsigned int, 3> n_bins = {{1, 1, 1}};
      std::vector<std::vector<unsigned int>> bins;
    };

    /**
     * Give the FE parameters @p p the read mesh @p file in place of the
     * generated patch (FE::GivenMesh): its mesh, fibre directions
     * (MeshFile::fibre_direction), section heights and sections, one
     * `ply` 0 for the snapshots, and the energy groups 0 (primary yarns:
     * a vertex inside the projectile's footprint at the start, the strip
     * |x - x_0| < R of the cylinder along z, the disc of radius R about
     * (x_0, z_0) of the others) and 1 (the other yarns).
     * @param primary set to the primary yarns' list for the set-up report
     * @return the yarns' total span along their axes [m]
     */
    double
    use_mesh_file(const std::shared_ptr<const MeshFile> &file,
                  const YarnImpact::Parameters::Projectile &projectile,
                  FE::Parameters &p,
                  std::string &primary);
  } // namespace Fabric
} // namespace YarnImpact

#endif
