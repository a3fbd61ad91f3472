#include <yarn_impact/fe/cell_kernel.h>
#include <yarn_impact/fe/constitutive_law.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace YarnImpact
{
  namespace FE
  {
    namespace
    {
      /** What the force loop keeps of one cell besides its forces. */
      struct CellResult
      {
        double energy         = 0.;    // strain energy [J]
        double max_elongation = -1.;   // largest ln(lambda_f)
        double sum_elongation = 0.;    // sum over Gauss points of ln(lambda_f)
        double max_compaction = 0.;    // largest |I_tc|
        double min_J          = 1e300; // smallest det F
      };

      /** What the force loop hands the integration of one cell. */
      struct CellInput
      {
        /** Nodal displacements [m], 3a + d. */
        const double *u;
        /** Shape gradients [1/m] (gradient_index()). */
        const double *grad;
        /** Fibre frames (frame_index()), or null on the straight path. */
        const double *frame;
        /** Gauss weights times Jacobians [m^3]. */
        const double *JxW;
        /** Whether the progressive failure law damages the fibre term. */
        bool progressive;
      };

      /**
       * Internal forces f (24 values [N], not yet negated) of one cell from
       * its nodal displacements, shape gradients and JxW (@p in), one Gauss
       * point at a time (any law); with in.progressive the fibre damage
       * from @p damage_of (the largest ln(lambda_f) and the sum of
       * ln(lambda_f)^2 JxW of this configuration). With @p oriented the
       * gradients are in the Gauss points' fibre frames in.frame
       * (CellData::frames) and F starts
       * from the frame instead of I: F is then F R, the law's argument,
       * and P the law's P', whose forces with the turned gradients are
       * those of P' R^T; the straight yarn compiles without it.
       */
      template <class Law, bool oriented, class Damage>
      inline CellResult
      integrate_scalar(const Law &law,
                       const CellInput &in,
                       const Damage &damage_of,
                       double *f)
      {
        const double *u = in.u, *grad = in.grad, *frame = in.frame,
                     *JxW = in.JxW;
        CellResult r;
        for (unsigned int k = 0; k < n_cell_dofs; ++k)
          f[k] = 0.;
        Mechanics::Matrix3 Fq[n_q];
        for (unsigned int q = 0; q < n_q; ++q)
          {
            double g[n_nodes * 3];
            gather_gradients(grad, q, g);
            if constexpr (oriented)
              {
                Mechanics::FibreFrame R;
                for (unsigned int k = 0; k < 9; ++k)
                  R[k] = frame[frame_index(q, k)];
                deformation_gradient(u, g, R, Fq[q]);
              }
            else
              deformation_gradient(u, g, Fq[q]);
          }
        double fibre_damage = 0.;
        if constexpr (Law::separable_fibre_term)
          if (in.progressive)
            {
              // The fibre stretches of this configuration, before the
              // stresses: the damage of this step (explicit, no lag).
              double max_Ie = -1., sum_Ie2_JxW = 0.;
              for (unsigned int q = 0; q < n_q; ++q)
                {
                  const Mechanics::Matrix3 &F = Fq[q];
                  const double Ie =
                    0.5 * std::log(F[0] * F[0] + F[3] * F[3] + F[6] * F[6]);
                  max_Ie = std::max(max_Ie, Ie);
                  sum_Ie2_JxW += Ie * Ie * JxW[q];
                }
              fibre_damage = damage_of(max_Ie, sum_Ie2_JxW);
            }
        for (unsigned int q = 0; q < n_q; ++q)
          {
            double g[n_nodes * 3];
            gather_gradients(grad, q, g);
            const Mechanics::Matrix3 &F = Fq[q];
            Mechanics::Matrix3 P;
            Mechanics::Invariants inv;
            double W = law.stress(F, P, inv);
            if constexpr (Law::separable_fibre_term)
              if (fibre_damage > 0.)
                {
                  // Remove d times the fibre part (k_e I_e / I4) F M (x) M
                  // of P and d times 1/2 k_e I_e^2 of W (M = e_x in the
                  // fibre frame: column 0 of F).
                  const double I4 = F[0] * F[0] + F[3] * F[3] + F[6] * F[6];
                  const double k  = fibre_damage * law.axial_modulus();
                  const double a  = k * inv.elongation / I4;
                  P[0] -= a * F[0];
                  P[3] -= a * F[3];
                  P[6] -= a * F[6];
                  W -= 0.5 * k * inv.elongation * inv.elongation;
                }
            r.max_elongation = std::max(r.max_elongation, inv.elongation);
            r.sum_elongation += inv.elongation;
            r.max_compaction =
              std::max(r.max_compaction, std::abs(inv.compaction));
            r.min_J = std::min(r.min_J, Mechanics::determinant(F));
            r.energy += W * JxW[q];
            for (double &p : P)
              p *= JxW[q];
            for (unsigned int a = 0; a < n_nodes; ++a)
              for (unsigned int i = 0; i < 3; ++i)
                f[3 * a + i] += P[3 * i] * g[3 * a] +
                                P[3 * i + 1] * g[3 * a + 1] +
                                P[3 * i + 2] * g[3 * a + 2];
          }
        return r;
      }

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
      /**
       * The same for a vectorised law (Law::vectorised), four Gauss points
       * at a time in SIMD lanes: the hot loop of the benchmark.
       */
      template <class Law, bool oriented, class Damage>
      inline CellResult
      integrate_lanes(const Law &law,
                      const CellInput &in,
                      const Damage &damage_of,
                      double *f)
      {
        const double *u = in.u, *grad = in.grad, *frame = in.frame,
                     *JxW = in.JxW;
        using internal::Double4;
        using internal::n_lanes;
        constexpr unsigned int n_blocks = n_q / n_lanes;
        CellResult r;
        Double4 fv[n_cell_dofs];
        for (auto &v : fv)
          v = Double4{0., 0., 0., 0.};
        // The shape gradients of a block, [vertex][direction][lane].
        const auto load_gradients = [grad](const unsigned int block,
                                           Double4(&g)[n_nodes][3]) {
          const double *gb = grad + block * gradient_block_size;
          for (unsigned int a = 0; a < n_nodes; ++a)
            for (unsigned int d = 0; d < 3; ++d)
              for (unsigned int l = 0; l < n_lanes; ++l)
                g[a][d][l] = gb[lane_gradient_index(a, d, l)];
        };
        Double4 Fb[n_blocks][9];
        for (unsigned int block = 0; block < n_blocks; ++block)
          {
            Double4 g[n_nodes][3];
            load_gradients(block, g);
            Double4(&F)[9] = Fb[block];
            if constexpr (oriented)
              std::memcpy(F,
                          frame + block * 9 * n_lanes,
                          sizeof(F)); // the block's frames, [entry][lane]
            else
              for (unsigned int k = 0; k < 9; ++k)
                F[k] = Double4{0., 0., 0., 0.} + (k % 4 == 0 ? 1. : 0.);
            for (unsigned int a = 0; a < n_nodes; ++a)
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = 0; j < 3; ++j)
                  F[3 * i + j] += u[3 * a + i] * g[a][j];
          }
        double fibre_damage = 0.;
        if constexpr (Law::separable_fibre_term)
          if (in.progressive)
            {
              // As in integrate_scalar(): the damage from this
              // configuration's fibre stretches, before the stresses.
              double max_Ie = -1., sum_Ie2_JxW = 0.;
              for (unsigned int block = 0; block < n_blocks; ++block)
                {
                  const Double4(&F)[9] = Fb[block];
                  const Double4 Ie =
                    0.5 *
                    internal::lane_log(F[0] * F[0] + F[3] * F[3] + F[6] * F[6]);
                  for (unsigned int l = 0; l < n_lanes; ++l)
                    {
                      max_Ie = std::max(max_Ie, Ie[l]);
                      sum_Ie2_JxW += Ie[l] * Ie[l] * JxW[block * n_lanes + l];
                    }
                }
              fibre_damage = damage_of(max_Ie, sum_Ie2_JxW);
            }
        for (unsigned int block = 0; block < n_blocks; ++block)
          {
            Double4 g[n_nodes][3];
            load_gradients(block, g);
            const Double4(&F)[9] = Fb[block];
            const Double4 J      = Mechanics::determinant(F);
            Double4 P[9], Ie, Itc, Itd;
            Double4 W = law.stress_kernel(F, P, Ie, Itc, Itd);
            if constexpr (Law::separable_fibre_term)
              if (fibre_damage > 0.)
                {
                  // As in integrate_scalar(): the damaged fibre part out.
                  const Double4 I4 = F[0] * F[0] + F[3] * F[3] + F[6] * F[6];
                  const double k   = fibre_damage * law.axial_modulus();
                  const Double4 a  = k * Ie / I4;
                  P[0] -= a * F[0];
                  P[3] -= a * F[3];
                  P[6] -= a * F[6];
                  W -= (0.5 * k) * Ie * Ie;
                }
            Double4 jxw;
            std::memcpy(&jxw, JxW + block * n_lanes, sizeof(jxw));
            for (auto &p : P)
              p *= jxw;
            const Double4 w = W * jxw;
            for (unsigned int l = 0; l < n_lanes; ++l)
              {
                r.energy += w[l];
                r.max_elongation = std::max(r.max_elongation, Ie[l]);
                r.sum_elongation += Ie[l];
                r.max_compaction = std::max(r.max_compaction, std::abs(Itc[l]));
                r.min_J          = std::min(r.min_J, J[l]);
              }
            for (unsigned int a = 0; a < n_nodes; ++a)
              for (unsigned int i = 0; i < 3; ++i)
                fv[3 * a + i] += P[3 * i] * g[a][0] + P[3 * i + 1] * g[a][1] +
                                 P[3 * i + 2] * g[a][2];
          }
        for (unsigned int k = 0; k < n_cell_dofs; ++k)
          f[k] = (fv[k][0] + fv[k][1]) + (fv[k][2] + fv[k][3]);
        return r;
      }
#pragma GCC diagnostic pop

      /** One cell with the path the law supports. */
      template <class Law, bool oriented, class Damage>
      inline CellResult
      integrate_cell(const Law &law,
                     const CellInput &in,
                     const Damage &damage_of,
                     double *f)
      {
        if constexpr (Law::vectorised)
          return integrate_lanes<Law, oriented>(law, in, damage_of, f);
        else
          return integrate_scalar<Law, oriented>(law, in, damage_of, f);
      }

      // Compiled twice, for CPUs with AVX2 and FMA and for any x86-64, and
      // dispatched on the CPU's features. (GCC's target_clones with
      // "arch=haswell" dispatches on the CPU *model*, so on a virtual
      // machine that reports a generic Xeon it silently ran the generic
      // clone.)
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
      template <class Law, bool oriented, class Damage>
      __attribute__((target("avx2,fma"), flatten)) CellResult
      integrate_avx2(const Law &law,
                     const CellInput &in,
                     const Damage &damage_of,
                     double *f)
      {
        return integrate_cell<Law, oriented>(law, in, damage_of, f);
      }
#endif

      template <class Law, bool oriented, class Damage>
      __attribute__((flatten)) CellResult
      integrate(const Law &law,
                const CellInput &in,
                const Damage &damage_of,
                double *f)
      {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
        if (internal::avx2_fma_kernel)
          return integrate_avx2<Law, oriented>(law, in, damage_of, f);
#endif
        return integrate_cell<Law, oriented>(law, in, damage_of, f);
      }
    } // namespace


    const char *
    cell_kernel_variant()
    {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
      if (internal::avx2_fma_kernel)
        return "avx2+fma";
#endif
      return "portable";
    }


    void
    CellData::set_fibre_frames(const unsigned int c,
                               const Mechanics::FibreFrame (&R)[n_q])
    {
      // The cells before c without a frame get the identity (e_x).
      const std::size_t n_framed = frames.size() / frame_size;
      frames.resize(std::max<std::size_t>(n_framed, c + 1) * frame_size, 0.);
      for (std::size_t b = n_framed; b < c; ++b)
        for (unsigned int q = 0; q < n_q; ++q)
          for (const unsigned int k : {0u, 4u, 8u})
            frames[b * frame_size + frame_index(q, k)] = 1.;
      double *grad = &grads[c * grad_size];
      for (unsigned int q = 0; q < n_q; ++q)
        {
          for (unsigned int k = 0; k < 9; ++k)
            frames[c * frame_size + frame_index(q, k)] = R[q][k];
          // grad N_a in the frame: component j is (column j of R) . grad.
          for (unsigned int a = 0; a < n_nodes; ++a)
            {
              const double g[3] = {grad[gradient_index(q, a, 0)],
                                   grad[gradient_index(q, a, 1)],
                                   grad[gradient_index(q, a, 2)]};
              for (unsigned int j = 0; j < 3; ++j)
                grad[gradient_index(q, a, j)] =
                  R[q][j] * g[0] + R[q][3 + j] * g[1] + R[q][6 + j] * g[2];
            }
        }
    }


    template <class Law>
    double
    internal_forces(
      const Law &law,
      CellData &cells,
      const dealii::LinearAlgebra::distributed::Vector<double> &displacement,
      dealii::LinearAlgebra::distributed::Vector<double> &force,
      const FailureLaw &failure,
      double &dissipated)
    {
      using Kind          = FailureLaw::Kind;
      const bool fails    = failure.kind != Kind::none;
      const bool progress = failure.kind == Kind::progressive;
      const bool oriented = !cells.frames.empty();
      double energy       = 0.;
      for (unsigned int c = 0; c < cells.size(); ++c)
        {
          if (cells.failed[c] != CellState::active)
            continue;
          const unsigned int *dofs = &cells.dofs[c * n_cell_dofs];
          const double *grad       = &cells.grads[c * grad_size];
          const double *JxW        = &cells.JxW[c * n_q];
          const double *frame =
            oriented ? &cells.frames[c * frame_size] : nullptr;
          double u[n_cell_dofs], f[n_cell_dofs];
          for (unsigned int k = 0; k < n_cell_dofs; ++k)
            u[k] = displacement.local_element(dofs[k]);
          // The damage of this step from the fibre stretches of this
          // configuration, which the kernel hands over before the stresses
          // (explicit, no lag): the largest ln(lambda_f) of the Gauss
          // points and the sum of ln(lambda_f)^2 JxW.
          const auto damage_of = [&](const double max_Ie,
                                     const double sum_Ie2_JxW) {
            if (max_Ie > cells.kappa[c])
              {
                const double fibre_energy =
                  0.5 * failure.fibre_modulus * sum_Ie2_JxW;
                const double I_0 = failure.onset_log_stretch_at(cells.depth[c]);
                const double d =
                  failure.damage(max_Ie, cells.fibre_length[c], I_0);
                // What the law dissipates: the exact integral along its
                // envelope (d only grows: irreversible).
                const double released =
                  dissipation_increment(failure,
                                        cells.kappa[c],
                                        max_Ie,
                                        fibre_energy,
                                        cells.fibre_length[c],
                                        I_0);
                dissipated += released;
                cells.dissipated[c] += released;
                cells.kappa[c]  = max_Ie;
                cells.damage[c] = std::max(cells.damage[c], d);
              }
            return cells.damage[c];
          };
          const CellInput in        = {u, grad, frame, JxW, progress};
          const CellResult r        = oriented
                                        ? integrate<Law, true>(law, in, damage_of, f)
                                        : integrate<Law, false>(law, in, damage_of, f);
          const double cell_energy  = r.energy;
          cells.energy[c]           = cell_energy;
          cells.log_stretch[c]      = r.max_elongation;
          cells.mean_log_stretch[c] = r.sum_elongation / n_q;
          cells.compaction[c]       = r.max_compaction;
          if (failure.kind == Kind::sudden &&
              r.max_elongation > failure.onset_log_stretch)
            {
              // The cell breaks: it carries no force from now on, and its
              // elastic energy is released (counted as dissipated).
              cells.failed[c] = CellState::broken;
              dissipated += cell_energy;
              cells.dissipated[c] += cell_energy;
              continue;
            }
          // A fully damaged cell keeps its transverse response while its
          // broken fibres still fill the section; once they are stretched
          // to twice its length their ends have parted by a whole cell,
          // and such a cell only degenerates (its altitude, and with it
          // the stable step, can fall to nothing: a cell torn at 5000 m/s
          // reached 2e-17 m).
          // Under the hybrid's fibre bars (Kind::erosion) the bars are the
          // fibres: a cell stretched to twice its length lies among their
          // broken ends, and parts the same way.
          const bool parted = (failure.kind == Kind::erosion ||
                               (progress && cells.damage[c] >= 1.)) &&
                              r.max_elongation > FailureLaw::parted_log_stretch;
          if (fails && (!std::isfinite(cell_energy) || r.min_J < 0.2 || parted))
            {
              // A cell crushed to less than a fifth of its volume, or
              // inverted, or parted, among the broken ends of a cut yarn: it is
              // eroded, as explicit impact codes do (such a cell would set a
              // vanishing time step); its elastic energy leaves with it
              // (counted as dissipated). Erosion is a numerical removal,
              // counted apart from failure. Without failure the run stops
              // instead on the NaN or on the energy error.
              cells.failed[c] = CellState::eroded;
              if (std::isfinite(cell_energy))
                {
                  dissipated += cell_energy;
                  cells.dissipated[c] += cell_energy;
                }
              continue;
            }
          energy += cell_energy;
          for (unsigned int k = 0; k < n_cell_dofs; ++k)
            force.local_element(dofs[k]) -= f[k];
        }
      return energy;
    }


#define YARN_IMPACT_FE_INSTANTIATE(type, Law, member)           \
  template double internal_forces<Law>(                         \
    const Law &,                                                \
    CellData &,                                                 \
    const dealii::LinearAlgebra::distributed::Vector<double> &, \
    dealii::LinearAlgebra::distributed::Vector<double> &,       \
    const FailureLaw &,                                         \
    double &);
    YARN_IMPACT_FE_FOR_EACH_LAW(YARN_IMPACT_FE_INSTANTIATE)
#undef YARN_IMPACT_FE_INSTANTIATE
  } // namespace FE
} // namespace YarnImpact
