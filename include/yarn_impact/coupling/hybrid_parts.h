#ifndef yarn_impact_coupling_hybrid_parts_h
#define yarn_impact_coupling_hybrid_parts_h

#include <yarn_impact/core/impact_model.h>
#include <yarn_impact/core/parameters.h>
#include <yarn_impact/coupling/hybrid_model.h>
#include <yarn_impact/dem/parameters.h>
#include <yarn_impact/fe/parameters.h>

#include <mpi.h>

#include <array>
#include <functional>
#include <utility>
#include <vector>

namespace dealii
{
  template <int dim, int spacedim>
  class Triangulation;
  template <int dim, typename Number>
  class Point;
} // namespace dealii

namespace YarnImpact
{
  namespace Coupling
  {
    /**
     * The two parts of a hybrid yarn as problems of their own models
     * (doc/hybrid.md section 3.1): the DEM part, the yarn |x| <= a with the
     * particle weights of the overlap per station and per truss and a free
     * end; with Hybrid/Clamp DEM length, the DEM part at the clamp,
     * x in [x_c, L/2], weighted the same way in its overlap [x_c, x_c + w];
     * the FE part, x in [a - w, L/2] (or [a - w, x_c + w]), with the
     * continuum weights per
     * cell layer, the density and axial modulus from the fibres, and no
     * failure (the DEM part holds the breaks). With `Symmetry = none` the
     * DEM part is |x| <= a, weighted on x < 0 as the mirror image of
     * x > 0, whose FE part the model builds a second time, mirrored, for
     * x < 0 (HybridLayout::whole). The FE part's section
     * quadrature (section_quadrature()) is set by the model only: it is
     * the one field that costs a search over the fibres.
     */
    struct HybridParts
    {
      YarnImpact::Parameters::Shared dem_shared, fe_shared;
      /** The DEM part at the impact point, and the one at the clamp
       * (meaningful when HybridLayout::clamp_cells > 0; its problem is the
       * whole yarn's, @p shared). */
      DEM::Parameters dem, dem_clamp;
      FE::Parameters fe;
    };

    /** The parts of the hybrid yarn of @p shared laid out by @p layout. */
    HybridParts
    hybrid_parts(const YarnImpact::Parameters::Shared &shared,
                 const FE::Parameters &fe,
                 const DEM::Parameters &dem,
                 const HybridLayout &layout);

    /**
     * Where a point (y, z) [m] of the section lies: the 2D section cell
     * whose (clamped) unit coordinates are nearest, its active index in
     * @p cell_index, its four vertices' indices and their bilinear shape
     * values there [-]. A fibre centre outside the polygonal section (the
     * packing ellipse can be a little larger) is tied to the nearest point
     * of the nearest cell.
     */
    void
    locate_in_section(const dealii::Triangulation<2, 2> &section,
                      const dealii::Point<2, double> &p,
                      unsigned int &cell_index,
                      std::array<unsigned int, 4> &vertices,
                      std::array<double, 4> &values);

    /**
     * The vertex of @p section at the point (y, z) = @p p [m] of an FE
     * node of a part extruded from it; throws naming the cause if no
     * vertex lies within 1e-6 of the section's smaller semi-axis
     * @p semi_axis [m].
     */
    unsigned int
    section_vertex(const dealii::Triangulation<2, 2> &section,
                   const dealii::Point<2, double> &p,
                   const double semi_axis);

    /** An FE node of a part: (layer n_vertices + section vertex, its local
     * x, y and z dofs). */
    using LayerNode = std::pair<unsigned int, std::array<unsigned int, 3>>;

    /**
     * The owned FE nodes of @p fe_model (extruded from @p section) on the
     * @p n_layers node layers x_begin + k h [m], by layer and section
     * vertex; nodes off that range are left out. Throws unless every
     * (layer, vertex) is owned by exactly one rank (collective).
     * @p semi_axis: the section's smaller semi-axis [m].
     */
    std::vector<LayerNode>
    layer_nodes(ImpactModel &fe_model,
                const dealii::Triangulation<2, 2> &section,
                const double x_begin,
                const double h,
                const unsigned int n_layers,
                const double semi_axis,
                const MPI_Comm communicator);

    /**
     * The FE part's section quadrature (doc/hybrid.md section 3.3): in each
     * section cell, the four Gauss weights w'_q that give each of its
     * vertices v the fibres' share of the axial stiffness,
     * sum_q w'_q psi_v(q) = A / n_f sum_{fibres in the cell} psi_v(f), with
     * A the ellipse's area (the FE modulus is E_f n_f A_f / A). Returned as
     * the factor w'_q / (JxW)_q [-] of the Gauss point at a reference
     * position (x, y, z) [m]; throws InputError naming FE/Section
     * refinements if a weight is not positive (too few fibres in a cell).
     */
    std::function<double(const double *)>
    section_quadrature(const YarnImpact::Parameters::Shared &shared,
                       const FE::Parameters &fe,
                       const DEM::Parameters &dem);
  } // namespace Coupling
} // namespace YarnImpact

#endif
