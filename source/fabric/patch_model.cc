// The generated patch (WovenPatch) given to the FE model
// (FE::GivenMesh, doc/fabric.md section 2).

#include <yarn_impact/core/crimped_yarn.h>
#include <yarn_impact/fabric/fabric_model.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace YarnImpact
{
  namespace Fabric
  {
    namespace
    {
      /**
       * Whether each yarn of @p patch is primary (true), the projectile's
       * footprint on the fabric's plane at the start covering part of it,
       * or secondary: the footprint is the strip |x - x_0| < R of the
       * cylinder along z, the disc of radius R about (x_0, z_0) of the
       * sphere and the flat cylinder; a yarn's is the band of its width,
       * 2 a_z, about its centreline's position.
       */
      std::vector<bool>
      primary_yarns(const WovenPatch &patch,
                    const YarnImpact::Parameters::Projectile &projectile)
      {
        const double reach =
          0.5 * projectile.diameter + patch.geometry().width_semi_axis;
        const bool strip =
          projectile.shape == YarnImpact::Parameters::ProjectileShape::cylinder;
        std::vector<bool> primary(patch.n_yarns());
        for (unsigned int id = 0; id < patch.n_yarns(); ++id)
          primary[id] =
            patch.is_warp(id)
              ? strip ||
                  std::abs(patch.position(id) - projectile.offset_z) < reach
              : std::abs(patch.position(id) - projectile.offset_x) < reach;
        return primary;
      }
    } // namespace


    /**
     * Give the FE parameters @p p the generated patch (FE::GivenMesh):
     * its mesh, fibre directions, section heights and sections, each
     * cell's ply, and the energy groups 2 p (ply p's primary yarns) and
     * 2 p + 1 (its secondary ones).
     * @param primary_ids set to the primary yarns' list, @p ply_heights
     * to the plies' heights, for the set-up report
     * @return the length of all yarns' centrelines [m], of the whole
     * patch where symmetry planes cut it
     */
    double
    use_patch(const std::shared_ptr<const WovenPatch> &patch,
              const YarnImpact::Parameters::Projectile &projectile,
              FE::Parameters &p,
              std::string &primary_ids,
              std::string &ply_heights)
    {
      const WovenPatchGeometry &g = patch->geometry();
      p.mesh.create               = [patch](dealii::Triangulation<3, 3> &mesh) {
        patch->create_mesh(mesh);
      };
      p.mesh.section_height = [patch](const double *xyz) {
        const dealii::Point<3> X(xyz[0], xyz[1], xyz[2]);
        const unsigned int id    = patch->yarn_of(X);
        const CrimpedYarn &y     = patch->yarn(id);
        const dealii::Point<3> P = patch->to_yarn_frame(id, X);
        const double s           = y.abscissa_of(P);
        return (P - y.centreline(s)) * y.normal(s);
      };
      p.fibre_direction = [patch](const double *xyz, double *M) {
        const dealii::Tensor<1, 3> t =
          patch->fibre_direction(dealii::Point<3>(xyz[0], xyz[1], xyz[2]));
        for (unsigned int d = 0; d < 3; ++d)
          M[d] = t[d];
      };

      // The broken yarns, by the sections of each yarn's cells; each
      // cell's ply in the snapshots.
      p.mesh.section = [patch](const unsigned int id, const double *xyz) {
        return patch->section_of(id, dealii::Point<3>(xyz[0], xyz[1], xyz[2]));
      };
      p.mesh.sections_per_yarn =
        std::max(g.n_warp, g.n_weft) * g.cells_per_spacing;
      p.mesh.n_yarns = patch->n_yarns();
      for (unsigned int id = 0; id < patch->n_yarns(); ++id)
        p.mesh.yarn_copies.push_back(patch->copies(id));
      p.mesh.material_fields = {
        {"ply", [patch](const unsigned int id) { return patch->ply(id); }}};

      // The energies of each ply's primary and secondary yarns apart:
      // group 2 p + 0 or 1.
      const std::vector<bool> primary = primary_yarns(*patch, projectile);
      p.energy_group = [primary, patch](const unsigned int id) {
        return 2 * patch->ply(id) + (primary[id] ? 0u : 1u);
      };
      p.n_energy_groups = 2 * g.n_plies;
      std::ostringstream ids, plies;
      for (unsigned int id = 0; id < patch->n_yarns(); ++id)
        if (primary[id])
          ids << (ids.tellp() > 0 ? ", " : "")
              << (g.n_plies > 1 ? "ply " + std::to_string(patch->ply(id)) + " "
                                : "")
              << (patch->is_warp(id) ? "warp " : "weft ")
              << patch->index_in_family(id);
      plies << g.n_plies << " plies, ";
      if (g.ply_offset_x == 0. && g.ply_offset_z == 0.)
        plies << "aligned";
      else
        plies << "each shifted by (" << g.ply_offset_x * 1e3 << ", "
              << g.ply_offset_z * 1e3 << ") mm along (x, z) from the one above";
      plies << ", their mid-planes at y =";
      for (unsigned int k = 0; k < g.n_plies; ++k)
        plies << (k > 0 ? "," : "") << " " << patch->ply_height(k) * 1e3;
      plies << " mm (yarn ids " << patch->yarns_per_ply()
            << " per ply, ply 0 first), a gap of "
            << (g.ply_spacing - WovenPatch::ply_thickness(g)) * 1e3
            << " mm between neighbouring plies' meshes";
      primary_ids = ids.str();
      ply_heights = plies.str();

      double yarn_length = 0.;
      for (unsigned int id = 0; id < patch->n_yarns(); ++id)
        yarn_length +=
          patch->length_copies(id) * patch->yarn(id).centreline_length();
      return yarn_length;
    }
  } // namespace Fabric
} // namespace YarnImpact
