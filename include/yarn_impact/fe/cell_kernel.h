#ifndef yarn_impact_fe_cell_kernel_h
#define yarn_impact_fe_cell_kernel_h

#include <yarn_impact/fe/simd.h>
#include <yarn_impact/mechanics/kinematics.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace YarnImpact
{
  namespace FE
  {
    /** Vertices of a Q1 hexahedron. */
    constexpr unsigned int n_nodes = 8;
    /** Gauss points of a cell (2x2x2). */
    constexpr unsigned int n_q = 8;
    /** Degrees of freedom of a cell: 3 per vertex, dof 3a + d is vertex a,
     * direction d. */
    constexpr unsigned int n_cell_dofs = 3 * n_nodes;
    /** Shape-gradient values stored per cell. */
    constexpr unsigned int grad_size = n_q * n_nodes * 3;
    /** Shape-gradient values of one block of internal::n_lanes Gauss
     * points. */
    constexpr unsigned int gradient_block_size =
      n_nodes * 3 * internal::n_lanes;

    /**
     * Where the gradient of the shape function of vertex @p a in direction
     * @p d at lane @p l of a block lies within the block. The blocks of
     * internal::n_lanes Gauss points are stored one after the other,
     * [block][vertex][direction][lane], so that the vectorised loop loads
     * the four Gauss points of a block as one Double4.
     */
    constexpr unsigned int
    lane_gradient_index(const unsigned int a,
                        const unsigned int d,
                        const unsigned int l)
    {
      return (3 * a + d) * internal::n_lanes + l;
    }

    /** Where the gradient of the shape function of vertex @p a in
     * direction @p d at Gauss point @p q lies among a cell's grad_size
     * values (see lane_gradient_index()). */
    constexpr unsigned int
    gradient_index(const unsigned int q,
                   const unsigned int a,
                   const unsigned int d)
    {
      return (q / internal::n_lanes) * gradient_block_size +
             lane_gradient_index(a, d, q % internal::n_lanes);
    }

    /** The shape gradients of Gauss point @p q of a cell, g[3a + d]
     * [1/m], from the cell's stored values @p grad. */
    inline void
    gather_gradients(const double *grad,
                     const unsigned int q,
                     double (&g)[n_nodes * 3])
    {
      for (unsigned int a = 0; a < n_nodes; ++a)
        for (unsigned int d = 0; d < 3; ++d)
          g[3 * a + d] = grad[gradient_index(q, a, d)];
    }

    /** F = I + sum_a u_a (x) grad N_a at one Gauss point, from the nodal
     * displacements u [m] and the shape gradients g [1/m] (both 3a + d). */
    inline void
    deformation_gradient(const double *u,
                         const double *g,
                         Mechanics::Matrix3 &F)
    {
      F[0] = F[4] = F[8] = 1.;
      F[1] = F[2] = F[3] = F[5] = F[6] = F[7] = 0.;
      for (unsigned int a = 0; a < n_nodes; ++a)
        {
          const double g0 = g[3 * a], g1 = g[3 * a + 1], g2 = g[3 * a + 2];
          for (unsigned int i = 0; i < 3; ++i)
            {
              const double ui = u[3 * a + i];
              F[3 * i] += ui * g0;
              F[3 * i + 1] += ui * g1;
              F[3 * i + 2] += ui * g2;
            }
        }
    }

    /** What has become of a cell (CellData::state). */
    enum CellState : unsigned char
    {
      /** Carries its stress (possibly with fibre damage). */
      active = 0,
      /** Broken by the sudden criterion: carries nothing from then on. */
      broken = 1,
      /** Removed because crushed below J = 0.2, inverted or with a
       * non-finite energy: erosion, a numerical removal, not a material
       * failure (counted apart, Observables::n_eroded). */
      eroded = 2
    };

    /**
     * The fibre-failure law of the force loop (doc/theory.md section 5).
     *
     * - sudden: the paper's criterion. A cell whose largest Gauss-point
     *   ln(lambda_f) passes onset_log_stretch breaks: it carries no
     *   force from then on and its strain energy is counted as dissipated.
     * - progressive: crack-band softening of the fibre term
     *   1/2 k_e I_e^2 of the energy. The history variable kappa is the
     *   largest ln(lambda_f) a cell's Gauss points have reached; above
     *   the onset I_0 the fibre Kirchhoff stress follows the linear
     *   envelope k_e I_0 (I_u - kappa)/(I_u - I_0) down to zero at
     *   I_u = 2 G_f / (h k_e I_0), h the cell's reference length along
     *   the fibre, so that a band one cell long dissipates G_f per unit
     *   area whatever h. With a tail (tail_stress_ratio beta > 0) the
     *   envelope is bilinear: from k_e I_0 down to beta k_e I_0 at the
     *   kink I_k, then down to zero at I_u, the tail dissipating G_t of
     *   G_f (doc/theory.md section 5.5). The damage d = 1 - envelope/(k_e
     * kappa) scales the fibre term only (the law's energy must separate it:
     *   Law::separable_fibre_term); the compaction and distortion terms
     *   stay, because the broken fibres still fill the section and are
     *   still pressed by the projectile (doc/fe-model.md section 4).
     *
     * Both erode cells crushed below J = 0.2, inverted or with a
     * non-finite energy (CellState::eroded).
     */
    struct FailureLaw
    {
      /** Which law, none for a yarn that does not fail (nor erode). */
      enum class Kind
      {
        none,
        sudden,
        progressive
      };
      Kind kind = Kind::none;
      /** I_0 = ln(1 + failure strain) [-]; for the progressive law, the
       * onset of the cells at the face that the projectile strikes. */
      double onset_log_stretch = 0.;
      /** Progressive law: relative growth s [-] of the onset strain across
       * the thickness, from expm1(onset_log_stretch) at the struck face to
       * (1 + s) times it at the opposite face (onset_log_stretch_at()). */
      double onset_spread = 0.;
      /** G_f, energy per unit crack area [J/m^2] (progressive). */
      double fracture_energy = 0.;
      /** beta [-]: the fibre stress at the kink of a bilinear envelope, as
       * a fraction of the onset stress k_e I_0 (progressive). 0: the linear
       * envelope. */
      double tail_stress_ratio = 0.;
      /** G_t [J/m^2]: the part of G_f that the tail of the bilinear
       * envelope dissipates, from the kink to complete failure
       * (progressive, with tail_stress_ratio > 0). */
      double tail_energy = 0.;
      /** k_e of the separable fibre term 1/2 k_e I_e^2 [Pa] (progressive).
       */
      double fibre_modulus = 0.;

      /** The onset I_0 [-] of a cell whose shallowest point lies at the
       * normalised depth @p depth [-] below the struck face (CellData::depth, 0
       * at the face the projectile strikes, 1 at the opposite one): the onset
       * strain grows linearly with the depth, eps_0 (1 + s depth). The
       * fibres nearest the nose are the most stretched of a section and
       * break first, those at the back last (doc/theory.md section 5.4);
       * a cell averages them, and the spread gives each cell the onset of
       * the fibres it holds. */
      double
      onset_log_stretch_at(const double depth) const
      {
        if (onset_spread == 0.)
          return onset_log_stretch;
        return std::log1p(std::expm1(onset_log_stretch) *
                          (1. + onset_spread * depth));
      }

      /** The ln(lambda_f) [-] at which the fibre stress of a cell @p h [m]
       * long along the fibre with onset @p I_0 [-] is gone: I_u = 2 G_f /
       * (h k_e I_0) for the linear envelope, 2 G_t / (h k_e beta I_0) with
       * a tail (the tail's area beta k_e I_0 I_u / 2 per unit volume is
       * G_t / h). */
      double
      final_log_stretch(const double h, const double I_0) const
      {
        if (tail_stress_ratio == 0.)
          return 2. * fracture_energy / (h * fibre_modulus * I_0);
        return 2. * tail_energy / (h * fibre_modulus * tail_stress_ratio * I_0);
      }

      /** The kink I_k [-] of the bilinear envelope of a cell @p h [m] long
       * with onset @p I_0 [-], where the fibre stress has fallen to
       * beta k_e I_0: the first branch dissipates G_f - G_t per unit area,
       * 1/2 k_e I_0 (I_k - beta I_0) h. Equal to final_log_stretch() for the
       * linear envelope. */
      double
      kink_log_stretch(const double h, const double I_0) const
      {
        if (tail_stress_ratio == 0.)
          return final_log_stretch(h, I_0);
        return tail_stress_ratio * I_0 +
               2. * (fracture_energy - tail_energy) / (h * fibre_modulus * I_0);
      }

      /** The envelope of the fibre Kirchhoff stress over k_e [-] at the
       * history variable @p kappa [-], for a cell @p h [m] long with onset
       * @p I_0 [-]: kappa up to the onset, then linear down to beta I_0 at
       * the kink and to zero at the final stretch. */
      double
      envelope(const double kappa, const double h, const double I_0) const
      {
        if (kappa <= I_0)
          return kappa;
        const double I_u = final_log_stretch(h, I_0);
        if (kappa >= I_u)
          return 0.;
        if (tail_stress_ratio == 0.)
          return I_0 * (I_u - kappa) / (I_u - I_0);
        const double I_k    = kink_log_stretch(h, I_0);
        const double tail_0 = tail_stress_ratio * I_0;
        if (kappa <= I_k)
          return I_0 - (I_0 - tail_0) * (kappa - I_0) / (I_k - I_0);
        return tail_0 * (I_u - kappa) / (I_u - I_k);
      }

      /** The damage [0, 1] of a cell @p h [m] long with onset @p I_0 [-]
       * at the history variable @p kappa (largest ln(lambda_f) reached)
       * [-]: 1 - envelope / kappa. */
      double
      damage(const double kappa, const double h, const double I_0) const
      {
        if (kappa <= I_0)
          return 0.;
        if (tail_stress_ratio != 0.)
          return 1. - envelope(kappa, h, I_0) / kappa;
        // The linear curve written out, as before the tail (the same bits).
        const double I_u = final_log_stretch(h, I_0);
        if (kappa >= I_u)
          return 1.;
        return 1. - I_0 * (I_u - kappa) / (kappa * (I_u - I_0));
      }
    };

    /**
     * The energy [J] that the progressive law dissipates in a cell whose
     * history variable grows from @p kappa_old to @p kappa_new [-], with
     * the undamaged fibre energy @p fibre_energy [J] at kappa_new, the
     * cell length @p h [m] along the fibre and the cell's onset @p I_0 [-].
     * Along the envelope the dissipation per unit volume is 1/2 k_e kappa^2 dd
     * = 1/2 k_e I_0 I_u / (I_u - I_0) dkappa, a constant rate (doc/theory.md
     * section 5.3; with a tail, one constant rate per branch, section 5.5),
     * so the increment is that rate times the part of [kappa_old,
     * kappa_new] inside [I_0, I_u], times the volume of the band. The volume is
     * fibre_energy / (1/2 k_e kappa_new^2): the whole cell when its strain is
     * uniform (then the crack dissipates G_f per unit area exactly, whatever
     * the step), less when its Gauss points are stretched less than the
     * largest, whose fibre energy the damage then removes in proportion, so
     * that the energy balance closes.
     */
    inline double
    dissipation_increment(const FailureLaw &law,
                          const double kappa_old,
                          const double kappa_new,
                          const double fibre_energy,
                          const double h,
                          const double I_0)
    {
      const double I_u = law.final_log_stretch(h, I_0);
      // The linear curve keeps its own expression: the general one below
      // gives the same number with other roundings.
      if (law.tail_stress_ratio == 0.)
        {
          const double lo = std::max(kappa_old, I_0);
          const double hi = std::min(kappa_new, I_u);
          if (hi <= lo)
            return 0.;
          return fibre_energy * I_0 * I_u * (hi - lo) /
                 ((I_u - I_0) * kappa_new * kappa_new);
        }
      // On a linear piece g = a + b kappa of the envelope the rate
      // 1/2 k_e (g - kappa g') = 1/2 k_e a is its intercept a: beta I_0
      // I_u / (I_u - I_k) on the tail, I_0 (I_k - beta I_0) / (I_k - I_0)
      // on the first branch.
      const double I_k    = law.kink_log_stretch(h, I_0);
      const double tail_0 = law.tail_stress_ratio * I_0;
      auto overlap        = [&](const double a, const double b) {
        return std::max(0., std::min(kappa_new, b) - std::max(kappa_old, a));
      };
      const double sum =
        I_0 * (I_k - tail_0) / (I_k - I_0) * overlap(I_0, I_k) +
        tail_0 * I_u / (I_u - I_k) * overlap(I_k, I_u);
      return fibre_energy * sum / (kappa_new * kappa_new);
    }

    /**
     * The owned cells as the internal-force loop sees them, cell c at
     * c * n_cell_dofs, c * grad_size, c * n_q in the flat arrays, and what
     * the loop keeps of each.
     */
    struct CellData
    {
      /** Local indices (in deal.II's distributed vectors) of the dofs. */
      std::vector<unsigned int> dofs;
      /** Shape gradients [1/m], laid out as gradient_index() says. */
      std::vector<double> grads;
      /** Gauss weights times Jacobians [m^3]. */
      std::vector<double> JxW;
      /** A CellState: not active once the cell has broken (sudden) or
       * been eroded; it then carries no force. */
      std::vector<unsigned char> failed;
      /** Fibre damage d in [0, 1] (progressive failure): the fibre term of
       * the energy is multiplied by 1 - d. Irreversible. */
      std::vector<double> damage;
      /** History variable of the damage: the largest ln(lambda_f) any
       * Gauss point of the cell has reached [-]. */
      std::vector<double> kappa;
      /** Reference length of the cell along the fibre [m] (the crack
       * band's width). */
      std::vector<double> fibre_length;
      /** Normalised depth [-] of the cell's shallowest reference point
       * below the face of the yarn that the projectile strikes: 0 on that face,
       * 1 on the opposite one (FailureLaw::onset_log_stretch_at()). */
      std::vector<double> depth;

      /** Largest ln(lambda_f) over the Gauss points: the strains are
       * expm1() of it, taken only where they are reported. */
      std::vector<double> log_stretch;
      /** Mean ln(lambda_f) over the Gauss points. */
      std::vector<double> mean_log_stretch;
      /** Largest |I_tc| over the Gauss points (stable time step). */
      std::vector<double> compaction;
      /** Strain energy [J] at the last evaluation; a failed cell keeps the
       * one it released when it failed. The energies are summed from these
       * per-cell terms (ReproducibleSum), so that the sums do not depend on
       * which rank holds which cell. */
      std::vector<double> energy;
      /** Energy the cell has released so far [J]: its strain energy when it
       * broke or was eroded, and the fibre-damage dissipation (summed
       * per cell for the same reason as #energy). */
      std::vector<double> dissipated;

      /** Size every per-cell state array to @p n cells, each cell active,
       * undamaged and unstrained. */
      void
      reset_state(const unsigned int n)
      {
        failed.assign(n, 0);
        damage.assign(n, 0.);
        kappa.assign(n, 0.);
        log_stretch.assign(n, 0.);
        mean_log_stretch.assign(n, 0.);
        compaction.assign(n, 0.);
        energy.assign(n, 0.);
        dissipated.assign(n, 0.);
      }

      /** Number of cells. */
      unsigned int
      size() const
      {
        return failed.size();
      }
    };

    /**
     * The internal forces of all active cells of @p cells at the
     * displacement @p displacement [m] (ghosts up to date): subtracts each
     * cell's forces [N] from @p force's local entries, cell after cell in
     * the order of @p cells, records each cell's strain energy [J] in
     * CellData::energy and returns their sum. The
     * failure law @p failure breaks, damages and erodes cells (FailureLaw);
     * the energy they release [J] goes to @p dissipated: the strain energy
     * of a broken or eroded cell, and for fibre damage the law's
     * dissipation along its envelope (dissipation_increment()), so that
     * the energy balance closes.
     *
     * Instantiated for each law of YARN_IMPACT_FE_FOR_EACH_LAW.
     */
    template <class Law>
    double
    internal_forces(
      const Law &law,
      CellData &cells,
      const dealii::LinearAlgebra::distributed::Vector<double> &displacement,
      dealii::LinearAlgebra::distributed::Vector<double> &force,
      const FailureLaw &failure,
      double &dissipated);
  } // namespace FE
} // namespace YarnImpact

#endif
