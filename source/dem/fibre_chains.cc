// The fibres of the DEM impact model as chains of spheres: layout, stations
// and masses.

#include <yarn_impact/dem/fibre_chains.h>

#include <deal.II/base/numbers.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      FibreChains::FibreChains(const YarnImpact::Parameters::Shared &shared,
                               const Parameters &prm)
        : x_sym(shared.general.symmetry !=
                  YarnImpact::Parameters::Symmetry::none &&
                prm.clamp_part_begin < 0.)
        , z_sym(shared.general.symmetry ==
                YarnImpact::Parameters::Symmetry::quarter)
        , factor(
            YarnImpact::Parameters::symmetry_factor(shared.general.symmetry))
      {
        const auto &y = shared.yarn;
        d             = y.fibre_diameter;
        radius        = 0.5 * d;
        // Fibre centres, checked as by validate() (also run at parsing).
        const FibreCentres centres = fibre_centres(shared, prm, z_sym);
        packing_scale              = centres.scale;
        nf_whole                   = centres.size();
        for (unsigned int a = 0; a < nf_whole; ++a)
          if (!z_sym || centres.z[a] >= 0.)
            {
              const bool on_plane = z_sym && centres.z[a] == 0.;
              // Touching neighbours get a gap of 1e-9 d, so that they do not
              // start as contacts with round-off overlaps.
              fibre_y0.push_back(centres.y[a] * (1. + 1e-9));
              fibre_z0.push_back(centres.z[a] * (1. + 1e-9));
              fibre_symmetry_weight.push_back(on_plane ? 0.5 : 1.);
              zmask.push_back(on_plane ? 0. : 1.);
            }
        nf = fibre_y0.size();

        // Stations: an even number of equal trusses over the length, so
        // that a cross-section lies on the plane x = 0.
        const unsigned int n_seg =
          2 * static_cast<unsigned int>(
                std::ceil(y.length / (2. * prm.sphere_spacing) - 1e-9));
        L0               = y.length / n_seg;
        n_whole_stations = n_seg + 1;
        n_prof           = n_seg / 2 + 1;
        n_st             = x_sym ? n_seg / 2 + 1 : n_seg + 1;
        s_impact         = x_sym ? 0 : n_seg / 2;
        coupled          = !prm.station_weight.empty();
        clamp_part       = prm.clamp_part_begin >= 0.;
        // The clamp part: the whole yarn's stations from clamp_part_begin
        // to L/2, its profile unfolded (station s is profile entry s).
        double x_begin = x_sym ? 0. : -0.5 * y.length;
        if (clamp_part)
          {
            const double trusses = (0.5 * y.length - prm.clamp_part_begin) / L0;
            if (!coupled || !(trusses >= 1.) ||
                std::abs(trusses - std::round(trusses)) > 1e-6)
              throw std::logic_error(
                "DEM: a clamp part must be coupled and span whole trusses");
            n_st     = static_cast<unsigned int>(std::lround(trusses)) + 1;
            n_prof   = n_st;
            s_impact = 0;
            // Both clamp parts of the whole yarn (half symmetry).
            n_whole_stations = 2 * n_st;
            x_begin          = 0.5 * y.length - (n_st - 1) * L0;
          }
        if (coupled && (prm.station_weight.size() != n_st ||
                        prm.truss_weight.size() != n_st - 1))
          throw std::logic_error("DEM: coupling weights for " +
                                 std::to_string(prm.station_weight.size()) +
                                 " stations, the model has " +
                                 std::to_string(n_st));
        for (unsigned int s = 0; s < n_st; ++s)
          {
            const double x   = x_begin + s * L0;
            const bool plane = x_sym && s == 0;
            // A coupled part's ends are tied to the continuum, not
            // clamped: the last station's, and with no symmetry plane the
            // first's too (the whole yarn's DEM part, doc/hybrid.md
            // section 3.1).
            const bool clamped =
              clamp_part ? s == n_st - 1
                         : !coupled && (s == n_st - 1 || (!x_sym && s == 0));
            const double weight = coupled ? prm.station_weight[s] : 1.;
            station_x0.push_back(x);
            station_symmetry_weight.push_back(plane ? 0.5 : 1.);
            station_inverse_mass_factor.push_back(
              clamped ? 0. : (plane ? 2. : 1.) / weight);
            xmask.push_back(plane ? 0. : 1.);
            cw.push_back(weight);
            if (s + 1 < n_st)
              tw.push_back(coupled ? prm.truss_weight[s] : 1.);
          }

        fibre_area  = dealii::numbers::PI * d * d / 4.;
        sphere_mass = y.fibre_density * fibre_area * L0;
        truss_k     = y.fibre_modulus * fibre_area / L0;
        for (unsigned int f = 0; f < nf; ++f)
          fibre_inverse_mass.push_back(
            1. / (sphere_mass * fibre_symmetry_weight[f]));

        total_mass = 0.;
        for (unsigned int f = 0; f < nf; ++f)
          for (unsigned int s = 0; s < n_st; ++s)
            total_mass += sphere_mass * fibre_symmetry_weight[f] *
                          station_symmetry_weight[s] * cw[s];
        total_mass *= factor;
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
