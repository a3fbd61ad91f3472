#ifndef yarn_impact_fabric_woven_patch_h
#define yarn_impact_fabric_woven_patch_h

#include <yarn_impact/core/crimped_yarn.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <set>
#include <vector>

namespace dealii
{
  template <int dim, int spacedim>
  class Triangulation;
}

namespace YarnImpact
{
  namespace Fabric
  {
    /** What a plain-woven patch is made of [m, -]. */
    struct WovenPatchGeometry
    {
      /** Warp yarns, along x, side by side in z [-]. */
      unsigned int n_warp = 2;
      /** Weft yarns, along z, side by side in x [-]. */
      unsigned int n_weft = 2;
      /** Distance between neighbouring parallel yarns [m]; the crimp
       * wavelength is twice it. */
      double spacing = 1e-3;
      /** Crimp amplitude A of every yarn [m]; crossing yarns' centrelines
       * are 2 A apart at the crossing. */
      double amplitude = 0.1e-3;
      /** Semi-axis of a section across the fabric (y) [m]. */
      double thickness_semi_axis = 0.0575e-3;
      /** Semi-axis of a section in the fabric's plane [m]. */
      double width_semi_axis = 0.267e-3;
      /** Cells along a yarn per spacing [-]. */
      unsigned int cells_per_spacing = 8;
      /** Refinements of each yarn's 12-cell section [-]. */
      unsigned int section_refinements = 0;
      /** Whether the two end sections of every warp yarn (the patch's
       * edges x = +-n_weft s / 2) are clamped; free ends otherwise. */
      bool clamp_warp_ends = true;
      /** Whether the two end sections of every weft yarn (the patch's
       * edges z = +-n_warp s / 2) are clamped; free ends otherwise. */
      bool clamp_weft_ends = true;
      /** Plies [-]: copies of the woven layer stacked along -y, each
       * shifted from the one above by ply_spacing down and by
       * (ply_offset_x, ply_offset_z) in the fabric's plane (aligned where
       * both are 0), ply 0 on top (its mid-plane y = 0), struck first. */
      unsigned int n_plies = 1;
      /** Distance along y between the mid-planes of consecutive plies
       * [m]: ply p's mid-plane is at y = -p ply_spacing. Used with
       * n_plies > 1, where it must exceed a ply's meshed thickness
       * (WovenPatch::ply_thickness), so that the plies do not touch at
       * rest. */
      double ply_spacing = 0.5e-3;
      /** The shift along x and along z [m] of each ply from the ply above
       * it: ply p is ply 0 moved by p ply_offset_x along x and
       * p ply_offset_z along z (a stack laid up with the plies' crossings
       * not over each other). 0 with a symmetry plane. */
      double ply_offset_x = 0., ply_offset_z = 0.;
      /** The symmetry plane x = 0 (`Symmetry = half` and `quarter`): only
       * the half x <= 0 is meshed, the warp yarns cut at mid-length, the
       * middle weft yarn, on the plane, cut lengthwise (its half section
       * on x <= 0), the weft yarns at x > 0 left out. The plain weave is
       * its own mirror image about the centreline of a weft yarn, not
       * about a plane between two (which swaps over and under): n_weft
       * must be odd, and cells_per_spacing even, so that x = 0 is a
       * layer of nodes. */
      bool mirror_x = false;
      /** The symmetry plane z = 0 (`Symmetry = quarter`): only z >= 0 is
       * meshed, the weft yarns cut at mid-length, the middle warp yarn
       * cut lengthwise, the warp yarns at z < 0 left out; n_warp odd,
       * cells_per_spacing even. */
      bool mirror_z = false;
    };

    /** The boundary id of the end sections of a yarn whose ends are free
     * (WovenPatchGeometry::clamp_warp_ends, clamp_weft_ends): neither
     * BoundaryIds::lateral nor BoundaryIds::end, so that the FE model
     * clamps none of its nodes and the projectile's contact, on the
     * lateral faces, leaves it out; the yarn contact acts on it
     * (yarn_contact_boundary_ids()). */
    constexpr unsigned int free_end_boundary_id = 3;

    /** The boundary id of the faces on a symmetry plane
     * (WovenPatchGeometry::mirror_x, mirror_z): the cut ends of the yarns
     * cut at mid-length and the cut faces of those cut lengthwise. Not
     * lateral, so that neither contact acts on them, and not clamped:
     * the FE model fixes the normal displacement of every node on the
     * plane by its position (doc/fabric.md section 10). */
    constexpr unsigned int symmetry_plane_boundary_id = 4;

    /** The boundary id of the end sections of a clamped yarn held by a
     * grip of finite force (ClampGrip; `Fabric/Clamp grip/Pull-out
     * force` > 0), set on the faces of BoundaryIds::end by the fabric
     * model: not BoundaryIds::end, so that the FE model clamps none of its
     * nodes, which the grip's springs hold instead. */
    constexpr unsigned int gripped_end_boundary_id = 5;

    /**
     * The boundary ids of a fabric's mesh (a WovenPatch's or a read
     * mesh's, doc/fabric.md sections 2 and 8) whose faces the yarn contact
     * acts on: the lateral faces (BoundaryIds::lateral) and the end
     * sections that move, free (free_end_boundary_id) or in a grip that
     * can slip (gripped_end_boundary_id), so that a moving end that meets
     * another yarn touches it and the end of another yarn cannot pass
     * through it. Not the rigidly clamped ends, which do not move, nor
     * the faces on a symmetry plane, which are inside the whole patch.
     */
    inline std::set<unsigned int>
    yarn_contact_boundary_ids()
    {
      return {BoundaryIds::lateral,
              free_end_boundary_id,
              gripped_end_boundary_id};
    }

    /**
     * A plain-woven patch (doc/fe-model.md section 8.3): n_warp warp yarns
     * along x at z_i = (i - (n_warp - 1)/2) s and n_weft weft yarns along
     * z at x_j = (j - (n_weft - 1)/2) s, s the spacing, each a
     * CrimpedYarn of wavelength 2 s spanning the patch, n s long, from
     * half a spacing before the first crossing yarn to half a spacing
     * after the last. Warp i's centreline is y = A cos(pi (x - x_0)/s +
     * i pi), weft j's y = -A cos(pi (z - z_0)/s + j pi): at every crossing
     * one yarn passes over (+A) and the other under (-A), alternately
     * along each yarn, the plain weave. With several plies
     * (WovenPatchGeometry::n_plies) the layer is repeated along -y, ply p
     * shifted by -p h (h the ply spacing), the plies aligned. Yarn ids:
     * warp i of ply p is p (n_warp + n_weft) + i, weft j of ply p is
     * p (n_warp + n_weft) + n_warp + j.
     *
     * The yarns must not touch at rest: the constructor refuses
     * A <= meshed_thickness_semi_axis() (crossing sections overlap),
     * 2 a_z >= s (neighbouring parallel yarns overlap) and, with several
     * plies, h <= ply_thickness() (neighbouring plies' meshes overlap), as
     * well as a folding crimp (CrimpedYarn).
     */
    class WovenPatch
    {
    public:
      /** @param geometry the patch; throws std::invalid_argument when the
       * yarns would touch or fold. */
      explicit WovenPatch(const WovenPatchGeometry &geometry);

      /**
       * The largest distance [m] of a vertex of the meshed section from
       * its centre along the thickness: the section of
       * create_yarn_section() with the semi-axes and refinements of
       * @p geometry, scaled to the ellipse's area, reaches beyond the
       * thickness semi-axis a_y by that scale (5.4 % with the 12-cell
       * section).
       */
      static double
      meshed_thickness_semi_axis(const WovenPatchGeometry &geometry);

      /** The thickness [m] of a ply of @p geometry as meshed, 2 (A +
       * meshed_thickness_semi_axis()): the tops of its crests' sections
       * (normal to the centreline, which is horizontal there) and the
       * bottoms of its troughs' bound its vertices, and so its Q1 cells. */
      static double
      ply_thickness(const WovenPatchGeometry &geometry)
      {
        return 2. * (geometry.amplitude + meshed_thickness_semi_axis(geometry));
      }

      /** The geometry [m, -]. */
      const WovenPatchGeometry &
      geometry() const
      {
        return g;
      }

      /** Number of yarns of a ply [-], warp then weft. */
      unsigned int
      yarns_per_ply() const
      {
        return g.n_warp + g.n_weft;
      }

      /** Number of yarns [-], ply after ply. */
      unsigned int
      n_yarns() const
      {
        return g.n_plies * yarns_per_ply();
      }

      /** The ply [-] of the yarn @p id, 0 on top. */
      unsigned int
      ply(const unsigned int id) const
      {
        return id / yarns_per_ply();
      }

      /** The height [m] of the mid-plane of ply @p p: -p times the ply
       * spacing (+0 for ply 0). */
      double
      ply_height(const unsigned int p) const
      {
        return p == 0 ? 0. : -(p * g.ply_spacing);
      }

      /** The shift [m] of ply @p p in the fabric's plane along x (@p d
       * = 0) or along z (@p d = 2): p ply_offset_x or p ply_offset_z
       * (exactly 0 for ply 0). */
      double
      ply_shift(const unsigned int p, const unsigned int d) const
      {
        return p == 0 ? 0. : p * (d == 0 ? g.ply_offset_x : g.ply_offset_z);
      }

      /** Whether the yarn @p id is a warp yarn (along x). */
      bool
      is_warp(const unsigned int id) const
      {
        return id % yarns_per_ply() < g.n_warp;
      }

      /** The number [-] of the yarn @p id among its ply's warp yarns (i)
       * or weft yarns (j). */
      unsigned int
      index_in_family(const unsigned int id) const
      {
        const unsigned int k = id % yarns_per_ply();
        return k < g.n_warp ? k : k - g.n_warp;
      }

      /** Whether yarn @p id is meshed: not left out by a symmetry plane
       * (WovenPatchGeometry::mirror_x, mirror_z). Every yarn keeps its
       * id and its CrimpedYarn, meshed or not. */
      bool
      meshed(const unsigned int id) const;

      /** The yarns [-] of the whole patch that yarn @p id stands for: 0
       * if it is not meshed, 2 if its mirror image in a symmetry plane
       * parallel to it is not meshed, 1 otherwise (no plane, or one that
       * cuts it at mid-length or lengthwise). */
      unsigned int
      copies(const unsigned int id) const;

      /** How many times [-] yarn @p id's centreline as meshed
       * (CrimpedYarn::centreline_length) goes into the whole patch's:
       * copies() times 2 where a symmetry plane cuts it at mid-length. */
      unsigned int
      length_copies(const unsigned int id) const;

      /** Yarn @p id in its own frame: its centreline along its local x
       * (the global x of a warp yarn, the global z of a weft yarn), its
       * ply's mid-plane at y = 0. */
      const CrimpedYarn &
      yarn(const unsigned int id) const
      {
        return yarns[id % yarns_per_ply()];
      }

      /** The position [m] of yarn @p id across its axis in the fabric's
       * plane: z_i of warp i, x_j of weft j, with its ply's shift. */
      double
      position(const unsigned int id) const
      {
        const double o     = offset[id % yarns_per_ply()];
        const double shift = ply_shift(ply(id), is_warp(id) ? 2 : 0);
        return shift == 0. ? o : o + shift;
      }

      /** The section [-] of yarn @p id through the reference point @p X
       * [m]: the station interval, 0 to yarn(id).geometry().n_cells - 1,
       * of the abscissa of its section (a layer of cells across the
       * yarn). */
      unsigned int
      section_of(const unsigned int id, const dealii::Point<3> &X) const;

      /** The point @p X [m] of the patch in the own frame of yarn @p id
       * [m], where that yarn is a CrimpedYarn centred on z = 0, its ply's
       * mid-plane at y = 0. */
      dealii::Point<3>
      to_yarn_frame(const unsigned int id, const dealii::Point<3> &X) const;

      /** The section coordinates (u, v) [m] of @p X in yarn @p id, along
       * its section's normal and its width, and the abscissa [m] of its
       * section along the yarn; @return (u/a_y)^2 + (v/a_z)^2 [-], below
       * 1 inside the yarn's elliptical tube (abscissa within its span). */
      double
      section_radius(const unsigned int id, const dealii::Point<3> &X) const;

      /** The yarn that holds @p X [m]: the one of smallest
       * section_radius() [-] among the yarns of the ply whose mid-plane
       * is nearest @p X (the plies do not touch). */
      unsigned int
      yarn_of(const dealii::Point<3> &X) const;

      /** The fibre direction [-] at @p X [m] (in the form of
       * FE::Parameters::fibre_direction): the tangent of yarn_of(X) at
       * its section, turned into the patch's frame. */
      dealii::Tensor<1, 3>
      fibre_direction(const dealii::Point<3> &X) const;

      /** The mesh: every yarn's CrimpedYarn::create_mesh, placed and
       * turned into its ply, merged into one triangulation with no
       * shared vertex; each cell's material id is its yarn's id, the
       * boundary ids those of BoundaryIds (lateral, end), the end sections
       * of a yarn with free ends free_end_boundary_id, the faces on a
       * symmetry plane symmetry_plane_boundary_id. Only the meshed()
       * yarns. */
      void
      create_mesh(dealii::Triangulation<3, 3> &mesh) const;

    private:
      WovenPatchGeometry g;
      /** The yarns of one ply, warp then weft. */
      std::vector<CrimpedYarn> yarns;
      /** The offset [m] of each yarn of a ply across its own axis in the
       * fabric's plane: z_i of warp i, x_j of weft j. */
      std::vector<double> offset;
    };
  } // namespace Fabric
} // namespace YarnImpact

#endif
