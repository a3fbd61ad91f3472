// The yarn-yarn contact (Fabric::YarnContact, doc/fe-model.md section 8.4)
// gives the same forces on any number of MPI ranks: the lateral surfaces
// of a 2 x 2 woven patch (Fabric::WovenPatch), their nodes free lumped
// masses (no internal forces: the contact alone), each yarn's nodes sent
// towards the fabric's mid-plane at 40 m/s and along the yarn at 5 m/s, so
// that the crossings collide with friction, are stepped by velocity Verlet
// on the communicator's ranks, nodes owned round-robin (node i by rank
// i mod n: every contact then spans ranks), side by side with the same
// contact on one rank owning every node. Every step, every owned node's
// force is compared bit for bit with the one-rank contact's, and so are
// the contact energy and the dissipated work. And the one-rank contact's
// forces are those of a contact with a skin 40 times longer, whose lists
// hold every contact by far: the short lists miss none. And a contact
// restarted at step 180 from the distributed one's checkpoint (save, load)
// gives the same forces and dissipation from then on. One expected
// output for 1 and 2 ranks.

#include <yarn_impact/fabric/woven_patch.h>
#include <yarn_impact/fabric/yarn_contact.h>

#include <deal.II/base/mpi.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numeric>

using namespace YarnImpact;

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm comm        = MPI_COMM_WORLD;
  const unsigned int rank    = dealii::Utilities::MPI::this_mpi_process(comm);
  const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  const char *yes_no[]       = {"no", "yes"};

  const Fabric::WovenPatch patch{Fabric::WovenPatchGeometry()};
  dealii::Triangulation<3> mesh;
  patch.create_mesh(mesh);
  const auto s =
    Fabric::make_contact_surface(mesh, 1440., {Fabric::BoundaryIds::lateral});
  const unsigned int n = s.n_nodes();

  Fabric::YarnContactParameters prm;
  prm.skin = 10e-6; // small: the lists are rebuilt often
  std::vector<unsigned int> all(n), mine;
  std::iota(all.begin(), all.end(), 0);
  for (unsigned int i = rank; i < n; i += n_ranks)
    mine.push_back(i);
  Fabric::YarnContact serial(prm, s, all, MPI_COMM_SELF);
  // Lists far longer than needed, rarely rebuilt: if the short lists of
  // the 10 um skin missed a contact, the forces would differ.
  Fabric::YarnContactParameters wide_prm = prm;
  wide_prm.skin                          = 0.4e-3;
  Fabric::YarnContact wide(wide_prm, s, all, MPI_COMM_SELF);
  Fabric::YarnContact parallel(prm, s, mine, comm);
  const double dt = 0.5 * serial.stable_time_step();

  std::vector<double> x(3 * n), v(3 * n), f(3 * n, 0.);
  for (unsigned int i = 0; i < n; ++i)
    {
      const bool warp = patch.is_warp(s.node_yarn[i]);
      for (unsigned int d = 0; d < 3; ++d)
        x[3 * i + d] = s.reference[i][d];
      v[3 * i]     = warp ? 5. : 0.;
      v[3 * i + 1] = s.reference[i][1] > 0. ? -40. : 40.;
      v[3 * i + 2] = warp ? 0. : 5.;
    }
  const auto owned_part = [&](const std::vector<double> &all_values) {
    std::vector<double> part(3 * mine.size());
    for (unsigned int k = 0; k < mine.size(); ++k)
      for (unsigned int d = 0; d < 3; ++d)
        part[3 * k + d] = all_values[3 * mine[k] + d];
    return part;
  };

  unsigned int different = 0, missed = 0, most = 0, after_restart = 0;
  std::unique_ptr<Fabric::YarnContact> restarted;
  unsigned int touching_at_restart = 0;
  double largest = 0., energy = 0.;
  const unsigned int steps = 600, restart_step = 180;
  for (unsigned int step = 0; step <= steps; ++step)
    {
      if (step > 0)
        for (unsigned int i = 0; i < 3 * n; ++i)
          {
            v[i] += 0.5 * dt * f[i] / s.mass[i / 3];
            x[i] += dt * v[i];
          }
      f.assign(3 * n, 0.);
      serial.add_forces(x, v, dt, f);
      // At step 180, among 32 touching contacts, a contact restarted
      // from the distributed one's checkpoint: from then on, the same
      // forces bit for bit.
      if (step == restart_step)
        {
          touching_at_restart = parallel.n_touching();
          Checkpoint::Writer out;
          parallel.save(out);
          restarted = std::make_unique<Fabric::YarnContact>(prm, s, mine, comm);
          Checkpoint::Reader in("memory", out.contents());
          restarted->load(in);
        }
      std::vector<double> g(3 * mine.size(), 0.), h(3 * n, 0.);
      wide.add_forces(x, v, dt, h);
      missed += std::memcmp(h.data(), f.data(), f.size() * sizeof(double)) != 0;
      parallel.add_forces(owned_part(x), owned_part(v), dt, g);
      const std::vector<double> expected = owned_part(f);
      if (restarted)
        {
          std::vector<double> r(3 * mine.size(), 0.);
          restarted->add_forces(owned_part(x), owned_part(v), dt, r);
          after_restart +=
            std::memcmp(r.data(), g.data(), g.size() * sizeof(double)) != 0;
          after_restart += restarted->dissipated() != parallel.dissipated();
        }
      different +=
        std::memcmp(g.data(), expected.data(), g.size() * sizeof(double)) != 0;
      for (const double value : f)
        largest = std::max(largest, std::abs(value));
      const double e_serial = serial.energy(), e_parallel = parallel.energy();
      const double w_serial   = serial.dissipated();
      const double w_parallel = parallel.dissipated();
      different += e_serial != e_parallel || w_serial != w_parallel;
      energy = std::max(energy, e_serial);
      most   = std::max(most, serial.n_touching());
      if (step > 0)
        for (unsigned int i = 0; i < 3 * n; ++i)
          v[i] += 0.5 * dt * f[i] / s.mass[i / 3];
    }
  different     = dealii::Utilities::MPI::sum(different, comm);
  after_restart = dealii::Utilities::MPI::sum(after_restart, comm);
  if (rank == 0)
    {
      std::printf("woven patch 2 x 2: %u surface nodes, %zu faces; %u steps "
                  "of %.4e s\n",
                  n,
                  s.faces.size(),
                  steps,
                  dt);
      std::printf("up to %u contacts; largest nodal force %.3e N; largest "
                  "contact energy %.3e J; dissipated %.3e J; %u rebuilds\n",
                  most,
                  largest,
                  energy,
                  serial.dissipated(),
                  serial.n_rebuilds());
      std::printf("forces the same bit for bit with a skin of 0.4 mm (%u "
                  "rebuilds): %s\n",
                  wide.n_rebuilds(),
                  yes_no[missed == 0]);
      std::printf("restarted from a checkpoint at step %u (%u contacts "
                  "touching): the same forces and dissipation bit for bit: "
                  "%s\n",
                  restart_step,
                  touching_at_restart,
                  yes_no[after_restart == 0]);
      std::printf("forces, energy and dissipation the same bit for bit as "
                  "on one rank: %s\n",
                  yes_no[different == 0]);
    }
  return 0;
}
