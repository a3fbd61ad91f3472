#ifndef yarn_impact_fe_cell_kernel_h
#define yarn_impact_fe_cell_kernel_h

#include <yarn_impact/fe/failure_law.h>
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

    /** Fibre-frame values stored per cell: a FibreFrame (9 values) per
     * Gauss point. */
    constexpr unsigned int frame_size = 9 * n_q;

    /** Where entry @p k (row-major) of the fibre frame of Gauss point @p q
     * lies among a cell's frame_size values: [block][entry][lane], as the
     * gradients, so that the vectorised loop loads entry k of the four
     * Gauss points of a block as one Double4. */
    constexpr unsigned int
    frame_index(const unsigned int q, const unsigned int k)
    {
      return (q / internal::n_lanes) * 9 * internal::n_lanes +
             k * internal::n_lanes + q % internal::n_lanes;
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

    /** F += sum_a u_a (x) g_a, from the nodal displacements u [m] and the
     * shape gradients g [1/m] (both 3a + d): the part of the deformation
     * gradient that both of its forms below add to their reference. */
    inline void
    add_displacement_gradient(const double *u,
                              const double *g,
                              Mechanics::Matrix3 &F)
    {
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

    /** F = I + sum_a u_a (x) grad N_a at one Gauss point, from the nodal
     * displacements u [m] and the shape gradients g [1/m] (both 3a + d). */
    inline void
    deformation_gradient(const double *u,
                         const double *g,
                         Mechanics::Matrix3 &F)
    {
      F[0] = F[4] = F[8] = 1.;
      F[1] = F[2] = F[3] = F[5] = F[6] = F[7] = 0.;
      add_displacement_gradient(u, g, F);
    }

    /** F R = R + sum_a u_a (x) g_a at one Gauss point with the fibre
     * frame @p R, from the nodal displacements u [m] and the shape
     * gradients g [1/m] in that frame (R^T grad N_a, CellData::frames):
     * the deformation gradient a law takes in its frame. */
    inline void
    deformation_gradient(const double *u,
                         const double *g,
                         const Mechanics::FibreFrame &R,
                         Mechanics::Matrix3 &F)
    {
      for (unsigned int k = 0; k < 9; ++k)
        F[k] = R[k];
      add_displacement_gradient(u, g, F);
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
      /** The fibre frames (Mechanics::FibreFrame: M, T1, T2 in the
       * reference configuration) of the Gauss points, frame_size values
       * per cell laid out as frame_index() says. Empty when every fibre
       * lies along x (the straight yarn): the force loop then runs its
       * straight path, R = I, and loads nothing. With frames, #grads holds
       * each Gauss point's shape gradients in its frame, R^T grad N_a, so
       * that R + sum_a u_a (x) R^T grad N_a is F R, the deformation
       * gradient that a law takes in its frame, and the nodal forces
       * P' R^T grad N_a are those of the stress P = P' R^T (doc/theory.md
       * section 1.8): the loop is the straight one but for F's start. */
      std::vector<double> frames;
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

      /**
       * Give cell @p c (whose gradients and JxW are stored) the fibre
       * frames @p R of its Gauss points: stores them and turns its shape
       * gradients into the frames (see #frames). Cells before @p c that
       * have no frame yet get that of e_x, the identity; once one cell
       * has frames, every cell must (the force loop reads them by cell
       * index), so a caller orients each cell it adds after this call.
       */
      void
      set_fibre_frames(const unsigned int c,
                       const Mechanics::FibreFrame (&R)[n_q]);
    };

    /** The deformation gradient of Gauss point @p q of cell @p c at the
     * nodal displacements @p u [m], in the point's fibre frame when the
     * cells have frames (F R, the laws' argument), F otherwise. */
    inline void
    cell_deformation_gradient(const CellData &cells,
                              const unsigned int c,
                              const unsigned int q,
                              const double *u,
                              Mechanics::Matrix3 &F)
    {
      double g[n_nodes * 3];
      gather_gradients(&cells.grads[c * grad_size], q, g);
      if (cells.frames.empty())
        {
          deformation_gradient(u, g, F);
          return;
        }
      Mechanics::FibreFrame R;
      for (unsigned int k = 0; k < 9; ++k)
        R[k] = cells.frames[c * frame_size + frame_index(q, k)];
      deformation_gradient(u, g, R, F);
    }

    /**
     * The variant of the cell kernel this process runs, for the run's
     * report: "avx2+fma" on a CPU with both unless the environment variable
     * YARN_IMPACT_PORTABLE_KERNEL is set, "portable" otherwise.
     */
    const char *
    cell_kernel_variant();

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
