#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/core/projectile.h>
#include <yarn_impact/fe/constitutive_law.h>
#include <yarn_impact/fe/fe_model.h>
#include <yarn_impact/fe/yarn_mesh.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q_eulerian.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <ostream>

namespace YarnImpact
{
  namespace FE
  {
    using namespace dealii;

    namespace
    {
      constexpr unsigned int n_nodes     = 8; // vertices of a hexahedron
      constexpr unsigned int n_q         = 8; // 2x2x2 Gauss points
      constexpr unsigned int n_cell_dofs = 3 * n_nodes;
      constexpr unsigned int grad_size   = n_q * n_nodes * 3;

      /** F = I + sum_a u_a (x) grad N_a at one quadrature point. */
      inline void
      deformation_gradient(const double *u, const double *grad, Matrix3 &F)
      {
        F[0] = F[4] = F[8] = 1.;
        F[1] = F[2] = F[3] = F[5] = F[6] = F[7] = 0.;
        for (unsigned int a = 0; a < n_nodes; ++a)
          {
            const double g0 = grad[3 * a], g1 = grad[3 * a + 1],
                         g2 = grad[3 * a + 2];
            for (unsigned int i = 0; i < 3; ++i)
              {
                const double ui = u[3 * a + i];
                F[3 * i] += ui * g0;
                F[3 * i + 1] += ui * g1;
                F[3 * i + 2] += ui * g2;
              }
          }
      }

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
       * Internal forces f (24 values, not yet negated) of one cell from its
       * nodal displacements u, shape gradients and JxW: the body of the hot
       * loop, instantiated per law below.
       */
      /**
       * Shape gradients of one cell are stored for the vectorised loop:
       * [block of 4 Gauss points][node][direction][Gauss point in block].
       */
      inline double
      gradient(const double *grad,
               const unsigned int q,
               const unsigned int a,
               const unsigned int d)
      {
        return grad[(q / 4) * 96 + a * 12 + d * 4 + q % 4];
      }

      /**
       * Internal forces f (24 values, not yet negated) of one cell from its
       * nodal displacements u, shape gradients and JxW, one Gauss point at a
       * time (any law).
       */
      template <class Law>
      inline CellResult
      integrate_cell(const Law &law,
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
            for (unsigned int a = 0; a < n_nodes; ++a)
              for (unsigned int d = 0; d < 3; ++d)
                g[3 * a + d] = gradient(grad, q, a, d);
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
       * The same for the Charmetant law, four Gauss points at a time in SIMD
       * lanes (the hot loop of the benchmark).
       */
      inline CellResult
      integrate_cell(const CharmetantLaw &law,
                     const double *u,
                     const double *grad,
                     const double *JxW,
                     double *f)
      {
        using internal::Double4;
        CellResult r;
        Double4 fv[n_cell_dofs];
        for (auto &v : fv)
          v = Double4{0., 0., 0., 0.};
        for (unsigned int block = 0; block < 2; ++block)
          {
            const double *gb = grad + block * 96;
            Double4 g[n_nodes][3];
            for (unsigned int a = 0; a < n_nodes; ++a)
              for (unsigned int d = 0; d < 3; ++d)
                for (unsigned int l = 0; l < 4; ++l)
                  g[a][d][l] = gb[a * 12 + d * 4 + l];
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
            std::memcpy(&jxw, JxW + block * 4, sizeof(jxw));
            for (auto &p : P)
              p *= jxw;
            const Double4 w = W * jxw;
            for (unsigned int l = 0; l < 4; ++l)
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


    /**
     * The FE yarn: Q1 hexahedra, 2x2x2 Gauss points, row-sum lumped mass,
     * explicit central difference driven by ImpactSimulation, penalty
     * contact with the rigid cylinder, cell failure at a longitudinal
     * strain. The hot loop works on pre-computed shape gradients and local
     * indices into deal.II's distributed vectors.
     */
    template <class Law>
    class YarnModel : public ImpactModel
    {
    public:
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      YarnModel(const YarnImpact::Parameters::Shared &shared,
                const Parameters &parameters,
                const Law &law,
                const MPI_Comm communicator);

      std::string
      name() const override
      {
        return "fe";
      }

      void
      setup(const Projectile &projectile, std::ostream &out) override;

      double
      yarn_top() const override
      {
        return top;
      }

      double
      stable_time_step() const override;

      double
      compute_forces(const Projectile &projectile, const double dt) override;

      void
      kick(const double dt) override;

      void
      drift(const double dt) override;

      Observables
      observables() const override;

      bool
      yarn_cut_through() const override;

      AxialProperties
      axial_properties() const override;

      double
      mass() const override
      {
        return total_mass;
      }

      std::string
      write_snapshot(const std::string &directory,
                     const unsigned int index,
                     const double time) const override;

      unsigned long
      n_elements() const override
      {
        return tria.n_global_active_cells();
      }

    private:
      /** Current positions of the 8 vertices of owned cell c. */
      void
      vertex_positions(const unsigned int c, double (&p)[n_nodes][3]) const;

      const YarnImpact::Parameters::Shared &shared;
      const Parameters parameters;
      const Law law;
      const MPI_Comm communicator;
      const double symmetry;

      parallel::distributed::Triangulation<3> tria;
      FESystem<3> fe;
      DoFHandler<3> dof_handler;

      mutable VectorType displacement;
      mutable VectorType velocity;
      VectorType force;
      VectorType lumped_mass;
      VectorType inverse_mass;
      /** Reference coordinate of each local dof (its own component). */
      std::vector<double> reference_coordinate;

      // Owned cells: local dof indices, shape gradients, JxW.
      std::vector<unsigned int> cell_dofs;
      std::vector<double> cell_grads;
      std::vector<double> cell_JxW;
      std::vector<unsigned int> cell_index; // active_cell_index
      std::vector<unsigned char> cell_axis; // local axis along x
      std::vector<unsigned int> cell_layer; // axial cell layer
      std::vector<unsigned char> cell_failed;
      // Largest and mean ln(lambda_f) of each cell: the strains are
      // expm1() of them, taken only where they are reported.
      std::vector<double> cell_log_stretch;
      std::vector<double> cell_mean_log_stretch;
      /** ln(1 + failure strain): the failure test without expm1 per cell. */
      double failure_log_stretch = 0.;
      std::vector<double> cell_volume;
      std::vector<double> cell_compaction; // max |I_tc|

      // Owned nodes: local indices of their x, y, z dofs and their station.
      std::vector<std::array<unsigned int, 3>> nodes;
      std::vector<unsigned int> node_station;
      // Owned contact nodes: index into nodes, reference area, mass.
      std::vector<unsigned int> contact_nodes;
      std::vector<double> contact_area;
      std::vector<double> contact_mass;

      unsigned int n_stations      = 0;
      unsigned int n_layers        = 0;
      unsigned int cells_per_layer = 0;
      double station_spacing       = 0.;
      std::vector<double> initial_width;
      double total_mass        = 0.;
      double top               = 0.;
      double contact_time_step = 0.;

      // Energies of the owned part, from the last compute_forces().
      double elastic_energy = 0.;
      double contact_energy = 0.;
      double dissipated     = 0.;
    };


    template <class Law>
    YarnModel<Law>::YarnModel(const YarnImpact::Parameters::Shared &shared,
                              const Parameters &parameters,
                              const Law &law,
                              const MPI_Comm communicator)
      : shared(shared)
      , parameters(parameters)
      , law(law)
      , communicator(communicator)
      , symmetry(
          YarnImpact::Parameters::symmetry_factor(shared.general.symmetry))
      , tria(communicator)
      , fe(FE_Q<3>(1), 3)
      , dof_handler(tria)
    {}


    template <class Law>
    void
    YarnModel<Law>::setup(const Projectile &, std::ostream &out)
    {
      const auto &yarn = shared.yarn;
      create_yarn_mesh(tria,
                       yarn,
                       shared.general.symmetry,
                       parameters.n_axial_cells,
                       parameters.section_refinements,
                       parameters.preserve_section_area);
      tria.refine_global(parameters.global_refinements);
      dof_handler.distribute_dofs(fe);

      const IndexSet owned = dof_handler.locally_owned_dofs();
      IndexSet relevant;
      DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
      for (VectorType *v :
           {&displacement, &velocity, &force, &lumped_mass, &inverse_mass})
        v->reinit(owned, relevant, communicator);
      const auto &partitioner = displacement.get_partitioner();
      const unsigned int n_local =
        partitioner->locally_owned_size() + partitioner->n_ghost_indices();
      reference_coordinate.assign(n_local, 0.);

      const bool reduced =
        shared.general.symmetry != YarnImpact::Parameters::Symmetry::none;
      const unsigned int refinement_factor = 1u
                                             << parameters.global_refinements;
      n_layers =
        (reduced ? parameters.n_axial_cells / 2 : parameters.n_axial_cells) *
        refinement_factor;
      station_spacing =
        yarn.length / (parameters.n_axial_cells * refinement_factor);
      n_stations         = parameters.n_axial_cells / 2 * refinement_factor + 1;
      cells_per_layer    = tria.n_global_active_cells() / n_layers;
      const double x_min = reduced ? 0. : -0.5 * yarn.length;

      FE_Q<3> scalar_fe(1);
      QGauss<3> quadrature(2);
      FEValues<3> fe_values(scalar_fe,
                            quadrature,
                            update_values | update_gradients |
                              update_JxW_values);
      QGauss<2> face_quadrature(2);
      FEFaceValues<3> fe_face_values(scalar_fe,
                                     face_quadrature,
                                     update_values | update_JxW_values);
      VectorType area;
      area.reinit(owned, relevant, communicator);

      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          fe_values.reinit(typename Triangulation<3>::cell_iterator(cell));
          cell_index.push_back(cell->active_cell_index());
          double x_lo = std::numeric_limits<double>::max(), x_hi = -x_lo;
          for (unsigned int a = 0; a < n_nodes; ++a)
            {
              double node_mass = 0.;
              for (unsigned int q = 0; q < n_q; ++q)
                node_mass +=
                  law.density * fe_values.shape_value(a, q) * fe_values.JxW(q);
              for (unsigned int d = 0; d < 3; ++d)
                {
                  const auto local =
                    partitioner->global_to_local(cell->vertex_dof_index(a, d));
                  cell_dofs.push_back(local);
                  reference_coordinate[local] = cell->vertex(a)[d];
                  lumped_mass.local_element(local) += node_mass;
                }
              x_lo = std::min(x_lo, cell->vertex(a)[0]);
              x_hi = std::max(x_hi, cell->vertex(a)[0]);
            }
          {
            const std::size_t offset = cell_grads.size();
            cell_grads.resize(offset + grad_size);
            for (unsigned int q = 0; q < n_q; ++q)
              {
                for (unsigned int a = 0; a < n_nodes; ++a)
                  for (unsigned int d = 0; d < 3; ++d)
                    cell_grads[offset + (q / 4) * 96 + a * 12 + d * 4 + q % 4] =
                      fe_values.shape_grad(a, q)[d];
                cell_JxW.push_back(fe_values.JxW(q));
              }
          }
          // The local axis along the fibre: the one whose opposite faces
          // are farthest apart in x.
          unsigned char axis = 0;
          double best        = -1.;
          for (unsigned int k = 0; k < 3; ++k)
            {
              double dx = 0.;
              for (unsigned int a = 0; a < n_nodes; ++a)
                dx += ((a >> k) & 1 ? 1. : -1.) * cell->vertex(a)[0];
              if (std::abs(dx) > best)
                {
                  best = std::abs(dx);
                  axis = k;
                }
            }
          cell_axis.push_back(axis);
          double volume = 0.;
          for (unsigned int q = 0; q < n_q; ++q)
            volume += fe_values.JxW(q);
          cell_volume.push_back(volume);
          cell_layer.push_back(static_cast<unsigned int>(
            std::floor((0.5 * (x_lo + x_hi) - x_min) / station_spacing)));

          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == BoundaryIds::lateral)
              {
                fe_face_values.reinit(typename Triangulation<3>::cell_iterator(
                                        cell),
                                      f);
                for (unsigned int a = 0; a < n_nodes; ++a)
                  {
                    double a_area = 0.;
                    for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                      a_area += fe_face_values.shape_value(a, q) *
                                fe_face_values.JxW(q);
                    area.local_element(partitioner->global_to_local(
                      cell->vertex_dof_index(a, 0))) += a_area;
                  }
              }
        }
      lumped_mass.compress(VectorOperation::add);
      area.compress(VectorOperation::add);
      const unsigned int n_owned_cells = cell_index.size();
      cell_failed.assign(n_owned_cells, 0);
      cell_log_stretch.assign(n_owned_cells, 0.);
      cell_mean_log_stretch.assign(n_owned_cells, 0.);
      failure_log_stretch = std::log1p(shared.yarn.failure_strain);
      cell_compaction.assign(n_owned_cells, 0.);

      // Owned nodes, their constraints and stations. The x dof of a vertex
      // identifies it; all three dofs of a vertex have the same owner.
      const double tol = 1e-6 * station_spacing;
      std::vector<bool> seen(n_local, false);
      for (unsigned int c = 0; c < n_owned_cells; ++c)
        for (unsigned int a = 0; a < n_nodes; ++a)
          {
            const unsigned int ix = cell_dofs[c * n_cell_dofs + 3 * a];
            if (seen[ix] || ix >= partitioner->locally_owned_size())
              continue;
            seen[ix]                               = true;
            const std::array<unsigned int, 3> node = {
              {ix,
               cell_dofs[c * n_cell_dofs + 3 * a + 1],
               cell_dofs[c * n_cell_dofs + 3 * a + 2]}};
            nodes.push_back(node);
            const double x = reference_coordinate[node[0]];
            const double z = reference_coordinate[node[2]];
            node_station.push_back(static_cast<unsigned int>(
              std::round(std::abs(x) / station_spacing)));
            std::array<bool, 3> fixed = {{false, false, false}};
            if (std::abs(std::abs(x) - 0.5 * yarn.length) < tol)
              fixed = {{true, true, true}};
            if (reduced && std::abs(x) < tol)
              fixed[0] = true;
            if (shared.general.symmetry ==
                  YarnImpact::Parameters::Symmetry::quarter &&
                std::abs(z) < 1e-9 * yarn.width_semi_axis)
              fixed[2] = true;
            for (unsigned int d = 0; d < 3; ++d)
              inverse_mass.local_element(node[d]) =
                fixed[d] ? 0. : 1. / lumped_mass.local_element(node[d]);

            const double node_area = area.local_element(node[0]);
            if (node_area > 0. && !fixed[1])
              {
                contact_nodes.push_back(nodes.size() - 1);
                contact_area.push_back(node_area);
                contact_mass.push_back(lumped_mass.local_element(node[0]));
              }
          }

      // Mass of the whole yarn (each node's x dof carries its mass once).
      double local_mass = 0.;
      for (const auto &node : nodes)
        local_mass += lumped_mass.local_element(node[0]);
      total_mass = symmetry * Utilities::MPI::sum(local_mass, communicator);
      double local_top = -std::numeric_limits<double>::max();
      for (const auto &node : nodes)
        local_top = std::max(local_top, reference_coordinate[node[1]]);
      top = Utilities::MPI::max(local_top, communicator);

      // Stable step of a contact node on its penalty spring.
      const double zeta = parameters.contact.damping_ratio;
      double dt_c       = std::numeric_limits<double>::max();
      for (unsigned int k = 0; k < contact_nodes.size(); ++k)
        dt_c = std::min(dt_c,
                        2. * std::sqrt(
                               contact_mass[k] /
                               (parameters.contact.penalty * contact_area[k])));
      contact_time_step = Utilities::MPI::min(dt_c, communicator) *
                          (std::sqrt(1. + zeta * zeta) - zeta);

      displacement = 0.;
      velocity     = 0.;
      displacement.update_ghost_values();

      // The initial section widths, measured as at every history row.
      initial_width.assign(n_stations, 0.);
      {
        const Observables o = observables();
        (void)o;
      }

      out << "[fe] mesh: " << tria.n_global_active_cells() << " cells ("
          << cells_per_layer << " per section, " << n_layers
          << " along the modelled length), " << dof_handler.n_dofs()
          << " dofs, " << Utilities::MPI::n_mpi_processes(communicator)
          << " MPI rank(s)\n"
          << "[fe] contact penalty " << parameters.contact.penalty
          << " Pa/m: stable step of a surface node on it "
          << contact_time_step * 1e9 << " ns\n";
    }


    template <class Law>
    void
    YarnModel<Law>::vertex_positions(const unsigned int c,
                                     double (&p)[n_nodes][3]) const
    {
      const unsigned int *dofs = &cell_dofs[c * n_cell_dofs];
      for (unsigned int a = 0; a < n_nodes; ++a)
        for (unsigned int d = 0; d < 3; ++d)
          p[a][d] = reference_coordinate[dofs[3 * a + d]] +
                    displacement.local_element(dofs[3 * a + d]);
    }


    template <class Law>
    double
    YarnModel<Law>::stable_time_step() const
    {
      // Per cell, the bound 1/sqrt(sum_k (c_k/h_k)^2) over its three local
      // directions (doc/theory.md section 3.3) with the current sizes h_k
      // (distances between opposite face centroids): the yarn flattens
      // under the projectile and its cells thin.
      const double c_axial2 = law.axial_modulus() / law.density;
      double rate2          = 0.;
      for (unsigned int c = 0; c < cell_index.size(); ++c)
        {
          if (cell_failed[c])
            continue;
          double p[n_nodes][3];
          vertex_positions(c, p);
          Invariants inv;
          inv.compaction        = cell_compaction[c];
          const double c_trans2 = law.transverse_modulus(inv) / law.density;
          double r2             = 0.;
          for (unsigned int k = 0; k < 3; ++k)
            {
              double d[3] = {0., 0., 0.};
              for (unsigned int a = 0; a < n_nodes; ++a)
                for (unsigned int i = 0; i < 3; ++i)
                  d[i] += ((a >> k) & 1 ? 0.25 : -0.25) * p[a][i];
              const double h2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
              r2 += (k == cell_axis[c] ? c_axial2 : c_trans2) / h2;
            }
          rate2 = std::max(rate2, r2);
        }
      rate2                = Utilities::MPI::max(rate2, communicator);
      const double dt_bulk = 1. / std::sqrt(rate2);
      return 1. / std::sqrt(1. / (dt_bulk * dt_bulk) +
                            1. / (contact_time_step * contact_time_step));
    }


    template <class Law>
    double
    YarnModel<Law>::compute_forces(const Projectile &projectile,
                                   const double dt)
    {
      displacement.update_ghost_values();
      force              = 0.;
      const bool failure = shared.yarn.failure;
      double energy      = 0.;

      for (unsigned int c = 0; c < cell_index.size(); ++c)
        {
          if (cell_failed[c])
            continue;
          const unsigned int *dofs = &cell_dofs[c * n_cell_dofs];
          const double *grad       = &cell_grads[c * grad_size];
          const double *JxW        = &cell_JxW[c * n_q];
          double u[n_cell_dofs], f[n_cell_dofs];
          for (unsigned int k = 0; k < n_cell_dofs; ++k)
            u[k] = displacement.local_element(dofs[k]);
          const CellResult r       = integrate(law, u, grad, JxW, f);
          const double cell_energy = r.energy;
          cell_log_stretch[c]      = r.max_elongation;
          cell_mean_log_stretch[c] = r.sum_elongation / n_q;
          cell_compaction[c]       = r.max_compaction;
          if (failure && r.max_elongation > failure_log_stretch)
            {
              // The cell breaks: it carries no force from now on, and its
              // elastic energy is released (counted as dissipated).
              cell_failed[c] = 1;
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
              cell_failed[c] = 1;
              if (std::isfinite(cell_energy))
                dissipated += cell_energy;
              continue;
            }
          energy += cell_energy;
          for (unsigned int k = 0; k < n_cell_dofs; ++k)
            force.local_element(dofs[k]) -= f[k];
        }
      force.compress(VectorOperation::add);
      elastic_energy = energy;

      // Penalty contact of the surface nodes with the rigid cylinder.
      const auto &contact = parameters.contact;
      const double R      = projectile.radius();
      const double yc     = projectile.axis_position();
      const double vp     = projectile.velocity();
      double reaction = 0., penalty_energy = 0.;
      for (unsigned int k = 0; k < contact_nodes.size(); ++k)
        {
          const auto &node = nodes[contact_nodes[k]];
          const double px =
            reference_coordinate[node[0]] + displacement.local_element(node[0]);
          const double py =
            reference_coordinate[node[1]] + displacement.local_element(node[1]);
          const double dx = px, dy = py - yc;
          const double dist2 = dx * dx + dy * dy;
          if (dist2 >= R * R)
            continue;
          const double dist = std::sqrt(dist2);
          const double gap  = R - dist;
          const double nx = dx / dist, ny = dy / dist;
          const double stiffness = contact.penalty * contact_area[k];
          // Relative velocity of the node with respect to the cylinder.
          const double rvx = velocity.local_element(node[0]);
          const double rvy = velocity.local_element(node[1]) - vp;
          const double rvz = velocity.local_element(node[2]);
          const double vn  = rvx * nx + rvy * ny;
          double fn        = stiffness * gap;
          if (contact.damping_ratio > 0.)
            {
              const double c = 2. * contact.damping_ratio *
                               std::sqrt(contact_mass[k] * stiffness);
              const double fd = std::max(-c * vn, -fn);
              fn += fd;
              dissipated += -fd * vn * dt;
            }
          double ft[3] = {0., 0., 0.};
          if (contact.friction > 0.)
            {
              const double vt[3] = {rvx - vn * nx, rvy - vn * ny, rvz};
              const double speed =
                std::sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
              // Coulomb's law, explicit: the friction force never exceeds
              // the one that stops the slip within the step (m |v_t| / dt),
              // so that sticking nodes do not chatter.
              const double limit = contact_mass[k] * speed / dt;
              const double scale =
                speed > 0. ? -std::min(contact.friction * fn, limit) / speed
                           : 0.;
              for (unsigned int d = 0; d < 3; ++d)
                ft[d] = scale * vt[d];
              dissipated +=
                -(ft[0] * vt[0] + ft[1] * vt[1] + ft[2] * vt[2]) * dt;
            }
          force.local_element(node[0]) += fn * nx + ft[0];
          force.local_element(node[1]) += fn * ny + ft[1];
          force.local_element(node[2]) += ft[2];
          reaction -= fn * ny + ft[1];
          penalty_energy += 0.5 * stiffness * gap * gap;
        }
      contact_energy = penalty_energy;
      return symmetry * Utilities::MPI::sum(reaction, communicator);
    }


    template <class Law>
    void
    YarnModel<Law>::kick(const double dt)
    {
      const unsigned int n  = velocity.locally_owned_size();
      double *const v       = velocity.begin();
      const double *const f = force.begin();
      const double *const m = inverse_mass.begin();
      for (unsigned int i = 0; i < n; ++i)
        v[i] += dt * f[i] * m[i];
    }


    template <class Law>
    void
    YarnModel<Law>::drift(const double dt)
    {
      displacement.zero_out_ghost_values();
      const unsigned int n  = displacement.locally_owned_size();
      double *const u       = displacement.begin();
      const double *const v = velocity.begin();
      for (unsigned int i = 0; i < n; ++i)
        u[i] += dt * v[i];
    }


    template <class Law>
    Observables
    YarnModel<Law>::observables() const
    {
      Observables o;
      double kinetic = 0.;
      {
        const unsigned int n  = velocity.locally_owned_size();
        const double *const v = velocity.begin();
        const double *const m = lumped_mass.begin();
        for (unsigned int i = 0; i < n; ++i)
          kinetic += 0.5 * m[i] * v[i] * v[i];
      }
      double local[4] = {kinetic, elastic_energy, contact_energy, dissipated};
      double global[4];
      Utilities::MPI::sum(ArrayView<const double>(local, 4),
                          communicator,
                          ArrayView<double>(global, 4));
      o.kinetic_energy    = symmetry * global[0];
      o.elastic_energy    = symmetry * global[1];
      o.contact_energy    = symmetry * global[2];
      o.dissipated_energy = symmetry * global[3];

      double max_strain     = 0.;
      unsigned int n_failed = 0;
      for (unsigned int c = 0; c < cell_index.size(); ++c)
        if (cell_failed[c])
          ++n_failed;
        else
          max_strain = std::max(max_strain, std::expm1(cell_log_stretch[c]));
      o.max_strain = Utilities::MPI::max(max_strain, communicator);
      o.n_failed   = static_cast<unsigned long>(symmetry) *
                   Utilities::MPI::sum(n_failed, communicator);

      // Station profile: maxima in one array, sums in another.
      const unsigned int n = n_stations;
      // The station's strain is the volume average over the cells that
      // touch its node layer: the yarn's strain T / EA. Fibres of one
      // section are not coupled in longitudinal shear (G_LT = 0), so the
      // largest strain in a section can be well above it.
      std::vector<double> maxima(3 * n, -std::numeric_limits<double>::max());
      // Sums: |x|, count, strain x volume, volume, volume x z^2 and
      // deformed volume per station.
      std::vector<double> sums(6 * n, 0.);
      for (unsigned int c = 0; c < cell_index.size(); ++c)
        {
          if (cell_failed[c])
            continue;
          const unsigned int *dofs = &cell_dofs[c * n_cell_dofs];
          // The deformed cell's volume and its second moment of z (2x2x2
          // Gauss points of the trilinear map, vertices numbered
          // i + 2j + 4k): each of its two node layers gets them whole.
          double p[n_nodes][3];
          vertex_positions(c, p);
          double vz2 = 0., vol = 0.;
          const double g[2] = {0.5 - 0.5 / std::sqrt(3.),
                               0.5 + 0.5 / std::sqrt(3.)};
          for (unsigned int q = 0; q < 8; ++q)
            {
              const double xi[3] = {g[q & 1], g[(q >> 1) & 1], g[(q >> 2) & 1]};
              double J[3][3] = {}, zq = 0.;
              for (unsigned int a = 0; a < n_nodes; ++a)
                {
                  double N = 1., dN[3] = {1., 1., 1.};
                  for (unsigned int d = 0; d < 3; ++d)
                    {
                      const bool hi   = (a >> d) & 1;
                      const double nd = hi ? xi[d] : 1. - xi[d];
                      N *= nd;
                      for (unsigned int e = 0; e < 3; ++e)
                        dN[e] *= (e == d ? (hi ? 1. : -1.) : nd);
                    }
                  zq += N * p[a][2];
                  for (unsigned int i = 0; i < 3; ++i)
                    for (unsigned int e = 0; e < 3; ++e)
                      J[i][e] += p[a][i] * dN[e];
                }
              const double detJ =
                std::abs(J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                         J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]));
              vz2 += 0.125 * detJ * zq * zq;
              vol += 0.125 * detJ;
            }
          for (unsigned int a = 0; a < n_nodes; ++a)
            {
              const unsigned int s = static_cast<unsigned int>(std::round(
                std::abs(reference_coordinate[dofs[3 * a]]) / station_spacing));
              // Each cell has four vertices on each of its two layers.
              sums[2 * n + s] +=
                0.25 * cell_volume[c] * std::expm1(cell_mean_log_stretch[c]);
              sums[3 * n + s] += 0.25 * cell_volume[c];
              sums[4 * n + s] += 0.25 * vz2;
              sums[5 * n + s] += 0.25 * vol;
            }
        }
      for (unsigned int k = 0; k < nodes.size(); ++k)
        {
          const auto &node     = nodes[k];
          const unsigned int s = node_station[k];
          const double x =
            reference_coordinate[node[0]] + displacement.local_element(node[0]);
          const double z =
            reference_coordinate[node[2]] + displacement.local_element(node[2]);
          maxima[s] = std::max(maxima[s], -displacement.local_element(node[1]));
          maxima[n + s]     = std::max(maxima[n + s], z);
          maxima[2 * n + s] = std::max(maxima[2 * n + s], -z);
          sums[s] += std::abs(x);
          sums[n + s] += 1.;
        }
      Utilities::MPI::max(maxima, communicator, maxima);
      Utilities::MPI::sum(sums, communicator, sums);

      const bool quarter =
        shared.general.symmetry == YarnImpact::Parameters::Symmetry::quarter;
      Analysis::StationProfile profile;
      profile.resize(n);
      for (unsigned int s = 0; s < n; ++s)
        {
          profile.position[s] = sums[s] / std::max(sums[n + s], 1.);
          profile.axial_strain[s] =
            sums[2 * n + s] / std::max(sums[3 * n + s], 1e-300);
          profile.deflection[s] = maxima[s];
          profile.width[s] =
            quarter ? 2. * maxima[n + s] : maxima[n + s] + maxima[2 * n + s];
          profile.rms_width[s] =
            4. * std::sqrt(sums[4 * n + s] / std::max(sums[5 * n + s], 1e-300));
        }
      if (initial_width[0] == 0.)
        const_cast<std::vector<double> &>(initial_width) = profile.width;
      profile.initial_width = initial_width;

      o.fronts = Analysis::measure_wave_fronts(profile, shared.wave_fronts);
      return o;
    }


    template <class Law>
    bool
    YarnModel<Law>::yarn_cut_through() const
    {
      std::vector<unsigned int> failed(n_layers, 0);
      bool any = false;
      for (unsigned int c = 0; c < cell_index.size(); ++c)
        if (cell_failed[c])
          {
            failed[std::min(cell_layer[c], n_layers - 1)] += 1;
            any = true;
          }
      if (!Utilities::MPI::logical_or(any, communicator))
        return false;
      Utilities::MPI::sum(failed, communicator, failed);
      for (const unsigned int n : failed)
        if (n >= cells_per_layer)
          return true;
      return false;
    }


    template <class Law>
    AxialProperties
    YarnModel<Law>::axial_properties() const
    {
      AxialProperties a;
      a.density = law.density;
      // The discretised section (a polygon inside the ellipse).
      a.area           = total_mass / (law.density * shared.yarn.length);
      a.modulus        = law.axial_modulus();
      const Law copy   = law;
      a.nominal_stress = [copy](const double e) {
        return copy.uniaxial_nominal_stress(e);
      };
      return a;
    }


    template <class Law>
    std::string
    YarnModel<Law>::write_snapshot(const std::string &directory,
                                   const unsigned int index,
                                   const double) const
    {
      displacement.update_ghost_values();
      velocity.update_ghost_values();
      const unsigned int n_cells  = tria.n_active_cells();
      const char *names[]         = {"I_e",
                                     "I_tc",
                                     "I_td",
                                     "longitudinal_strain",
                                     "cauchy_xx",
                                     "cauchy_yy",
                                     "cauchy_zz",
                                     "cauchy_xy",
                                     "cauchy_xz",
                                     "cauchy_yz",
                                     "failed",
                                     "mpi_rank"};
      const unsigned int n_fields = sizeof(names) / sizeof(names[0]);
      std::vector<Vector<float>> fields(n_fields, Vector<float>(n_cells));
      const float rank = Utilities::MPI::this_mpi_process(communicator);
      for (unsigned int c = 0; c < cell_index.size(); ++c)
        {
          const unsigned int id    = cell_index[c];
          const unsigned int *dofs = &cell_dofs[c * n_cell_dofs];
          double u[n_cell_dofs];
          for (unsigned int k = 0; k < n_cell_dofs; ++k)
            u[k] = displacement.local_element(dofs[k]);
          double sums[10] = {};
          for (unsigned int q = 0; q < n_q; ++q)
            {
              Matrix3 F, P;
              double g[n_nodes * 3];
              for (unsigned int a = 0; a < n_nodes; ++a)
                for (unsigned int d = 0; d < 3; ++d)
                  g[3 * a + d] = gradient(&cell_grads[c * grad_size], q, a, d);
              deformation_gradient(u, g, F);
              Invariants inv;
              law.stress(F, P, inv);
              inv = charmetant_invariants(F);
              // Cauchy stress sigma = P F^T / J.
              const double J = internal::determinant(F);
              double sigma[9];
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = 0; j < 3; ++j)
                  sigma[3 * i + j] =
                    (P[3 * i] * F[3 * j] + P[3 * i + 1] * F[3 * j + 1] +
                     P[3 * i + 2] * F[3 * j + 2]) /
                    J;
              const double values[10] = {inv.elongation,
                                         inv.compaction,
                                         inv.distortion,
                                         0.,
                                         sigma[0],
                                         sigma[4],
                                         sigma[8],
                                         sigma[1],
                                         sigma[2],
                                         sigma[5]};
              for (unsigned int k = 0; k < 10; ++k)
                sums[k] += values[k] / n_q;
            }
          if (cell_failed[c])
            for (unsigned int k = 4; k < 10; ++k)
              sums[k] = 0.;
          sums[3] = std::expm1(cell_log_stretch[c]);
          for (unsigned int k = 0; k < 10; ++k)
            fields[k][id] = sums[k];
          fields[10][id] = cell_failed[c];
          fields[11][id] = rank;
        }

      DataOut<3> data_out;
      data_out.attach_dof_handler(dof_handler);
      const std::vector<
        DataComponentInterpretation::DataComponentInterpretation>
        vector_field(3,
                     DataComponentInterpretation::component_is_part_of_vector);
      data_out.add_data_vector(displacement,
                               std::vector<std::string>(3, "displacement"),
                               DataOut<3>::type_dof_data,
                               vector_field);
      data_out.add_data_vector(velocity,
                               std::vector<std::string>(3, "velocity"),
                               DataOut<3>::type_dof_data,
                               vector_field);
      for (unsigned int k = 0; k < n_fields; ++k)
        data_out.add_data_vector(fields[k],
                                 names[k],
                                 DataOut<3>::type_cell_data);
      // The geometry written is the deformed one.
      MappingQEulerian<3, VectorType> mapping(1, dof_handler, displacement);
      data_out.build_patches(mapping);
      return data_out.write_vtu_with_pvtu_record(directory + "/",
                                                 "fe",
                                                 index,
                                                 communicator,
                                                 4,
                                                 0);
    }


    void
    validate(const YarnImpact::Parameters::Shared &shared,
             const Parameters &parameters)
    {
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
      const double cells = 12. * std::pow(4., parameters.section_refinements) *
                           parameters.n_axial_cells *
                           std::pow(8., parameters.global_refinements);
      require(cells <= 5e7,
              "FE/Global refinements",
              "gives more than 50 million cells");
    }


    std::unique_ptr<ImpactModel>
    create_model(const YarnImpact::Parameters::Shared &shared,
                 const Parameters &parameters,
                 const MPI_Comm communicator)
    {
      validate(shared, parameters);
      const double density = parameters.density_from_fibres
                               ? shared.yarn.fibre_density *
                                   shared.yarn.fibre_area() /
                                   shared.yarn.section_area()
                               : parameters.density;
      if (parameters.law == LawType::charmetant)
        return std::make_unique<YarnModel<CharmetantLaw>>(
          shared,
          parameters,
          CharmetantLaw(parameters.charmetant, density),
          communicator);
      return std::make_unique<YarnModel<LinearTransverselyIsotropicLaw>>(
        shared,
        parameters,
        LinearTransverselyIsotropicLaw(parameters.linear, density),
        communicator);
    }
  } // namespace FE
} // namespace YarnImpact
