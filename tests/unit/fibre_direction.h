// Helpers shared by the physics checks of the FE laws with a fibre
// direction at any angle (tests/unit/fibre_direction.cc,
// tests/unit/fibre_direction_closed_forms.cc): random rotations and
// directions, 3x3 algebra, a law evaluated along M, and one distorted Q1
// cell run through the FE cell kernel.
#ifndef yarn_impact_tests_unit_fibre_direction_h
#define yarn_impact_tests_unit_fibre_direction_h

#include <yarn_impact/fe/cell_kernel.h>
#include <yarn_impact/fe/constitutive_law.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace FibreDirectionTest
{
  using namespace YarnImpact::FE;
  using YarnImpact::Mechanics::Invariants;
  using YarnImpact::Mechanics::Matrix3;
  using Vector = dealii::LinearAlgebra::distributed::Vector<double>;

  inline std::mt19937 generator(2024);

  inline double
  uniform(const double a, const double b)
  {
    return std::uniform_real_distribution<double>(a, b)(generator);
  }

  /** A random rotation, from a uniformly random unit quaternion. */
  inline void
  random_rotation(Matrix3 &Q)
  {
    std::normal_distribution<double> normal;
    double q[4], n = 0.;
    for (double &c : q)
      {
        c = normal(generator);
        n += c * c;
      }
    n              = std::sqrt(n);
    const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    const double R[9] = {1 - 2 * (y * y + z * z),
                         2 * (x * y - w * z),
                         2 * (x * z + w * y),
                         2 * (x * y + w * z),
                         1 - 2 * (x * x + z * z),
                         2 * (y * z - w * x),
                         2 * (x * z - w * y),
                         2 * (y * z + w * x),
                         1 - 2 * (x * x + y * y)};
    std::copy(R, R + 9, Q);
  }

  inline void
  random_direction(double (&M)[3])
  {
    std::normal_distribution<double> normal;
    double n = 0.;
    for (double &c : M)
      {
        c = normal(generator);
        n += c * c;
      }
    for (double &c : M)
      c /= std::sqrt(n);
  }

  inline void
  multiply(const Matrix3 &A, const Matrix3 &B, Matrix3 &AB)
  {
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        AB[3 * i + j] =
          A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
  }

  /** Q A Q^T. */
  inline void
  rotate(const Matrix3 &Q, const Matrix3 &A, Matrix3 &B)
  {
    Matrix3 QA, Qt;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        Qt[3 * i + j] = Q[3 * j + i];
    multiply(Q, A, QA);
    multiply(QA, Qt, B);
  }

  inline void
  rotate_vector(const Matrix3 &Q, const double *v, double *w)
  {
    for (unsigned int i = 0; i < 3; ++i)
      w[i] = Q[3 * i] * v[0] + Q[3 * i + 1] * v[1] + Q[3 * i + 2] * v[2];
  }

  /** Largest |a - b| over largest |b|. */
  inline double
  difference(const double *a, const double *b, const unsigned int n)
  {
    double diff = 0., norm = 1e-300;
    for (unsigned int i = 0; i < n; ++i)
      {
        diff = std::max(diff, std::abs(a[i] - b[i]));
        norm = std::max(norm, std::abs(b[i]));
      }
    return diff / norm;
  }

  inline double
  relative(const double a, const double b)
  {
    return std::abs(a - b) / std::max(std::abs(b), 1e-300);
  }

  inline void
  report(const char *what, const double worst, const double tolerance)
  {
    std::printf("  %-52s %s (below %.0e)\n",
                what,
                worst < tolerance ? "OK" : "WRONG",
                tolerance);
  }

  inline void
  check(const char *name,
        const double value,
        const double reference,
        const double tolerance)
  {
    std::printf("  %-40s %12.6f  reference %12.6f  %s\n",
                name,
                value,
                reference,
                relative(value, reference) <= tolerance ? "OK" : "WRONG");
  }

  /** The law with fibre direction M at F: P [Pa], returns W [J/m^3]. */
  template <class Law>
  double
  stress_along(const Law &law,
               const Matrix3 &F,
               const double (&M)[3],
               Matrix3 &P,
               Invariants &inv)
  {
    Matrix3 R;
    YarnImpact::Mechanics::fibre_frame(M, R);
    return oriented_stress(law, F, R, P, inv);
  }

  /** One distorted Q1 cell as the force loop sees it. */
  struct OneCell
  {
    /** Reference vertices [m], deal.II's order. */
    std::vector<dealii::Point<3>> X;
    /** Shape gradients [1/m] at the Gauss points, [q][a][d]. */
    double g[n_q][n_nodes][3];
    double JxW[n_q];
  };

  inline OneCell
  make_cell(const std::vector<dealii::Point<3>> &X)
  {
    dealii::Triangulation<3> tria;
    dealii::GridGenerator::general_cell(tria, X);
    dealii::FE_Q<3> fe(1);
    dealii::QGauss<3> quadrature(2);
    dealii::FEValues<3> values(fe,
                               quadrature,
                               dealii::update_gradients |
                                 dealii::update_JxW_values);
    values.reinit(tria.begin_active());
    OneCell cell;
    cell.X = X;
    for (unsigned int q = 0; q < n_q; ++q)
      {
        cell.JxW[q] = values.JxW(q);
        for (unsigned int a = 0; a < n_nodes; ++a)
          for (unsigned int d = 0; d < 3; ++d)
            cell.g[q][a][d] = values.shape_grad(a, q)[d];
      }
    return cell;
  }

  /**
   * The cell kernel on one cell: nodal forces f [N] (the internal forces,
   * not negated) at the nodal displacements u [m] with fibre directions M
   * per Gauss point (or the straight yarn's layout without frames when
   * @p with_frames is false). Returns the energy [J]; the damage comes
   * back in @p damage.
   */
  template <class Law>
  inline double
  kernel_forces(const Law &law,
                const OneCell &cell,
                const double (&M)[n_q][3],
                const bool with_frames,
                const double (&u)[n_cell_dofs],
                const FailureLaw &failure,
                double (&f)[n_cell_dofs],
                double &damage)
  {
    CellData cells;
    for (unsigned int k = 0; k < n_cell_dofs; ++k)
      cells.dofs.push_back(k);
    cells.grads.resize(grad_size);
    for (unsigned int q = 0; q < n_q; ++q)
      {
        for (unsigned int a = 0; a < n_nodes; ++a)
          for (unsigned int d = 0; d < 3; ++d)
            cells.grads[gradient_index(q, a, d)] = cell.g[q][a][d];
        cells.JxW.push_back(cell.JxW[q]);
      }
    cells.fibre_length.push_back(1e-4);
    cells.depth.push_back(0.);
    if (with_frames)
      {
        Matrix3 R[n_q];
        for (unsigned int q = 0; q < n_q; ++q)
          YarnImpact::Mechanics::fibre_frame(M[q], R[q]);
        cells.set_fibre_frames(0, R);
      }
    cells.reset_state(1);
    Vector displacement(n_cell_dofs), force(n_cell_dofs);
    for (unsigned int k = 0; k < n_cell_dofs; ++k)
      displacement.local_element(k) = u[k];
    double dissipated = 0.;
    const double energy =
      internal_forces(law, cells, displacement, force, failure, dissipated);
    for (unsigned int k = 0; k < n_cell_dofs; ++k)
      f[k] = -force.local_element(k);
    damage = cells.damage[0];
    return energy;
  }

  /** The reference cell: a unit cube of side 0.1 mm, its vertices moved
   * at random by up to 15 % of the side, centred near the origin. */
  inline std::vector<dealii::Point<3>>
  distorted_cube()
  {
    const double h = 1e-4;
    std::vector<dealii::Point<3>> X;
    for (unsigned int a = 0; a < n_nodes; ++a)
      X.emplace_back(h * ((a & 1) - 0.5 + uniform(-0.15, 0.15)),
                     h * (((a >> 1) & 1) - 0.5 + uniform(-0.15, 0.15)),
                     h * (((a >> 2) & 1) - 0.5 + uniform(-0.15, 0.15)));
    return X;
  }

} // namespace FibreDirectionTest

#endif
