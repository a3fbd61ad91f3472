#include <yarn_impact/core/output_file.h>
#include <yarn_impact/core/reproducible_sum.h>
#include <yarn_impact/fe/constitutive_law.h>
#include <yarn_impact/mechanics/kinematics.h>

#include <deal.II/base/mpi.h>
#include <deal.II/fe/mapping_q_eulerian.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "yarn_model.h"

namespace YarnImpact
{
  namespace FE
  {
    using namespace dealii;


    namespace
    {
      /**
       * deal.II's DataOut whose patches can be reflected x -> -x after
       * build_patches(): a part built as the mirror image of the yarn it
       * stands for (FE::Parameters::mirrored) is written where it is.
       */
      class ReflectedDataOut : public DataOut<3>
      {
      public:
        /** Negate the patches' x coordinates and their data rows
         * @p odd_rows (the components odd under the reflection: x of a
         * vector, the xy and xz shear stresses) [-], and reverse each
         * patch's first reference direction, so that its cells keep a
         * positive orientation in the file. */
        void
        reflect_x(const std::vector<unsigned int> &odd_rows)
        {
          for (auto &patch : patches)
            {
              for (auto &vertex : patch.vertices)
                vertex[0] = -vertex[0];
              std::vector<unsigned int> rows = odd_rows;
              // Curved patches carry their points' coordinates as the
              // last three rows.
              if (patch.points_are_available)
                rows.push_back(patch.data.n_rows() - 3);
              for (const unsigned int r : rows)
                for (unsigned int c = 0; c < patch.data.n_cols(); ++c)
                  patch.data(r, c) = -patch.data(r, c);
              // Vertices and points are lexicographic, the first
              // reference direction fastest.
              for (unsigned int v = 0; v < 8; v += 2)
                std::swap(patch.vertices[v], patch.vertices[v + 1]);
              const unsigned int n = patch.n_subdivisions + 1;
              for (unsigned int line = 0; line < n * n; ++line)
                for (unsigned int i = 0; i < n / 2; ++i)
                  for (unsigned int r = 0; r < patch.data.n_rows(); ++r)
                    std::swap(patch.data(r, line * n + i),
                              patch.data(r, line * n + n - 1 - i));
            }
        }
      };
    } // namespace


    template <class Law>
    Observables
    YarnModel<Law>::observables() const
    {
      Observables o;
      // Every sum over the ranks is a ReproducibleSum of per-dof, per-cell
      // and per-node terms, so that the history does not depend on the
      // partition: sums 0-3 are the energies, then the station sums.
      const unsigned int n = n_stations;
      ReproducibleSum sums(4 + 6 * n);
      {
        const unsigned int n_owned = velocity.locally_owned_size();
        const double *const v      = velocity.begin();
        const double *const m      = lumped_mass.begin();
        for (unsigned int i = 0; i < n_owned; ++i)
          sums.add(0, 0.5 * m[i] * v[i] * v[i]);
      }
      // Broken: by the sudden criterion, or fibre damage 1 (a cell that
      // keeps only its transverse response); eroded apart; damaged: fibre
      // damage started (progressive), whatever became of the cell since.
      double max_strain      = 0.;
      unsigned int counts[3] = {0, 0, 0}; // failed, eroded, damaged
      for (const unsigned int c : owned_cells)
        {
          if (cells.damage[c] > 0.)
            ++counts[2];
          if (cells.failed[c] == CellState::eroded)
            ++counts[1];
          else if (cells.failed[c] == CellState::broken ||
                   cells.damage[c] >= 1.)
            ++counts[0];
          if (cells.failed[c] == CellState::active)
            {
              if (cells.damage[c] < 1.)
                max_strain =
                  std::max(max_strain, std::expm1(cells.log_stretch[c]));
              sums.add(1, cells.energy[c]);
            }
          // What the cell released: its energy when it broke or was eroded
          // (none if that was not finite), and its fibre-damage dissipation.
          sums.add(3, cells.dissipated[c]);
        }
      contact.add_energies(sums, 2);
      contact.add_dissipated(sums, 3);
      Utilities::MPI::sum(ArrayView<const unsigned int>(counts, 3),
                          communicator,
                          ArrayView<unsigned int>(counts, 3));
      o.max_strain      = Utilities::MPI::max(max_strain, communicator);
      const auto factor = static_cast<unsigned long>(symmetry);
      o.n_failed        = factor * counts[0];
      o.n_eroded        = factor * counts[1];
      o.n_damaged       = factor * counts[2];

      // Station profile: maxima in one array, sums in the other.
      // The station's strain is the volume average over the cells that
      // touch its node layer: the yarn's strain T / EA. Fibres of one
      // section are not coupled in longitudinal shear (G_LT = 0), so the
      // largest strain in a section can be well above it.
      std::vector<double> maxima(3 * n, -std::numeric_limits<double>::max());
      // Sums 4 + (0-5) n + s: |x|, count, strain x volume, volume,
      // volume x z^2 and deformed volume per station s.
      const unsigned int st = 4;
      for (const unsigned int c : owned_cells)
        {
          if (cells.failed[c])
            continue;
          const unsigned int *dofs = &cells.dofs[c * n_cell_dofs];
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
              const unsigned int s =
                station_of(reference_abscissa[dofs[3 * a]]);
              // Each cell has four vertices on each of its two layers.
              sums.add(st + 2 * n + s,
                       0.25 * cell_volume[c] *
                         std::expm1(cells.mean_log_stretch[c]));
              sums.add(st + 3 * n + s, 0.25 * cell_volume[c]);
              sums.add(st + 4 * n + s, 0.25 * vz2);
              sums.add(st + 5 * n + s, 0.25 * vol);
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
          sums.add(st + s, std::abs(x));
          sums.add(st + n + s, 1.);
        }
      Utilities::MPI::max(maxima, communicator, maxima);
      const std::vector<double> total = sums.sum(communicator);
      o.kinetic_energy                = symmetry * total[0];
      o.elastic_energy                = symmetry * total[1];
      o.contact_energy                = symmetry * total[2];
      o.dissipated_energy             = symmetry * total[3];
      {
        // Along -y, the impact direction; its own sum, which leaves the
        // energies' sums as they were.
        ReproducibleSum momentum(1);
        for (const auto &node : nodes)
          momentum.add(0,
                       -lumped_mass.local_element(node[1]) *
                         velocity.local_element(node[1]));
        o.momentum = symmetry * momentum.sum(communicator)[0];
      }
      if (parameters.n_energy_groups > 0)
        {
          // The terms of sums 0 and 1, by group.
          const unsigned int n_groups = parameters.n_energy_groups;
          ReproducibleSum groups(2 * n_groups);
          for (unsigned int k = 0; k < nodes.size(); ++k)
            for (const unsigned int i : nodes[k])
              groups.add(node_group[k],
                         0.5 * lumped_mass.local_element(i) *
                           velocity.local_element(i) *
                           velocity.local_element(i));
          for (const unsigned int c : owned_cells)
            if (cells.failed[c] == CellState::active)
              groups.add(n_groups + cell_group[c], cells.energy[c]);
          const std::vector<double> g = groups.sum(communicator);
          for (unsigned int i = 0; i < n_groups; ++i)
            {
              o.group_kinetic_energy.push_back(symmetry * g[i]);
              o.group_elastic_energy.push_back(symmetry * g[n_groups + i]);
            }
        }
      // The extra forces' energy and dissipation are the whole model's.
      for (const auto &forces : parameters.extra_forces)
        {
          o.contact_energy += forces->energy();
          o.dissipated_energy += forces->dissipated();
        }

      const bool quarter =
        shared.general.symmetry == YarnImpact::Parameters::Symmetry::quarter;
      StationProfile &profile = o.profile;
      profile.resize(n);
      for (unsigned int s = 0; s < n; ++s)
        {
          const double *const t = &total[st];
          profile.position[s]   = t[s] / std::max(t[n + s], 1.);
          profile.axial_strain[s] =
            t[2 * n + s] / std::max(t[3 * n + s], 1e-300);
          profile.deflection[s] = maxima[s];
          profile.width[s] =
            quarter ? 2. * maxima[n + s] : maxima[n + s] + maxima[2 * n + s];
          profile.rms_width[s] =
            4. * std::sqrt(t[4 * n + s] / std::max(t[5 * n + s], 1e-300));
        }
      if (initial_width[0] == 0.)
        const_cast<std::vector<double> &>(initial_width) = profile.width;
      profile.initial_width = initial_width;

      // Only a yarn with failed or eroded cells can be cut (and the check
      // is collective: the counts are the same on every rank).
      o.cut_through = (o.n_failed > 0 || o.n_eroded > 0) &&
                      !parameters.mesh.given() && yarn_cut_through();
      // The counts are the same on every rank: all or none count.
      if (parameters.mesh.section)
        o.extra_columns = {
          double(o.n_failed > 0 || o.n_eroded > 0 ? broken_yarns() : 0)};
      return o;
    }


    template <class Law>
    unsigned int
    YarnModel<Law>::broken_yarns() const
    {
      // Failed cells per section, summed over the ranks (integers: the
      // same on every rank whatever the partition).
      std::vector<unsigned int> failed(section_cells.size(), 0);
      for (const unsigned int c : owned_cells)
        if (cells.failed[c] != CellState::active || cells.damage[c] >= 1.)
          ++failed[cell_section[c]];
      Utilities::MPI::sum(failed, communicator, failed);
      const unsigned int per_yarn = parameters.mesh.sections_per_yarn;
      unsigned int broken         = 0;
      for (unsigned int y = 0; y < parameters.mesh.n_yarns; ++y)
        for (unsigned int k = y * per_yarn; k < (y + 1) * per_yarn; ++k)
          if (section_cells[k] > 0 && failed[k] == section_cells[k])
            {
              broken += parameters.mesh.yarn_copies.empty()
                          ? 1u
                          : parameters.mesh.yarn_copies[y];
              break;
            }
      return broken;
    }


    template <class Law>
    bool
    YarnModel<Law>::yarn_cut_through() const
    {
      std::vector<unsigned int> failed(n_layers, 0);
      bool any = false;
      // A layer is cut when none of its cells carries fibre stress:
      // broken, eroded, or fully damaged.
      for (const unsigned int c : owned_cells)
        if (cells.failed[c] != CellState::active || cells.damage[c] >= 1.)
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
                                     "mpi_rank",
                                     "damage"};
      const unsigned int n_fields = sizeof(names) / sizeof(names[0]);
      std::vector<Vector<float>> fields(n_fields, Vector<float>(n_cells));
      const float rank = Utilities::MPI::this_mpi_process(communicator);
      for (const unsigned int c : owned_cells)
        {
          const unsigned int id    = cell_index[c];
          const unsigned int *dofs = &cells.dofs[c * n_cell_dofs];
          double u[n_cell_dofs];
          for (unsigned int k = 0; k < n_cell_dofs; ++k)
            u[k] = displacement.local_element(dofs[k]);
          double sums[10] = {};
          for (unsigned int q = 0; q < n_q; ++q)
            {
              // F and P in the Gauss point's fibre frame when the cells
              // have frames: the invariants and the Cauchy stress
              // P F^T / J do not change.
              Mechanics::Matrix3 F, P;
              cell_deformation_gradient(cells, c, q, u, F);
              Mechanics::Invariants inv;
              law.stress(F, P, inv);
              if constexpr (Law::separable_fibre_term)
                if (cells.damage[c] > 0.)
                  {
                    // The stress the force loop uses: the damaged fibre
                    // part out (cell_kernel.cc).
                    const double I4 = F[0] * F[0] + F[3] * F[3] + F[6] * F[6];
                    const double a  = cells.damage[c] * law.axial_modulus() *
                                     inv.elongation / I4;
                    P[0] -= a * F[0];
                    P[3] -= a * F[3];
                    P[6] -= a * F[6];
                  }
              inv = Mechanics::invariants(F);
              // Cauchy stress sigma = P F^T / J.
              const double J = Mechanics::determinant(F);
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
          if (cells.failed[c])
            for (unsigned int k = 4; k < 10; ++k)
              sums[k] = 0.;
          sums[3] = std::expm1(cells.log_stretch[c]);
          for (unsigned int k = 0; k < 10; ++k)
            fields[k][id] = sums[k];
          fields[10][id] = cells.failed[c];
          fields[11][id] = rank;
          fields[12][id] = cells.damage[c];
        }

      ReflectedDataOut data_out;
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
      // On a given mesh of several yarns: each cell's yarn and its mean
      // fibre direction in the reference configuration.
      // Then the fields of GivenMesh::material_fields after `yarn`.
      std::vector<std::string> mesh_names = {"yarn",
                                             "fibre_direction_x",
                                             "fibre_direction_y",
                                             "fibre_direction_z"};
      const auto &material_fields         = parameters.mesh.material_fields;
      const unsigned int n_extra          = material_fields.size();
      for (unsigned int k = 0; k < n_extra; ++k)
        mesh_names.insert(mesh_names.begin() + 1 + k, material_fields[k].first);
      std::vector<Vector<float>> mesh_fields;
      if (parameters.mesh.given())
        {
          mesh_fields.assign(mesh_names.size(), Vector<float>(n_cells));
          std::vector<unsigned int> yarn(n_cells, 0);
          for (const auto &cell : tria.active_cell_iterators())
            yarn[cell->active_cell_index()] = cell->material_id();
          for (const unsigned int c : owned_cells)
            {
              const unsigned int id = cell_index[c];
              mesh_fields[0][id]    = yarn[id];
              for (unsigned int k = 0; k < n_extra; ++k)
                mesh_fields[1 + k][id] = material_fields[k].second(yarn[id]);
              for (unsigned int d = 0; d < 3; ++d)
                mesh_fields[1 + n_extra + d][id] = cell_fibre[c][d];
            }
          for (unsigned int k = 0; k < mesh_names.size(); ++k)
            data_out.add_data_vector(mesh_fields[k],
                                     mesh_names[k],
                                     DataOut<3>::type_cell_data);
        }
      // The geometry written is the deformed one.
      MappingQEulerian<3, VectorType> mapping(1, dof_handler, displacement);
      data_out.build_patches(mapping);
      // The rows of the data added above: displacement and velocity (3
      // each), then the cell fields in the order of names[].
      if (parameters.mirrored)
        data_out.reflect_x({0, 3, 6 + 7, 6 + 8});
      // The file names of deal.II's write_vtu_with_pvtu_record (one piece
      // per rank), each written whole or not at all.
      const unsigned int n_ranks =
        Utilities::MPI::n_mpi_processes(communicator);
      const unsigned int digits =
        Utilities::needed_digits(std::max(0, int(n_ranks) - 1));
      const std::string base =
        parameters.snapshot_name + "_" + Utilities::int_to_string(index, 4);
      const auto piece = [&](const unsigned int r) {
        return base + "." + Utilities::int_to_string(r, digits) + ".vtu";
      };
      const unsigned int this_rank =
        Utilities::MPI::this_mpi_process(communicator);
      AtomicFile vtu(directory + "/" + piece(this_rank));
      data_out.write_vtu(vtu.stream());
      vtu.commit();
      if (this_rank == 0)
        {
          std::vector<std::string> pieces;
          for (unsigned int r = 0; r < n_ranks; ++r)
            pieces.push_back(piece(r));
          AtomicFile record(directory + "/" + base + ".pvtu");
          data_out.write_pvtu_record(record.stream(), pieces);
          record.commit();
        }
      return base + ".pvtu";
    }


    // The members defined here, for each law (those of fe_model.cc are
    // instantiated by create_model()).
#define YARN_IMPACT_FE_INSTANTIATE(type, Law, member)                      \
  template Observables YarnModel<Law>::observables() const;                \
  template unsigned int YarnModel<Law>::broken_yarns() const;              \
  template std::string YarnModel<Law>::write_snapshot(const std::string &, \
                                                      const unsigned int,  \
                                                      const double) const;
    YARN_IMPACT_FE_FOR_EACH_LAW(YARN_IMPACT_FE_INSTANTIATE)
#undef YARN_IMPACT_FE_INSTANTIATE
  } // namespace FE
} // namespace YarnImpact
