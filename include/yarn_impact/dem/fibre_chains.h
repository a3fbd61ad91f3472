#ifndef yarn_impact_dem_fibre_chains_h
#define yarn_impact_dem_fibre_chains_h

#include <yarn_impact/core/parameters.h>
#include <yarn_impact/dem/parameters.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      /**
       * The fibres of the DEM impact model as chains of spheres joined by
       * trusses: the modelled part of the yarn (the symmetry planes cut it),
       * the fibre centres, the cross-sections (stations) along x and the
       * masses and weights of every sphere. Fixed once built.
       *
       * A sphere on a symmetry plane is half in the model: its weight is
       * 1/2 in the mass, the energies and the contacts with other spheres
       * on that plane, and its velocity normal to the plane is held at 0
       * (the masks below).
       */
      struct FibreChains
      {
        /**
         * Lay out the yarn of @p shared with the fibre layout of @p prm
         * (checked as by DEM::validate()).
         * @throw InputError naming the parameter or the file
         */
        FibreChains(const YarnImpact::Parameters::Shared &shared,
                    const Parameters &prm);

        /** Half (x = 0) or quarter (x = 0 and z = 0) symmetry. */
        bool x_sym, z_sym;
        /** Whole yarn over modelled part (1, 2 or 4) [-]. */
        double factor;

        /** Modelled fibres and fibres of the whole yarn. */
        unsigned int nf = 0, nf_whole = 0;
        /** Modelled stations (cross-sections) and those of the whole yarn.
         */
        unsigned int n_st = 0, n_whole_stations = 0;
        /** Station at x = 0. */
        unsigned int s_impact = 0;
        /** Stations of the profile folded about x = 0. */
        unsigned int n_prof = 0;
        /** Fibre diameter and sphere radius [m]. */
        double d = 0., radius = 0.;
        /** Rest length of a truss [m]. */
        double L0 = 0.;
        /** Mass of a whole sphere [kg]. */
        double sphere_mass = 0.;
        /** Axial stiffness EA/L0 of a truss [N/m]. */
        double truss_k = 0.;
        /** Cross-section of a fibre [m^2]. */
        double fibre_area = 0.;
        /** Factor by which the packing ellipse was enlarged [-]. */
        double packing_scale = 1.;
        /** Mass of the modelled spheres times the symmetry factor [kg]. */
        double total_mass = 0.;

        /** Per fibre: the initial y and z of its centre [m]. */
        std::vector<double> fibre_y0, fibre_z0;
        /** Per fibre: the share of its spheres that the model holds, 1/2
         * for a fibre cut by the symmetry plane z = 0, else 1 [-] (mass,
         * truss stiffness, contacts, energies). */
        std::vector<double> fibre_symmetry_weight;
        /** Per fibre: the inverse mass of its sphere at a whole station,
         * 1 / (sphere_mass fibre_symmetry_weight) [1/kg]; a sphere's inverse
         * mass is this times station_inverse_mass_factor of its station. */
        std::vector<double> fibre_inverse_mass;
        /** Per fibre: the z-velocity mask (0 on z = 0) [-]. */
        std::vector<double> zmask;
        /** Per station: its initial x [m]. */
        std::vector<double> station_x0;
        /** Per station: the share of its spheres that the model holds, 1/2
         * on the symmetry plane x = 0, else 1 [-]. */
        std::vector<double> station_symmetry_weight;
        /** Per station: the factor of fibre_inverse_mass that gives its
         * spheres' inverse mass [-]: 0 when clamped, 2 on x = 0 (half a
         * sphere), 1 / the coupling's particle weight when coupled, else 1.
         */
        std::vector<double> station_inverse_mass_factor;
        /** Per station: the x-velocity mask (0 on x = 0) [-]. */
        std::vector<double> xmask;
        /** Per station: the coupling's particle weight (mass, contacts,
         * energies) [-]; per truss from station s to s + 1: its weight
         * (stiffness, energy) [-]. All 1 without a coupling
         * (Parameters::station_weight). */
        std::vector<double> cw, tw;
        /** Whether the weights come from a coupling (then the last station
         * is free: its motion is the coupling's). */
        bool coupled = false;
        /** Whether this is the clamp part of a hybrid yarn
         * (Parameters::clamp_part_begin): then the first station is the
         * free, coupled one and the last the clamp. */
        bool clamp_part = false;
      };


      /**
       * Axial strain [-] of the truss from sphere @p i to the same fibre's
       * sphere @p i + @p nf at the positions @p pos [m], with rest length
       * @p L0 [m]; its length [m] in @p length if given.
       */
      inline double
      truss_strain(const double *pos,
                   const std::size_t i,
                   const unsigned int nf,
                   const double L0,
                   double *length = nullptr)
      {
        const std::size_t j = i + nf;
        const double e[3]   = {pos[3 * j] - pos[3 * i],
                               pos[3 * j + 1] - pos[3 * i + 1],
                               pos[3 * j + 2] - pos[3 * i + 2]};
        const double l = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
        if (length)
          *length = l;
        return l / L0 - 1.;
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact

#endif
