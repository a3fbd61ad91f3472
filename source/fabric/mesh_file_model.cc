// The read mesh (MeshFile) given to the FE model in place of the
// generated patch (doc/fabric.md section 8).

#include <yarn_impact/fabric/mesh_file.h>

#include <cmath>
#include <sstream>
#include <vector>

namespace YarnImpact
{
  namespace Fabric
  {
    double
    use_mesh_file(const std::shared_ptr<const MeshFile> &file,
                  const YarnImpact::Parameters::Projectile &projectile,
                  FE::Parameters &p,
                  std::string &primary)
    {
      p.mesh.create = [file](dealii::Triangulation<3, 3> &mesh) {
        file->create_mesh(mesh);
      };
      p.mesh.section_height = [file](const double *xyz) {
        return file->section_height(dealii::Point<3>(xyz[0], xyz[1], xyz[2]));
      };
      p.fibre_direction = [file](const double *xyz, double *M) {
        const dealii::Tensor<1, 3> t =
          file->fibre_direction(dealii::Point<3>(xyz[0], xyz[1], xyz[2]));
        for (unsigned int d = 0; d < 3; ++d)
          M[d] = t[d];
      };
      // The FE model asks by the cell's reference centre, inside it.
      p.mesh.section = [file](const unsigned int, const double *xyz) {
        return file->section(
          file->locate(dealii::Point<3>(xyz[0], xyz[1], xyz[2])));
      };
      p.mesh.sections_per_yarn = file->sections_per_yarn();
      p.mesh.n_yarns           = file->n_yarns();
      p.mesh.material_fields = {{"ply", [](const unsigned int) { return 0.; }}};

      // The primary yarns: a vertex inside the footprint.
      const double R = 0.5 * projectile.diameter;
      const bool strip =
        projectile.shape == YarnImpact::Parameters::ProjectileShape::cylinder;
      std::vector<bool> is_primary(file->n_yarns(), false);
      for (unsigned int c = 0; c < file->n_cells(); ++c)
        {
          const dealii::Triangulation<3>::active_cell_iterator
            cell(&file->triangulation(), 0, c);
          for (unsigned int v = 0; v < 8; ++v)
            {
              const double dx = cell->vertex(v)[0] - projectile.offset_x,
                           dz = cell->vertex(v)[2] - projectile.offset_z;
              if (strip ? std::abs(dx) < R : std::hypot(dx, dz) < R)
                is_primary[file->yarn(c)] = true;
            }
        }
      p.energy_group = [is_primary](const unsigned int id) {
        return is_primary[id] ? 0u : 1u;
      };
      p.n_energy_groups = 2;
      std::ostringstream ids;
      double span = 0.;
      for (unsigned int id = 0; id < file->n_yarns(); ++id)
        {
          if (is_primary[id])
            ids << (ids.tellp() > 0 ? ", " : "") << "yarn " << id;
          span += file->yarn_span(id);
        }
      primary = ids.str();
      return span;
    }
  } // namespace Fabric
} // namespace YarnImpact
