// The FE model's set-up: the yarn data from the fibres, the checks of its
// parameters against the shared ones (also run by --check), and its memory
// estimate.

#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/fe/cell_kernel.h>
#include <yarn_impact/fe/failure_law.h>
#include <yarn_impact/fe/fe_model.h>

#include <cmath>
#include <sstream>
#include <string>

namespace YarnImpact
{
  namespace FE
  {
    Parameters
    with_fibre_data(const YarnImpact::Parameters::Shared &shared,
                    const Parameters &given)
    {
      Parameters parameters = given;
      if (given.density_from_fibres)
        parameters.density = shared.yarn.fibre_density *
                             shared.yarn.fibre_area() /
                             shared.yarn.section_area();
      // The DEM's axial stiffness, n_f E_f A_f, spread over the ellipse.
      if (given.axial_modulus_from_fibres)
        {
          const double modulus = shared.yarn.fibre_modulus *
                                 shared.yarn.fibre_area() /
                                 shared.yarn.section_area();
          parameters.charmetant.k_e = modulus;
          parameters.linear.E_L     = modulus;
        }
      return parameters;
    }


    namespace
    {
      /** The checks of `FE/Crimp` with a positive amplitude. */
      void
      validate_crimp(const YarnImpact::Parameters::Shared &shared,
                     const Parameters &parameters)
      {
        using YarnImpact::Parameters::require;
        const CrimpParameters &crimp = parameters.crimp;
        require(parameters.layer_weight.empty(),
                "FE/Crimp/Amplitude",
                "must be 0 for Model = hybrid (its FE part is a straight "
                "yarn)");
        require(parameters.global_refinements == 0,
                "FE/Global refinements",
                "must be 0 with a crimp (FE/Crimp/Amplitude > 0): it would "
                "put the new vertices on the straight edges between the "
                "swept sections, off the tube; refine with FE/Cells along "
                "the axis and FE/Section refinements");
        // The smallest radius of curvature of A cos(k x), at the crests,
        // 1 / (A k^2): a section reaching past it folds the tube.
        const double k      = 2. * M_PI / crimp.wavelength;
        const double radius = 1. / (crimp.amplitude * k * k);
        const double a_y    = shared.yarn.thickness_semi_axis;
        std::ostringstream fold;
        fold << "= " << crimp.amplitude * 1e3
             << " mm folds the yarn: the centreline's smallest radius of "
                "curvature, Wavelength^2 / (4 pi^2 Amplitude) = "
             << radius * 1e3
             << " mm, must exceed the yarn's thickness semi-axis "
                "(Yarn/Thickness semi-axis) "
             << a_y * 1e3 << " mm: lower it below " << 1. / (a_y * k * k) * 1e3
             << " mm or lengthen the wavelength";
        require(radius > a_y, "FE/Crimp/Amplitude", fold.str());
        // The sections are equally spaced in x; a wavelength over fewer
        // than 8 of them is a polygon, not a crimp.
        const double h = shared.yarn.length / parameters.n_axial_cells;
        std::ostringstream coarse;
        coarse << "= " << crimp.wavelength * 1e3 << " mm spans "
               << crimp.wavelength / h << " cells of " << h * 1e3
               << " mm (Yarn/Length / FE/Cells along the axis): at least 8 "
                  "are needed to resolve the crimp (raise FE/Cells along "
                  "the axis)";
        require(crimp.wavelength >= 8. * h * (1. - 1e-12),
                "FE/Crimp/Wavelength",
                coarse.str());
      }
    } // namespace


    void
    validate(const YarnImpact::Parameters::Shared &shared,
             const Parameters &given)
    {
      const Parameters parameters = with_fibre_data(shared, given);
      using YarnImpact::Parameters::require;
      require(parameters.n_axial_cells % 2 == 0,
              "FE/Cells along the axis",
              "must be even, so that a node layer lies under the projectile "
              "at x = 0 (the symmetry plane of half and quarter models)");
      require(shared.yarn.length / parameters.n_axial_cells <
                0.5 * shared.projectile.diameter,
              "FE/Cells along the axis",
              "is too small: cells longer than the projectile radius cannot "
              "resolve the contact");
      if (parameters.crimp.crimped())
        validate_crimp(shared, parameters);
      const FailureParameters &failure = parameters.failure;
      if (shared.yarn.failure &&
          failure.model == FailureParameters::Model::progressive)
        {
          require(parameters.law == LawType::charmetant,
                  "Yarn/Failure model",
                  "= progressive needs FE/Constitutive law = Charmetant: it "
                  "damages the fibre term 1/2 k_e I_e^2 of the energy, which "
                  "the linear transversely isotropic law does not separate "
                  "(set Yarn/Failure model = sudden with the linear law)");
          // Softening must not snap back in the longest cell: the final
          // strain I_u = 2 G_f / (h k_e I_0) must lie above the onset I_0,
          // i.e. G_f above the elastic energy per area h k_e I_0^2 / 2
          // (doc/theory.md section 5).
          const double h = shared.yarn.length / parameters.n_axial_cells /
                           std::pow(2., parameters.global_refinements);
          // The largest onset is at the back face (doc/theory.md 5.4).
          const FailureLaw law =
            make_failure_law(shared.yarn, failure, parameters.charmetant.k_e);
          const double I_0   = law.onset_log_stretch_at(1.);
          const double G_min = 0.5 * h * parameters.charmetant.k_e * I_0 * I_0;
          std::ostringstream s;
          s << "= " << failure.fracture_energy
            << " J/m^2 is not above the elastic energy per unit area of a "
            << h * 1e3
            << " mm cell at the largest damage onset strain (Damage onset "
               "strain x (1 + Damage onset spread)), "
            << G_min
            << " J/m^2: its softening would snap back (raise it or refine "
               "FE/Cells along the axis)";
          require(failure.fracture_energy > G_min,
                  "Yarn/Fracture energy",
                  s.str());
          if (failure.softening_tail_stress > 0.)
            {
              // The bilinear envelope must fall on both branches in the
              // longest cell at the largest onset, where both margins are
              // smallest: I_0 < I_k < I_u (doc/theory.md section 5.5).
              const double I_k = law.kink_log_stretch(h, I_0);
              const double I_u = law.final_log_stretch(h, I_0);
              std::ostringstream k;
              k << "leaves the first branch of the softening curve of a "
                << h * 1e3 << " mm cell at the largest onset ending at the "
                << "fibre log-stretch " << I_k << ", not above the onset "
                << I_0 << ": it would snap back (lower Softening tail energy, "
                << "or raise Fracture energy)";
              require(I_k > I_0, "Yarn/Softening tail energy", k.str());
              std::ostringstream u;
              u << "is too small for Softening tail stress = "
                << failure.softening_tail_stress << ": the tail of a "
                << h * 1e3 << " mm cell at the largest onset would end at "
                << "the fibre log-stretch " << I_u << ", not beyond its kink "
                << I_k << " (raise it, or lower Softening tail stress)";
              require(I_u > I_k, "Yarn/Softening tail energy", u.str());
            }
        }
      // The cell count is the memory estimate's, which also names the
      // parameter that makes it large.
      const MemoryEstimate size = memory_estimate(shared, parameters);
      require(size.n_elements <= 5e7,
              size.parameter,
              "gives more than 50 million cells");
    }


    MemoryEstimate
    memory_estimate(const YarnImpact::Parameters::Shared &,
                    const Parameters &parameters)
    {
      const double axial   = parameters.n_axial_cells / 100.;
      const double section = std::pow(4., parameters.section_refinements);
      const double global  = std::pow(8., parameters.global_refinements);
      MemoryEstimate e;
      e.n_elements = 12. * 100. * axial * section * global;
      // With fibre directions each cell also holds its Gauss points'
      // frames (CellData::frames).
      e.bytes =
        (6.5e3 + (parameters.fibre_direction || parameters.crimp.crimped()
                    ? sizeof(double) * frame_size
                    : 0.)) *
        e.n_elements;
      e.element_name = "cells";
      e.parameter =
        (axial >= section && axial >= global ? "FE/Cells along the axis"
         : section >= global                 ? "FE/Section refinements"
                                             : "FE/Global refinements");
      return e;
    }
  } // namespace FE
} // namespace YarnImpact
