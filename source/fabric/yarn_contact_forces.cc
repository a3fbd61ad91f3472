// The yarn contact as the FE model's extra forces in `Model = fabric`
// (doc/fabric.md section 1), and the cone's fronts it measures.

#include <yarn_impact/fabric/yarn_contact_forces.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace YarnImpact
{
  namespace Fabric
  {
    YarnContactForces::YarnContactForces(
      const YarnContactParameters &parameters,
      ContactSurface &&surface,
      std::shared_ptr<StepTimer> timer,
      const double symmetry,
      const unsigned int n_plies,
      std::function<unsigned int(unsigned int)> ply_of_yarn)
      : parameters(parameters)
      , surface(std::move(surface))
      , timer(std::move(timer))
      , symmetry(symmetry)
      , n_plies(n_plies)
      , ply_of_yarn(std::move(ply_of_yarn))
    {}

    std::vector<unsigned int>
    YarnContactForces::setup(const std::vector<double> &reference,
                             const MPI_Comm communicator)
    {
      std::vector<unsigned int> owned, nodes;
      for (const auto &f : match_surface_nodes(surface.reference, reference))
        {
          owned.push_back(f.first);
          nodes.push_back(f.second);
        }
      // Throws if some surface node is owned by no rank.
      contact.emplace(parameters, surface, owned, communicator);
      contact->set_timer(timer.get());
      this->communicator = communicator;
      for (const unsigned int n : owned)
        {
          for (unsigned int d = 0; d < 3; ++d)
            node_reference.push_back(surface.reference[n][d]);
          node_ply.push_back(ply_of_yarn(surface.node_yarn[n]));
        }
      return nodes;
    }

    void
    YarnContactForces::remove_cells(const std::vector<double> &cells,
                                    const bool restored)
    {
      contact->remove_cells(cells, restored);
    }

    void
    YarnContactForces::add_forces(const std::vector<double> &x,
                                  const std::vector<double> &v,
                                  const double dt,
                                  std::vector<double> &force)
    {
      // force holds only these forces (FE model): their sums over
      // the steps, for the check that they balance (remarks()).
      contact->add_forces(x, v, dt, force);
      positions = x;
      for (unsigned int i = 0; i < force.size(); ++i)
        {
          net[i % 3] += force[i];
          magnitude += std::abs(force[i]);
        }
    }

    std::string
    YarnContactForces::remarks() const
    {
      double sums[4] = {net[0], net[1], net[2], magnitude};
      MPI_Allreduce(MPI_IN_PLACE, sums, 4, MPI_DOUBLE, MPI_SUM, communicator);
      const double balance =
        std::sqrt(sums[0] * sums[0] + sums[1] * sums[1] + sums[2] * sums[2]) /
        std::max(sums[3], 1e-300);
      const unsigned int touching = contact->n_touching();
      const double energy = this->energy(), work = dissipated();
      std::ostringstream s;
      s << "yarn contact: " << touching << " touching contacts at the end, "
        << contact->n_rebuilds() << " candidate lists built, "
        << contact->n_removed_faces()
        << " faces of failed cells left out; energy " << energy * 1e3
        << " mJ, dissipated " << work * 1e3
        << " mJ; net force over the sum of |forces|, all steps, " << balance;
      return s.str();
    }

    std::vector<double>
    YarnContactForces::cone_fronts(const double x0,
                                   const double z0,
                                   const double threshold,
                                   const double band) const
    {
      std::vector<double> fronts(3 * n_plies, 0.);
      for (unsigned int k = 0; 3 * k < positions.size(); ++k)
        {
          const double *X = &node_reference[3 * k];
          if (X[1] - positions[3 * k + 1] <= threshold)
            continue;
          double *front   = &fronts[3 * node_ply[k]];
          const double dx = X[0] - x0, dz = X[2] - z0;
          if (std::abs(dz) < band)
            front[0] = std::max(front[0], std::abs(dx));
          if (std::abs(dx) < band)
            front[1] = std::max(front[1], std::abs(dz));
          if (std::min(std::abs(dx - dz), std::abs(dx + dz)) <
              std::sqrt(2.) * band)
            front[2] = std::max(front[2], std::hypot(dx, dz));
        }
      MPI_Allreduce(MPI_IN_PLACE,
                    fronts.data(),
                    fronts.size(),
                    MPI_DOUBLE,
                    MPI_MAX,
                    communicator);
      return fronts;
    }

    double
    YarnContactForces::stable_time_step() const
    {
      return contact->stable_time_step();
    }

    double
    YarnContactForces::energy() const
    {
      return symmetry * contact->energy();
    }

    double
    YarnContactForces::dissipated() const
    {
      return symmetry * contact->dissipated();
    }

    void
    YarnContactForces::save(Checkpoint::Writer &out) const
    {
      contact->save(out);
      out.put(std::vector<double>{net[0], net[1], net[2], magnitude});
    }

    void
    YarnContactForces::load(Checkpoint::Reader &in)
    {
      contact->load(in);
      std::vector<double> sums(4);
      in.get_same_size(sums, "sums of the yarn contact's forces");
      std::copy(sums.begin(), sums.begin() + 3, net);
      magnitude = sums[3];
    }

    std::string
    YarnContactForces::report() const
    {
      std::ostringstream s;
      s << "[fabric] yarn contact: " << surface.n_nodes() << " surface nodes, "
        << surface.faces.size() << " faces, penalty " << parameters.penalty
        << " Pa/m, friction " << parameters.friction
        << ": stable step of a node on its springs "
        << contact->stable_time_step() * 1e9 << " ns\n";
      return s.str();
    }
  } // namespace Fabric
} // namespace YarnImpact
