// The hybrid yarn's parameters (subsection Hybrid), its layout, the
// problems of its two parts, and the set-up checks (doc/hybrid.md sections
// 1 and 3.1).

#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/coupling/hybrid_model.h>
#include <yarn_impact/coupling/hybrid_parts.h>
#include <yarn_impact/dem/dem_model.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace YarnImpact
{
  namespace Coupling
  {
    using namespace dealii;
    using YarnImpact::Parameters::require;


    void
    HybridParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Hybrid");
      prm.declare_entry(
        "DEM half-length",
        "3e-3",
        Patterns::Double(),
        "Model = hybrid: the DEM fibres model |x| <= a, this half-length, "
        "rounded to whole FE cells from the clamp; it must hold the "
        "projectile's contact zone and every fibre break (the run stops, "
        "naming this parameter, when the FE part's fibre strain comes within "
        "10 % of Yarn/Failure strain) [m].");
      prm.declare_entry(
        "Overlap width",
        "1e-3",
        Patterns::Double(),
        "Model = hybrid: width w of the overlap a - w <= |x| <= a where both "
        "models exist and their weights go from the DEM's to the FE's, "
        "rounded to whole FE cells (at least one) [m].");
      prm.declare_entry(
        "Clamp DEM length",
        "0",
        Patterns::Double(),
        "Model = hybrid: length b of a second DEM part at the clamp, "
        "L/2 - b <= x <= L/2, tied to the FE part by a second overlap of "
        "Overlap width, so that the fibres are held one by one at the clamp "
        "as in the DEM and may break there (doc/hybrid.md section 5.4); "
        "rounded to whole FE cells, longer than the overlap; 0: none, the "
        "FE part reaches the clamp (the only value with Symmetry = none) "
        "[m].");
      prm.declare_entry(
        "Far field",
        "continuum",
        Patterns::Selection("continuum|fibre bars"),
        "Model = hybrid: what carries the yarn outside the DEM part. "
        "continuum: the identified FE continuum alone, every fibre tied to "
        "its one motion in the overlap. fibre bars: the continuum for the "
        "section's motion (compaction, distortion, deflection) and each "
        "fibre as its own chain of bars between the FE node layers for the "
        "axial motion, so that fibres slide along each other, carry their "
        "own bar waves to and from the clamp, and may break there "
        "(doc/hybrid.md section 3.4); with a Clamp DEM length the bars end "
        "in the clamp part's overlap, tied to its fibres; needs "
        "FE/Constitutive law = Charmetant.");
      prm.declare_entry(
        "Fibre bars per FE cell",
        "0",
        Patterns::Integer(0),
        "Model = hybrid, Far field = fibre bars: bars of each fibre per FE "
        "cell along the axis; 0: one per DEM truss, so that the fibres' bar "
        "waves keep the DEM's resolution and the overlap ties each sphere "
        "to one bar node (fewer bars are cheaper but reflect the short "
        "waves the DEM part sends, doc/hybrid.md section 3.4) [-].");
      prm.declare_entry(
        "FE cells along the axis",
        "0",
        Patterns::Integer(0),
        "Model = hybrid: cells along the axis of the hybrid's FE part, in "
        "place of FE/Cells along the axis, so that a run of several models "
        "(Model = fe, dem, hybrid) gives each FE its own mesh: the hybrid's "
        "overlap passes the DEM part's short waves with cells of a few "
        "trusses (doc/hybrid.md section 5.9), where the FE model alone is "
        "identified on its own cells; 0: FE/Cells along the axis [-].");
      prm.declare_entry(
        "Transverse tie",
        "field",
        Patterns::Selection("field|section mean|section affine"),
        "Model = hybrid, Far field = fibre bars: how the overlap ties the "
        "spheres' y and z motion to the continuum (doc/hybrid.md section "
        "2.5). field: every sphere moves with the continuum's field at its "
        "reference position. section mean: per FE node layer (its hat "
        "function along x) only the spheres' mass-weighted mean y and z "
        "velocity equals the continuum's at the spheres, so that fibres move "
        "relative to each other across the section. section affine: the "
        "mean and the moments linear in the section coordinates.");
      prm.leave_subsection();
    }


    void
    HybridParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Hybrid");
      dem_half_length =
        YarnImpact::Parameters::get_positive_double(prm,
                                                    "Hybrid",
                                                    "DEM half-length");
      overlap_width =
        YarnImpact::Parameters::get_positive_double(prm,
                                                    "Hybrid",
                                                    "Overlap width");
      clamp_dem_length = prm.get_double("Clamp DEM length");
      require(std::isfinite(clamp_dem_length) && clamp_dem_length >= 0.,
              "Hybrid/Clamp DEM length",
              "must be 0 (no DEM part at the clamp) or a positive length "
              "(got " +
                prm.get("Clamp DEM length") + ")");
      fibre_bars            = prm.get("Far field") == "fibre bars";
      bars_per_cell         = prm.get_integer("Fibre bars per FE cell");
      fe_axial_cells        = prm.get_integer("FE cells along the axis");
      const std::string tie = prm.get("Transverse tie");
      transverse_modes      = tie == "section mean"     ? 1
                              : tie == "section affine" ? 3
                                                        : 0;
      prm.leave_subsection();
    }


    HybridLayout
    hybrid_layout(const YarnImpact::Parameters::Shared &shared,
                  const FE::Parameters &fe,
                  const DEM::Parameters &dem,
                  const HybridParameters &hybrid)
    {
      const double half = 0.5 * shared.yarn.length;
      HybridLayout l;
      // The DEM's trusses as FibreChains lays them on the whole yarn: L/2
      // in K equal trusses.
      const unsigned int K =
        static_cast<unsigned int>(std::ceil(half / dem.sphere_spacing - 1e-9));
      l.station_spacing = half / K;
      // FE cells of about the FE model's own length, whole trusses each.
      const double nominal = shared.yarn.length / fe.n_axial_cells;
      l.cell_trusses =
        std::max<long>(1, std::lround(nominal / l.station_spacing));
      l.cell_length = l.cell_trusses * l.station_spacing;
      l.overlap_cells =
        std::max<long>(1, std::lround(hybrid.overlap_width / l.cell_length));
      const long fe_only =
        std::lround((half - hybrid.dem_half_length) / l.cell_length);
      require(fe_only >= 1,
              "Hybrid/DEM half-length",
              "must leave at least one FE cell of " +
                std::to_string(l.cell_length * 1e3) +
                " mm between the DEM part and the clamp");
      require(static_cast<long>(K) - fe_only * long(l.cell_trusses) >
                long(l.overlap_cells * l.cell_trusses),
              "Hybrid/Overlap width",
              "must be smaller than Hybrid/DEM half-length (after rounding "
              "both to whole FE cells)");
      l.fe_cells        = fe_only + l.overlap_cells;
      l.dem_trusses     = K - fe_only * l.cell_trusses;
      l.dem_half_length = l.dem_trusses * l.station_spacing;
      l.first_coupled_station =
        l.dem_trusses - l.overlap_cells * l.cell_trusses;
      l.overlap_begin = l.first_coupled_station * l.station_spacing;
      l.fe_end        = half;
      l.whole =
        shared.general.symmetry == YarnImpact::Parameters::Symmetry::none;
      l.fibre_bars = hybrid.fibre_bars;
      l.bars_per_cell =
        hybrid.bars_per_cell > 0 ? hybrid.bars_per_cell : l.cell_trusses;
      if (hybrid.clamp_dem_length > 0.)
        {
          const long clamp =
            std::lround(hybrid.clamp_dem_length / l.cell_length);
          require(clamp > long(l.overlap_cells),
                  "Hybrid/Clamp DEM length",
                  "must be longer than Hybrid/Overlap width (after rounding "
                  "both to whole FE cells of " +
                    std::to_string(l.cell_length * 1e3) + " mm)");
          require(fe_only - clamp >= 1,
                  "Hybrid/Clamp DEM length",
                  "must leave at least one FE-only cell of " +
                    std::to_string(l.cell_length * 1e3) +
                    " mm between the two overlaps (lower it or Hybrid/DEM "
                    "half-length)");
          l.clamp_cells   = clamp;
          l.clamp_trusses = clamp * l.cell_trusses;
          l.clamp_begin   = (K - l.clamp_trusses) * l.station_spacing;
          l.fe_cells      = fe_only - clamp + 2 * l.overlap_cells;
          l.fe_end = (K - l.clamp_trusses + l.overlap_cells * l.cell_trusses) *
                     l.station_spacing;
        }
      return l;
    }


    HybridParts
    hybrid_parts(const YarnImpact::Parameters::Shared &shared,
                 const FE::Parameters &fe,
                 const DEM::Parameters &dem,
                 const HybridLayout &l)
    {
      HybridParts p;
      // The DEM part: the yarn |x| <= a.
      p.dem_shared             = shared;
      p.dem_shared.yarn.length = 2. * l.dem_half_length;
      p.dem                    = dem;
      p.dem.sphere_spacing     = l.station_spacing;
      p.dem.truss_weight.assign(l.dem_trusses, 1.);
      for (unsigned int s = l.first_coupled_station; s < l.dem_trusses; ++s)
        p.dem.truss_weight[s] =
          l.particle_weight((s - l.first_coupled_station) / l.cell_trusses);
      // The whole yarn's DEM part spans |x| <= a, its trusses counted from
      // x = -a: those on x < 0 weighted as the mirror images of those on
      // x > 0.
      if (l.whole)
        {
          const std::vector<double> positive = p.dem.truss_weight;
          p.dem.truss_weight.assign(2 * l.dem_trusses, 1.);
          for (unsigned int t = 0; t < l.dem_trusses; ++t)
            {
              p.dem.truss_weight[l.dem_trusses - 1 - t] = positive[t];
              p.dem.truss_weight[l.dem_trusses + t]     = positive[t];
            }
        }
      // A station's weight is the mean of its two trusses' (an end's outer
      // side is the FE's alone; the first station of a half yarn is on the
      // symmetry plane, its weight 1).
      const unsigned int n_trusses = p.dem.truss_weight.size();
      p.dem.station_weight.assign(n_trusses + 1, 1.);
      for (unsigned int s = 1; s <= n_trusses; ++s)
        p.dem.station_weight[s] =
          0.5 * (p.dem.truss_weight[s - 1] +
                 (s < n_trusses ? p.dem.truss_weight[s] : 0.));
      if (l.whole)
        p.dem.station_weight[0] = 0.5 * p.dem.truss_weight[0];

      // The FE part: x in [a - w, L/2], the DEM's yarn, no failure.
      p.fe_shared              = shared;
      p.fe_shared.yarn.failure = false;
      p.fe                     = fe;
      // Its cells among the broken ends of a cut yarn are crushed as a
      // failing FE yarn's are, and eroded as they are.
      p.fe.erode_crushed_cells = shared.yarn.failure;
      // The same yarn on both sides (doc/hybrid.md section 3.2).
      p.fe.density_from_fibres       = true;
      p.fe.axial_modulus_from_fibres = true;
      p.fe.part_begin                = l.overlap_begin;
      p.fe.layer_weight.assign(l.fe_cells, 1.);
      for (unsigned int k = 0; k < l.overlap_cells; ++k)
        p.fe.layer_weight[k] = 1. - l.particle_weight(k);
      // Under fibre bars the bars carry the fibres' axial stiffness: the
      // continuum keeps the section's terms only.
      if (l.fibre_bars)
        {
          p.fe.axial_modulus_from_fibres  = false;
          p.fe.charmetant.k_e             = 0.;
          p.fe.charmetant.resist_dilation = false;
          // The projectile touches the fibres' bar nodes, not the
          // continuum's surface: a push along x on the surface would go
          // through P^T to whatever bars lie under it, broken ones too.
          p.fe.projectile_contact = false;
        }

      // The DEM part at the clamp: the whole yarn's stations from x_c to
      // L/2, weighted in its overlap [x_c, x_c + w] as the mirror image of
      // the other.
      if (l.clamp_cells > 0)
        {
          p.fe.part_end        = l.fe_end;
          const unsigned int n = l.fe_cells - l.overlap_cells;
          for (unsigned int k = 0; k < l.overlap_cells; ++k)
            p.fe.layer_weight[n + k] = 1. - l.clamp_particle_weight(k);
          p.dem_clamp                  = dem;
          p.dem_clamp.sphere_spacing   = l.station_spacing;
          p.dem_clamp.clamp_part_begin = l.clamp_begin;
          p.dem_clamp.truss_weight.assign(l.clamp_trusses, 1.);
          for (unsigned int s = 0; s < l.overlap_cells * l.cell_trusses; ++s)
            p.dem_clamp.truss_weight[s] =
              l.clamp_particle_weight(s / l.cell_trusses);
          // The free end's outer side is the FE's alone.
          p.dem_clamp.station_weight.assign(l.clamp_trusses + 1, 1.);
          for (unsigned int s = 0; s < l.clamp_trusses; ++s)
            p.dem_clamp.station_weight[s] =
              0.5 * ((s > 0 ? p.dem_clamp.truss_weight[s - 1] : 0.) +
                     p.dem_clamp.truss_weight[s]);
        }
      return p;
    }


    void
    validate(const YarnImpact::Parameters::Shared &shared,
             const FE::Parameters &fe,
             const DEM::Parameters &dem,
             const HybridParameters &hybrid)
    {
      require(shared.general.symmetry !=
                  YarnImpact::Parameters::Symmetry::none ||
                hybrid.clamp_dem_length == 0.,
              "Hybrid/Clamp DEM length",
              "must be 0 with Symmetry = none (the whole yarn's hybrid has no "
              "DEM parts at the clamps)");
      require(fe.global_refinements == 0,
              "FE/Global refinements",
              "must be 0 for Model = hybrid (the overlap's weights are per "
              "cell layer; refine with FE/Cells along the axis)");
      const HybridLayout l = hybrid_layout(shared, fe, dem, hybrid);
      // With the continuum far field the spheres' x is the continuum's
      // too, sphere by sphere; the coarse tie is built on the bars' own
      // axial tie.
      require(hybrid.transverse_modes == 0 || l.fibre_bars,
              "Hybrid/Transverse tie",
              "must be field unless Hybrid/Far field = fibre bars (the "
              "section's coarse tie leaves each fibre's axial motion to its "
              "bars)");
      // The section's coarse tie is built for the overlap by the nose; the
      // clamp part's overlap ties each sphere (field).
      require(hybrid.transverse_modes == 0 || l.clamp_cells == 0,
              "Hybrid/Transverse tie",
              "must be field with a Hybrid/Clamp DEM length (the clamp "
              "part's overlap ties each sphere to the continuum)");
      if (l.fibre_bars)
        {
          require(fe.law == FE::LawType::charmetant,
                  "FE/Constitutive law",
                  "must be Charmetant with Hybrid/Far field = fibre bars (the "
                  "bars replace its fibre term 1/2 k_e I_e^2, which the "
                  "linear transversely isotropic law does not separate)");
        }
      std::ostringstream zone;
      zone << "leaves the DEM-only zone |x| < " << l.overlap_begin * 1e3
           << " mm (after rounding to whole FE cells) no wider than the "
              "projectile's contact zone, its radius "
           << 0.5 * shared.projectile.diameter * 1e3
           << " mm: raise it or narrow Hybrid/Overlap width";
      require(l.overlap_begin >
                0.5 * shared.projectile.diameter + shared.yarn.fibre_diameter,
              "Hybrid/DEM half-length",
              zone.str());
      const HybridParts parts = hybrid_parts(shared, fe, dem, l);
      FE::validate(parts.fe_shared, parts.fe);
      DEM::validate(parts.dem_shared, parts.dem);
      if (l.clamp_cells > 0)
        DEM::validate(shared, parts.dem_clamp);
      // The overlap's section quadrature must exist (positive weights).
      if (!l.fibre_bars)
        section_quadrature(shared, fe, dem);
    }


    MemoryEstimate
    memory_estimate(const YarnImpact::Parameters::Shared &shared,
                    const FE::Parameters &fe,
                    const DEM::Parameters &dem,
                    const HybridParameters &hybrid)
    {
      const HybridLayout l    = hybrid_layout(shared, fe, dem, hybrid);
      const HybridParts parts = hybrid_parts(shared, fe, dem, l);
      MemoryEstimate e = DEM::memory_estimate(parts.dem_shared, parts.dem);
      // The whole yarn's second FE part and bars (x < 0) are copies of
      // the first's.
      const double sides = l.whole ? 2. : 1.;
      e.bytes += sides * FE::memory_estimate(parts.fe_shared, parts.fe).bytes;
      if (l.clamp_cells > 0)
        {
          const MemoryEstimate c =
            DEM::memory_estimate(shared, parts.dem_clamp);
          e.bytes += c.bytes;
          e.n_elements += c.n_elements;
        }
      // The fibre bars: every rank holds every fibre's arrays (six
      // doubles and a flag per bar node, FibreBars::memory_consumption).
      if (l.fibre_bars)
        e.bytes += sides * 49. * shared.yarn.n_fibres *
                   (l.fe_cells * l.bars_per_cell + 1);
      e.parameter = "Hybrid/DEM half-length";
      return e;
    }
  } // namespace Coupling
} // namespace YarnImpact
