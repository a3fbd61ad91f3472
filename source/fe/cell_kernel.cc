#include <yarn_impact/fe/cell_kernel.h>
#include <yarn_impact/fe/constitutive_law.h>

#include <algorithm>
#include <cmath>
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

      /**
       * Internal forces f (24 values [N], not yet negated) of one cell from
       * its nodal displacements u, shape gradients and JxW, one Gauss point
       * at a time (any law).
       */
      template <class Law>
      inline CellResult
      integrate_scalar(const Law &law,
                       const double *u,
                       const double *grad,
                       const double *JxW,
                       double *f)
      {
        CellResult r;
        for (unsigned int k = 0; k < n_cell_dofs; ++k)
          f[k] = 0.;
        for (unsigned int q = 0; q < n_q; ++q)
          {
            double g[n_nodes * 3];
            gather_gradients(grad, q, g);
            Matrix3 F, P;
            deformation_gradient(u, g, F);
            Invariants inv;
            const double W   = law.stress(F, P, inv);
            r.max_elongation = std::max(r.max_elongation, inv.elongation);
            r.sum_elongation += inv.elongation;
            r.max_compaction =
              std::max(r.max_compaction, std::abs(inv.compaction));
            r.min_J = std::min(r.min_J, internal::determinant(F));
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
      template <class Law>
      inline CellResult
      integrate_lanes(const Law &law,
                      const double *u,
                      const double *grad,
                      const double *JxW,
                      double *f)
      {
        using internal::Double4;
        using internal::n_lanes;
        CellResult r;
        Double4 fv[n_cell_dofs];
        for (auto &v : fv)
          v = Double4{0., 0., 0., 0.};
        for (unsigned int block = 0; block < n_q / n_lanes; ++block)
          {
            const double *gb = grad + block * gradient_block_size;
            Double4 g[n_nodes][3];
            for (unsigned int a = 0; a < n_nodes; ++a)
              for (unsigned int d = 0; d < 3; ++d)
                for (unsigned int l = 0; l < n_lanes; ++l)
                  g[a][d][l] = gb[lane_gradient_index(a, d, l)];
            Double4 F[9];
            for (unsigned int k = 0; k < 9; ++k)
              F[k] = Double4{0., 0., 0., 0.} + (k % 4 == 0 ? 1. : 0.);
            for (unsigned int a = 0; a < n_nodes; ++a)
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = 0; j < 3; ++j)
                  F[3 * i + j] += u[3 * a + i] * g[a][j];
            const Double4 J = internal::determinant(F);
            Double4 P[9], Ie, Itc, Itd;
            const Double4 W = law.stress_kernel(F, P, Ie, Itc, Itd);
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
      template <class Law>
      inline CellResult
      integrate_cell(const Law &law,
                     const double *u,
                     const double *grad,
                     const double *JxW,
                     double *f)
      {
        if constexpr (Law::vectorised)
          return integrate_lanes(law, u, grad, JxW, f);
        else
          return integrate_scalar(law, u, grad, JxW, f);
      }

      // Compiled twice, for CPUs with AVX2 and FMA and for any x86-64, and
      // dispatched on the CPU's features. (GCC's target_clones with
      // "arch=haswell" dispatches on the CPU *model*, so on a virtual
      // machine that reports a generic Xeon it silently ran the generic
      // clone.)
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
      template <class Law>
      __attribute__((target("avx2,fma"), flatten)) CellResult
      integrate_avx2(const Law &law,
                     const double *u,
                     const double *grad,
                     const double *JxW,
                     double *f)
      {
        return integrate_cell(law, u, grad, JxW, f);
      }

      const bool cpu_has_avx2_fma =
        __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#endif

      template <class Law>
      __attribute__((flatten)) CellResult
      integrate(const Law &law,
                const double *u,
                const double *grad,
                const double *JxW,
                double *f)
      {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
        if (cpu_has_avx2_fma)
          return integrate_avx2(law, u, grad, JxW, f);
#endif
        return integrate_cell(law, u, grad, JxW, f);
      }
    } // namespace


    template <class Law>
    double
    internal_forces(
      const Law &law,
      CellData &cells,
      const dealii::LinearAlgebra::distributed::Vector<double> &displacement,
      dealii::LinearAlgebra::distributed::Vector<double> &force,
      const bool failure,
      const double failure_log_stretch,
      double &dissipated)
    {
      double energy = 0.;
      for (unsigned int c = 0; c < cells.size(); ++c)
        {
          if (cells.failed[c])
            continue;
          const unsigned int *dofs = &cells.dofs[c * n_cell_dofs];
          const double *grad       = &cells.grads[c * grad_size];
          const double *JxW        = &cells.JxW[c * n_q];
          double u[n_cell_dofs], f[n_cell_dofs];
          for (unsigned int k = 0; k < n_cell_dofs; ++k)
            u[k] = displacement.local_element(dofs[k]);
          const CellResult r        = integrate(law, u, grad, JxW, f);
          const double cell_energy  = r.energy;
          cells.energy[c]           = cell_energy;
          cells.log_stretch[c]      = r.max_elongation;
          cells.mean_log_stretch[c] = r.sum_elongation / n_q;
          cells.compaction[c]       = r.max_compaction;
          if (failure && r.max_elongation > failure_log_stretch)
            {
              // The cell breaks: it carries no force from now on, and its
              // elastic energy is released (counted as dissipated).
              cells.failed[c] = 1;
              dissipated += cell_energy;
              continue;
            }
          if (failure && (!std::isfinite(cell_energy) || r.min_J < 0.2))
            {
              // A cell crushed to less than a fifth of its volume, or
              // inverted, among the broken ends of a cut yarn: it is eroded,
              // as explicit impact codes do (such a cell would set a
              // vanishing time step); its elastic energy leaves with it
              // (counted as dissipated). Without failure the run stops
              // instead on the NaN or on the energy error.
              cells.failed[c] = 1;
              if (std::isfinite(cell_energy))
                dissipated += cell_energy;
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
    const bool,                                                 \
    const double,                                               \
    double &);
    YARN_IMPACT_FE_FOR_EACH_LAW(YARN_IMPACT_FE_INSTANTIATE)
#undef YARN_IMPACT_FE_INSTANTIATE
  } // namespace FE
} // namespace YarnImpact
