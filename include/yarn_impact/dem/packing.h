#ifndef yarn_impact_dem_packing_h
#define yarn_impact_dem_packing_h

#include <string>
#include <vector>

namespace YarnImpact
{
  namespace DEM
  {
    /** Fibre centres in the yarn's cross-section (y: thickness, z: width). */
    struct FibreCentres
    {
      /** Centre coordinates [m]. */
      std::vector<double> y, z;
      /** Factor by which the ellipse was enlarged so that all centres lie
       * inside it (1 when they fit in the yarn's ellipse) [-]. */
      double scale = 1.;

      /** Number of fibres. */
      unsigned int
      size() const
      {
        return y.size();
      }
    };

    /**
     * Exactly @p n centres of a hexagonal lattice of spacing @p d (rows along
     * z, centred on the origin, so the set is symmetric about y = 0 and z = 0
     * whenever the count allows it) inside the ellipse
     * \f$(y/a_y)^2 + (z/a_z)^2 \le s^2\f$, with the smallest scale
     * \f$s \ge 1\f$ that holds @p n of them. The centres closest to the
     * ellipse's centre (in the ellipse norm) are taken; with
     * @p symmetric_z, a mirror pair \f$(y,\pm z)\f$ is never split (the
     * last slot goes to the next centre on z = 0), so the layout is
     * symmetric about z = 0 whenever possible (quarter symmetry).
     * @throw InputError if @p s would exceed @p max_scale
     */
    FibreCentres
    hexagonal_packing(const unsigned int n,
                      const double d,
                      const double a_y,
                      const double a_z,
                      const double max_scale,
                      const bool symmetric_z = false);

    /**
     * Read fibre centres, one `y z` pair per line [m]; blank lines and text
     * after '#' are ignored. Checks that there are exactly @p n centres and
     * that no two are closer than @p d, and that every centre lies inside
     * the yarn's ellipse (semi-axes @p a_y, @p a_z [m]) enlarged by
     * @p max_scale (DEM/Maximum packing scale): a centre far outside is a
     * units error or another yarn.
     * @throw InputError naming the file and the line on any problem
     */
    FibreCentres
    read_fibre_file(const std::string &file,
                    const unsigned int n,
                    const double d,
                    const double a_y,
                    const double a_z,
                    const double max_scale);

    /** Smallest distance between two centres (infinity for fewer than two),
     * for the checks [m]. */
    double
    min_distance(const FibreCentres &centres);
  } // namespace DEM
} // namespace YarnImpact

#endif
