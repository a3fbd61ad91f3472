// The fibre bars' observables (energies, strains, broken bars) and their
// checkpoint: collective where they sum over the fibres, in fibre order, so
// that they are the same on any number of ranks.

#include <yarn_impact/coupling/fibre_bars.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace YarnImpact
{
  namespace Coupling
  {
    using namespace dealii;


    double
    FibreBars::sum_over_fibres(std::vector<double> per_fibre) const
    {
      gather_fibres(per_fibre, 1);
      double sum = 0.;
      for (const double v : per_fibre)
        sum += v;
      return sum;
    }


    double
    FibreBars::kinetic_energy() const
    {
      std::vector<double> fibre_energy(n_fibres, 0.);
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        for (std::size_t i = index(f, 0); i < index(f + 1, 0); ++i)
          fibre_energy[f] += 0.5 * mass[i] * velocity[i] * velocity[i];
      return sum_over_fibres(std::move(fibre_energy));
    }


    double
    FibreBars::elastic_energy() const
    {
      // 1/2 k (l - h)^2 = 1/2 k (eps h)^2 per intact bar (a broken one
      // has eps = 0).
      std::vector<double> fibre_energy(n_fibres, 0.);
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        for (unsigned int j = 0; j + 1 < n_nodes; ++j)
          {
            double xi;
            const double d = strain[index(f, j)] * h;
            fibre_energy[f] += 0.5 * fibre_weight[f] *
                               cell_weight[cell_of(j, xi)] * stiffness * d * d;
          }
      return sum_over_fibres(std::move(fibre_energy));
    }


    double
    FibreBars::dissipated_energy() const
    {
      std::vector<double> fibre_energy(fibre_dissipated);
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        fibre_energy[f] += fibre_contact_dissipated[f];
      return sum_over_fibres(std::move(fibre_energy));
    }


    double
    FibreBars::largest_strain() const
    {
      double largest = 0.;
      for (std::size_t i = index(fibre_begin, 0); i < index(fibre_end, 0); ++i)
        largest = std::max(largest, strain[i]);
      return Utilities::MPI::max(largest, communicator);
    }


    unsigned long
    FibreBars::n_broken() const
    {
      return std::count(broken.begin(), broken.end(), 1);
    }


    std::vector<unsigned long>
    FibreBars::broken_per_millimetre() const
    {
      std::vector<unsigned long> count;
      for (unsigned int f = 0; f < n_fibres; ++f)
        for (unsigned int j = 0; j + 1 < n_nodes; ++j)
          if (broken[index(f, j)])
            {
              const unsigned int mm = (node_x(j) + 0.5 * h) * 1e3;
              if (count.size() <= mm)
                count.resize(mm + 1, 0);
              ++count[mm];
            }
      return count;
    }


    std::vector<FibreBreak>
    FibreBars::fibre_breaks(const MPI_Comm communicator) const
    {
      std::vector<FibreBreak> own;
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        for (unsigned int j = 0; j + 1 < n_nodes; ++j)
          if (broken[index(f, j)])
            {
              FibreBreak b;
              b.time  = break_time[index(f, j)];
              b.fibre = f;
              b.x     = (mirrored ? -0.5 : 0.5) * (node_x(j) + node_x(j + 1));
              b.y     = fibre_y[f];
              b.z     = fibre_z[f];
              own.push_back(b);
            }
      return gather_fibre_breaks(own, "bars", communicator);
    }


    bool
    FibreBars::fibre_broken(const unsigned int f) const
    {
      const auto b = broken.begin() + index(f, 0);
      return std::find(b, b + n_nodes, 1) != b + n_nodes;
    }


    std::vector<double>
    FibreBars::largest_strains() const
    {
      // Each fibre's largest strain of the intact bars j - 1 and j at each
      // layer's node j (0 where both are broken), as the DEM's station
      // profile takes the largest over its fibres.
      std::vector<double> layer_strain(std::size_t(n_fibres) * n_layers, 0.);
      for (unsigned int f = fibre_begin; f < fibre_end; ++f)
        for (unsigned int k = 0; k < n_layers; ++k)
          {
            const unsigned int j = k * bars_per_cell;
            double largest       = 0.;
            for (unsigned int b = (j > 0 ? j - 1 : 0);
                 b <= j && b + 1 < n_nodes;
                 ++b)
              if (!broken[index(f, b)])
                largest = std::max(largest, strain[index(f, b)]);
            layer_strain[std::size_t(f) * n_layers + k] = largest;
          }
      gather_fibres(layer_strain, n_layers);
      std::vector<double> largest(n_layers, 0.);
      for (unsigned int k = 0; k < n_layers; ++k)
        for (unsigned int f = 0; f < n_fibres; ++f)
          largest[k] =
            std::max(largest[k], layer_strain[std::size_t(f) * n_layers + k]);
      return largest;
    }


    void
    FibreBars::save_state(Checkpoint::Writer &out) const
    {
      // Every fibre's state, as one rank would hold it, so that a run may
      // go on with another number of ranks.
      auto gathered = [this](std::vector<double> values,
                             const unsigned int per_fibre) {
        gather_fibres(values, per_fibre);
        return values;
      };
      out.tag("fibre bars");
      out.put(gathered(displacement, n_nodes));
      out.put(gathered(velocity, n_nodes));
      out.put(gathered(force, n_nodes));
      out.put(gathered(strain, n_nodes));
      out.put(broken);
      out.put(gathered(break_time, n_nodes));
      out.put(time);
      out.put(gathered(fibre_dissipated, 1));
      out.put(gathered(fibre_contact_dissipated, 1));
      std::vector<double> history = gathered(contact_history, 3 * n_nodes);
      out.put(history);
      std::vector<std::uint8_t> touched(touching);
      gather_fibres(touched, n_nodes);
      out.put(touched);
    }


    void
    FibreBars::load_state(Checkpoint::Reader &in)
    {
      in.tag("fibre bars");
      in.get_same_size(displacement, "fibre bars' displacements");
      in.get_same_size(velocity, "fibre bars' velocities");
      in.get_same_size(force, "fibre bars' forces");
      in.get_same_size(strain, "fibre bars' strains");
      in.get_same_size(broken, "fibre bars' failure states");
      in.get_same_size(break_time, "fibre bars' break times");
      in.get(time);
      in.get_same_size(fibre_dissipated, "fibre bars' released energies");
      in.get_same_size(fibre_contact_dissipated,
                       "fibre bars' contact dissipation");
      in.get_same_size(contact_history, "fibre bars' contact histories");
      in.get_same_size(touching, "fibre bars' contact states");
    }


    std::size_t
    FibreBars::memory_consumption() const
    {
      return displacement.size() * (9 * sizeof(double) + 2) +
             (node_state.size() + node_force.size()) * sizeof(double) +
             (fibre_record.size() + layer_axial.size()) * sizeof(double) +
             n_fibres * (4 * sizeof(unsigned int) + 7 * sizeof(double)) +
             projection.size() * sizeof(double);
    }
  } // namespace Coupling
} // namespace YarnImpact
