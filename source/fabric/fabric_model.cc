// `Model = fabric`: the FE model on the woven patch, with the contact of
// crossing yarns as its extra forces (doc/fabric.md). The fabric is a
// layer above the FE model (doc/architecture.md): it gives the FE model
// its mesh, fibre directions and clamps (FE::GivenMesh) and the
// YarnContact (FE::ExtraForces), and the FE model steps the yarns.

#include <yarn_impact/core/crimped_yarn.h>
#include <yarn_impact/fabric/fabric_model.h>
#include <yarn_impact/fabric/mesh_file.h>
#include <yarn_impact/fabric/step_timer.h>
#include <yarn_impact/fe/extra_forces.h>
#include <yarn_impact/fe/fe_model.h>

#include <deal.II/base/mpi.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

namespace YarnImpact
{
  namespace Fabric
  {
    namespace
    {
      /**
       * The YarnContact of the patch's crossing yarns as the FE model's
       * extra forces: its surface is the lateral surface of the whole
       * mesh, made on every rank before the FE model distributes its own
       * copy; each rank's nodes on it are the owned FE nodes found at the
       * same reference position (the two meshes are made by the same
       * code, so that their vertices are equal bit for bit).
       */
      class YarnContactForces : public FE::ExtraForces
      {
      public:
        /** @param surface the lateral surface of the whole patch
         * @param timer the fabric's step timer, which times the contact's
         * parts
         * @param symmetry the whole patch over the meshed part [-]
         * (1, 2, 4), by which energy() and dissipated() scale the
         * contact's to the whole patch's, as the FE model scales its own */
        YarnContactForces(const YarnContactParameters &parameters,
                          ContactSurface &&surface,
                          std::shared_ptr<StepTimer> timer,
                          const double symmetry)
          : parameters(parameters)
          , surface(std::move(surface))
          , timer(std::move(timer))
          , symmetry(symmetry)
        {}

        std::vector<unsigned int>
        setup(const std::vector<double> &reference,
              const MPI_Comm communicator) override
        {
          std::map<std::array<double, 3>, unsigned int> index;
          for (unsigned int n = 0; n < surface.n_nodes(); ++n)
            index.emplace(std::array<double, 3>{{surface.reference[n][0],
                                                 surface.reference[n][1],
                                                 surface.reference[n][2]}},
                          n);
          // (surface node, FE node), in the surface's order.
          std::vector<std::pair<unsigned int, unsigned int>> found;
          for (unsigned int k = 0; 3 * k < reference.size(); ++k)
            {
              const auto it = index.find({{reference[3 * k],
                                           reference[3 * k + 1],
                                           reference[3 * k + 2]}});
              if (it != index.end())
                found.emplace_back(it->second, k);
            }
          std::sort(found.begin(), found.end());
          std::vector<unsigned int> owned, nodes;
          for (const auto &f : found)
            {
              owned.push_back(f.first);
              nodes.push_back(f.second);
            }
          // Throws if some surface node is owned by no rank.
          contact.emplace(parameters, surface, owned, communicator);
          contact->set_timer(timer.get());
          this->communicator = communicator;
          for (const unsigned int n : owned)
            for (unsigned int d = 0; d < 3; ++d)
              node_reference.push_back(surface.reference[n][d]);
          return nodes;
        }

        void
        add_forces(const std::vector<double> &x,
                   const std::vector<double> &v,
                   const double dt,
                   std::vector<double> &force) override
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

        /** The contacts' state and the check of their forces' balance for
         * the run summary: the sum over the steps of the net force,
         * whose every contact's forces cancel to round-off, over the sum
         * of its components' magnitudes [-]. Collective. */
        std::string
        remarks() const
        {
          double sums[4] = {net[0], net[1], net[2], magnitude};
          MPI_Allreduce(MPI_IN_PLACE,
                        sums,
                        4,
                        MPI_DOUBLE,
                        MPI_SUM,
                        communicator);
          const double balance =
            std::sqrt(sums[0] * sums[0] + sums[1] * sums[1] +
                      sums[2] * sums[2]) /
            std::max(sums[3], 1e-300);
          const unsigned int touching = contact->n_touching();
          const double energy = this->energy(), work = dissipated();
          std::ostringstream s;
          s << "yarn contact: " << touching << " touching contacts at the end, "
            << contact->n_rebuilds() << " candidate lists built; energy "
            << energy * 1e3 << " mJ, dissipated " << work * 1e3
            << " mJ; net force over the sum of |forces|, all steps, "
            << balance;
          return s.str();
        }

        /**
         * The cone's (transverse) fronts [m] at the positions of the last
         * add_forces(): the largest reference distance from the impact
         * point (@p x0, @p z0) [m] of a surface node deflected along -y by
         * more than @p threshold [m], among the nodes within @p band [m]
         * of the line through the impact point along x (the warp yarns'
         * direction), along z (the weft yarns') and along the diagonals
         * x = +-z; 0 where none. Collective.
         */
        std::array<double, 3>
        cone_fronts(const double x0,
                    const double z0,
                    const double threshold,
                    const double band) const
        {
          std::array<double, 3> front = {{0., 0., 0.}};
          for (unsigned int k = 0; 3 * k < positions.size(); ++k)
            {
              const double *X = &node_reference[3 * k];
              if (X[1] - positions[3 * k + 1] <= threshold)
                continue;
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
                        front.data(),
                        3,
                        MPI_DOUBLE,
                        MPI_MAX,
                        communicator);
          return front;
        }

        double
        stable_time_step() const override
        {
          return contact->stable_time_step();
        }

        double
        energy() const override
        {
          return symmetry * contact->energy();
        }

        double
        dissipated() const override
        {
          return symmetry * contact->dissipated();
        }

        void
        save(Checkpoint::Writer &out) const override
        {
          contact->save(out);
          out.put(std::vector<double>{net[0], net[1], net[2], magnitude});
        }

        void
        load(Checkpoint::Reader &in) override
        {
          contact->load(in);
          std::vector<double> sums(4);
          in.get_same_size(sums, "sums of the yarn contact's forces");
          std::copy(sums.begin(), sums.begin() + 3, net);
          magnitude = sums[3];
        }

        std::string
        report() const override
        {
          std::ostringstream s;
          s << "[fabric] yarn contact: " << surface.n_nodes()
            << " surface nodes, " << surface.faces.size() << " faces, penalty "
            << parameters.penalty << " Pa/m, friction " << parameters.friction
            << ": stable step of a node on its springs "
            << contact->stable_time_step() * 1e9 << " ns\n";
          return s.str();
        }

      private:
        const YarnContactParameters parameters;
        const ContactSurface surface;
        const std::shared_ptr<StepTimer> timer;
        const double symmetry;
        std::optional<YarnContact> contact;
        MPI_Comm communicator = MPI_COMM_SELF;
        /** The reference positions [m] of this rank's nodes, 3 each, in
         * the order of add_forces(), and their positions [m] at the last
         * add_forces(). */
        std::vector<double> node_reference, positions;
        /** Sums over the steps of this rank's yarn-contact forces [N] and
         * of their components' magnitudes [N]. */
        double net[3] = {0., 0., 0.}, magnitude = 0.;
      };


      /**
       * The FE model of the patch under the name "fabric", with the copy
       * of the run's parameters it refers to, and the axial properties of
       * one of its yarns.
       */
      class FabricModel : public ImpactModel
      {
      public:
        /** @param yarn_length the length of all yarns' centrelines [m] */
        FabricModel(
          std::unique_ptr<YarnImpact::Parameters::Shared> &&shared_copy,
          const FE::Parameters &fe_parameters,
          std::shared_ptr<const YarnContactForces> yarn_contact,
          const double yarn_length,
          const std::string &primary,
          const std::string &plies,
          const unsigned int n_plies,
          const double cone_threshold,
          const double spacing,
          std::shared_ptr<StepTimer> timer,
          const MPI_Comm communicator)
          : shared(std::move(shared_copy))
          , fe(FE::create_model(*shared, fe_parameters, communicator))
          , yarn_contact(std::move(yarn_contact))
          , yarn_length(yarn_length)
          , primary(primary)
          , plies(plies)
          , n_plies(n_plies)
          , cone_threshold(cone_threshold)
          , spacing(spacing)
          , timer(std::move(timer))
          , communicator(communicator)
        {}

        std::string
        name() const override
        {
          return "fabric";
        }
        void
        setup(const Projectile &projectile, std::ostream &out) override
        {
          fe->setup(projectile, out);
          if (n_plies > 1)
            out << "[fabric] " << plies << "\n";
          out << "[fabric] primary yarns (under the projectile at the "
                 "start): "
              << primary << "\n";
        }
        double
        yarn_top() const override
        {
          return fe->yarn_top();
        }
        double
        stable_time_step() const override
        {
          StepTimer::Scope scope(timer.get(), StepTimer::stable_step);
          return fe->stable_time_step();
        }
        double
        compute_forces(const Projectile &projectile, const double dt) override
        {
          if (!timer->enabled)
            return fe->compute_forces(projectile, dt);
          // The FE's part: the call's time less the yarn contact's parts
          // timed inside it.
          const double contact_before = timer->yarn_contact_seconds();
          const double contact_cpu    = timer->yarn_contact_seconds(true);
          const auto start            = std::chrono::steady_clock::now();
          const double cpu_start      = StepTimer::thread_cpu_seconds();
          const double f              = fe->compute_forces(projectile, dt);
          const double elapsed        = std::chrono::duration<double>(
                                   std::chrono::steady_clock::now() - start)
                                   .count();
          const double cpu = StepTimer::thread_cpu_seconds() - cpu_start;
          timer->add(StepTimer::fe_forces,
                     elapsed - (timer->yarn_contact_seconds() - contact_before),
                     cpu - (timer->yarn_contact_seconds(true) - contact_cpu));
          timer->count_step();
          return f;
        }
        void
        kick(const double dt) override
        {
          StepTimer::Scope scope(timer.get(), StepTimer::integration);
          fe->kick(dt);
        }
        void
        drift(const double dt) override
        {
          StepTimer::Scope scope(timer.get(), StepTimer::integration);
          fe->drift(dt);
        }
        /** The FE's, with the fabric's own columns (extra_column_names()):
         * the energy groups are 2 p for the primary yarns of ply p, 2 p +
         * 1 for its secondary ones; the FE model's one column is the
         * broken yarns (FE::GivenMesh::section). */
        Observables
        observables() const override
        {
          StepTimer::Scope scope(timer.get(), StepTimer::observables);
          Observables o       = fe->observables();
          const double broken = o.extra_columns.at(0);
          o.extra_columns     = {o.momentum,
                                 1e3 * yarn_contact->energy(),
                                 1e3 * yarn_contact->dissipated()};
          const auto &kinetic = o.group_kinetic_energy;
          const auto &strain  = o.group_elastic_energy;
          for (unsigned int g = 0; g < 2; ++g)
            {
              // Over the plies, ply 0 first (alone with one ply).
              double k = kinetic[g], e = strain[g];
              for (unsigned int p = 1; p < n_plies; ++p)
                {
                  k += kinetic[2 * p + g];
                  e += strain[2 * p + g];
                }
              o.extra_columns.push_back(1e3 * k);
              o.extra_columns.push_back(1e3 * e);
            }
          for (const double f :
               yarn_contact->cone_fronts(shared->projectile.offset_x,
                                         shared->projectile.offset_z,
                                         cone_threshold,
                                         0.5 * spacing))
            o.extra_columns.push_back(1e3 * f);
          o.extra_columns.push_back(broken);
          for (unsigned int p = 0; n_plies > 1 && p < n_plies; ++p)
            {
              o.extra_columns.push_back(1e3 *
                                        (kinetic[2 * p] + kinetic[2 * p + 1]));
              o.extra_columns.push_back(1e3 *
                                        (strain[2 * p] + strain[2 * p + 1]));
            }
          return o;
        }
        /** The yarns' momentum along the impact direction, which with the
         * projectile's is conserved where no yarn end is clamped
         * (`Fabric/Clamped edges = none`); the yarn contact's stored
         * energy and dissipation (inside the contact and dissipated
         * energies of the common columns); the kinetic and strain energies
         * of the primary yarns (group 0 of primary_yarns()) and of the
         * secondary ones; the cone's fronts along x, z and the diagonals
         * (YarnContactForces::cone_fronts(), within half a spacing of
         * each line through the impact point); the broken yarns [-],
         * those with a section whose every cell has failed or been
         * eroded; with several plies, each ply's kinetic and strain
         * energies [mJ]. */
        std::vector<std::string>
        extra_column_names() const override
        {
          std::vector<std::string> names = {
            "yarn momentum [kg m/s]",
            "yarn contact energy [mJ]",
            "yarn contact dissipated energy [mJ]",
            "primary yarns kinetic energy [mJ]",
            "primary yarns strain energy [mJ]",
            "secondary yarns kinetic energy [mJ]",
            "secondary yarns strain energy [mJ]",
            "cone front along warp [mm]",
            "cone front along weft [mm]",
            "cone front along diagonal [mm]",
            "broken yarns"};
          for (unsigned int p = 0; n_plies > 1 && p < n_plies; ++p)
            for (const char *e : {"kinetic", "strain"})
              names.push_back("ply " + std::to_string(p) + " " + e +
                              " energy [mJ]");
          return names;
        }
        /** The FE's, with the area of one yarn's section: the patch's mass
         * over its density and its yarns' total length. */
        AxialProperties
        axial_properties() const override
        {
          AxialProperties a = fe->axial_properties();
          a.area            = fe->mass() / (a.density * yarn_length);
          return a;
        }
        double
        mass() const override
        {
          return fe->mass();
        }
        std::string
        write_snapshot(const std::string &directory,
                       const unsigned int index,
                       const double time) const override
        {
          StepTimer::Scope scope(timer.get(), StepTimer::output);
          return fe->write_snapshot(directory, index, time);
        }
        unsigned long
        n_elements() const override
        {
          return fe->n_elements();
        }

        /** The yarns' FE cells are eroded as a single yarn's. */
        bool
        erodes_cells() const override
        {
          return true;
        }

        /** A woven patch: the verification window's Smith quantities,
         * those of one yarn struck across, do not apply. */
        bool
        single_yarn() const override
        {
          return false;
        }
        void
        save_state(Checkpoint::Writer &out) const override
        {
          fe->save_state(out);
        }
        void
        load_state(Checkpoint::Reader &in) override
        {
          fe->load_state(in);
        }
        /** The yarn contact's (YarnContactForces::remarks()), with the
         * step's parts (StepTimer::report()) under `Fabric/Step
         * timing`. */
        std::string
        remarks() const override
        {
          std::string s = yarn_contact->remarks();
          if (timer->enabled)
            s += "\n" + timer->report(communicator);
          return s;
        }

      private:
        // Before the model, which refers to it.
        const std::unique_ptr<YarnImpact::Parameters::Shared> shared;
        const std::unique_ptr<ImpactModel> fe;
        const std::shared_ptr<const YarnContactForces> yarn_contact;
        const double yarn_length;
        /** The primary yarns' ids and the plies' heights, for the set-up
         * report. */
        const std::string primary, plies;
        /** Fabric/Plies [-]. */
        const unsigned int n_plies;
        /** Fabric/Cone deflection threshold [m], Fabric/Yarn spacing [m]. */
        const double cone_threshold, spacing;
        /** The step's parts (Fabric/Step timing); mutable through the
         * pointer: timing a const call changes no state of the model. */
        const std::shared_ptr<StepTimer> timer;
        const MPI_Comm communicator;
      };
    } // namespace


    std::unique_ptr<ImpactModel>
    create_fabric_model(const YarnImpact::Parameters::Shared &shared,
                        const FE::Parameters &fe,
                        const FabricParameters &fabric,
                        const MPI_Comm communicator)
    {
      WovenPatchGeometry g  = fabric.patch;
      g.thickness_semi_axis = shared.yarn.thickness_semi_axis;
      g.width_semi_axis     = shared.yarn.width_semi_axis;
      g.section_refinements = fe.section_refinements;
      // The symmetry planes (doc/fabric.md section 10): x = 0, and z = 0
      // with quarter; only the generated patch (validated).
      using YarnImpact::Parameters::Symmetry;
      g.mirror_x       = shared.general.symmetry != Symmetry::none;
      g.mirror_z       = shared.general.symmetry == Symmetry::quarter;
      const auto patch = std::make_shared<const WovenPatch>(g);

      // The stations go by x over the warp yarns' span (FE::GivenMesh).
      auto copy = std::make_unique<YarnImpact::Parameters::Shared>(shared);
      copy->yarn.length = g.n_weft * g.spacing;
      FE::Parameters p  = fe;
      p.n_axial_cells   = g.n_weft * g.cells_per_spacing;
      p.n_axial_cells += p.n_axial_cells % 2;
      p.crimp = FE::CrimpParameters();
      std::string ids, plies;
      double yarn_length = 0.;
      if (fabric.mesh_file.empty())
        yarn_length = use_patch(patch, shared.projectile, p, ids, plies);
      else
        {
          // The read mesh (doc/fabric.md section 8): one "ply", whatever
          // the file holds.
          g.n_plies = 1;
          const auto file =
            std::make_shared<const MeshFile>(fabric.mesh_file,
                                             fabric.orientation_file,
                                             g.clamp_warp_ends,
                                             g.clamp_weft_ends);
          yarn_length = use_mesh_file(file, shared.projectile, p, ids);
        }

      // The surface of the whole mesh, before the FE model distributes it.
      dealii::Triangulation<3> whole;
      p.mesh.create(whole);
      const double density = FE::with_fibre_data(*copy, p).density;
      const auto timer     = std::make_shared<StepTimer>(fabric.step_timing);
      YarnContactParameters contact = fabric.contact;
      contact.mirror_x              = g.mirror_x;
      contact.mirror_z              = g.mirror_z;
      const auto yarn_contact       = std::make_shared<YarnContactForces>(
        contact,
        make_contact_surface(whole, density, {BoundaryIds::lateral}),
        timer,
        YarnImpact::Parameters::symmetry_factor(shared.general.symmetry));
      p.extra_forces = yarn_contact;

      return std::make_unique<FabricModel>(std::move(copy),
                                           p,
                                           yarn_contact,
                                           yarn_length,
                                           ids,
                                           plies,
                                           g.n_plies,
                                           fabric.cone_threshold,
                                           g.spacing,
                                           timer,
                                           communicator);
    }
  } // namespace Fabric
} // namespace YarnImpact
