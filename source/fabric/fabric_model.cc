// `Model = fabric`: the FE model on the woven patch, with the contact of
// crossing yarns as its extra forces (doc/fabric.md). The fabric is a
// layer above the FE model (doc/architecture.md): it gives the FE model
// its mesh, fibre directions and clamps (FE::GivenMesh) and the
// YarnContact (FE::ExtraForces), and the FE model steps the yarns.

#include <yarn_impact/core/crimped_yarn.h>
#include <yarn_impact/fabric/fabric_model.h>
#include <yarn_impact/fabric/mesh_file.h>
#include <yarn_impact/fabric/step_timer.h>
#include <yarn_impact/fabric/yarn_contact_forces.h>
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
          std::shared_ptr<ClampGrip> clamp_grip,
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
          , clamp_grip(std::move(clamp_grip))
          , yarn_length(yarn_length)
          , primary(primary)
          , plies(plies)
          , n_plies(n_plies)
          , cone_threshold(cone_threshold)
          , spacing(spacing)
          , timer(std::move(timer))
          , communicator(communicator)
        {
          // The grip's default stiffness is the yarn's: its law's modulus.
          if (this->clamp_grip)
            this->clamp_grip->set_axial_modulus(fe->axial_properties().modulus);
        }

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
          // The whole fabric's fronts: the farthest of the plies'.
          const std::vector<double> fronts =
            yarn_contact->cone_fronts(shared->projectile.offset_x,
                                      shared->projectile.offset_z,
                                      cone_threshold,
                                      0.5 * spacing);
          for (unsigned int d = 0; d < 3; ++d)
            {
              double f = 0.;
              for (unsigned int p = 0; p < n_plies; ++p)
                f = std::max(f, fronts[3 * p + d]);
              o.extra_columns.push_back(1e3 * f);
            }
          o.extra_columns.push_back(broken);
          for (unsigned int p = 0; n_plies > 1 && p < n_plies; ++p)
            {
              o.extra_columns.push_back(1e3 *
                                        (kinetic[2 * p] + kinetic[2 * p + 1]));
              o.extra_columns.push_back(1e3 *
                                        (strain[2 * p] + strain[2 * p + 1]));
            }
          for (unsigned int i = 0; n_plies > 1 && i < fronts.size(); ++i)
            o.extra_columns.push_back(1e3 * fronts[i]);
          if (clamp_grip)
            {
              o.extra_columns.push_back(1e3 * clamp_grip->largest_slip());
              o.extra_columns.push_back(clamp_grip->n_slipping_ends());
              o.extra_columns.push_back(1e3 * clamp_grip->energy());
              o.extra_columns.push_back(1e3 * clamp_grip->dissipated());
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
         * energies [mJ], then each ply's cone fronts [mm], of which the
         * fabric's are the farthest; with a grip of finite force, the
         * largest slip of a node in its clamp [mm], the yarn ends that
         * slip [-], the grip's stored energy and its dissipation [mJ]
         * (inside the contact and dissipated energies of the common
         * columns). */
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
          for (unsigned int p = 0; n_plies > 1 && p < n_plies; ++p)
            for (const char *d : {"warp", "weft", "diagonal"})
              names.push_back("ply " + std::to_string(p) +
                              " cone front along " + d + " [mm]");
          if (clamp_grip)
            for (const char *name : {"clamp slip [mm]",
                                     "slipping yarn ends",
                                     "clamp grip energy [mJ]",
                                     "clamp grip dissipated energy [mJ]"})
              names.push_back(name);
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
        /** The yarn contact's (YarnContactForces::remarks()), the
         * clamps' slip with a grip of finite force, with the step's parts
         * (StepTimer::report()) under `Fabric/Step timing`. */
        std::string
        remarks() const override
        {
          std::string s = yarn_contact->remarks();
          if (clamp_grip)
            {
              std::ostringstream grip;
              grip << "\nclamp grip: " << clamp_grip->n_slipping_ends()
                   << " yarn ends slipped, the largest slip "
                   << 1e3 * clamp_grip->largest_slip() << " mm; dissipated "
                   << 1e3 * clamp_grip->dissipated() << " mJ";
              s += grip.str();
            }
          if (timer->enabled)
            s += "\n" + timer->report(communicator);
          return s;
        }

      private:
        // Before the model, which refers to it.
        const std::unique_ptr<YarnImpact::Parameters::Shared> shared;
        const std::unique_ptr<ImpactModel> fe;
        const std::shared_ptr<const YarnContactForces> yarn_contact;
        /** The clamps' grip; null where the clamps are rigid. */
        const std::shared_ptr<ClampGrip> clamp_grip;
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

      // A grip of finite force holds the clamped ends instead of the FE
      // model's clamps: their faces get the gripped ends' id.
      const bool grip = fabric.grip.pull_out_force > 0.;
      if (grip)
        {
          p.mesh.outside_projectile_contact = {gripped_end_boundary_id};
          p.mesh.create                     = [create =
                             p.mesh.create](dealii::Triangulation<3> &mesh) {
            create(mesh);
            for (const auto &face : mesh.active_face_iterators())
              if (face->at_boundary() &&
                  face->boundary_id() == BoundaryIds::end)
                face->set_boundary_id(gripped_end_boundary_id);
          };
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
        make_contact_surface(whole, density, yarn_contact_boundary_ids()),
        timer,
        YarnImpact::Parameters::symmetry_factor(shared.general.symmetry),
        g.n_plies,
        [patch, file = !fabric.mesh_file.empty()](const unsigned int id) {
          return file ? 0u : patch->ply(id);
        });
      p.extra_forces = {yarn_contact};
      std::shared_ptr<ClampGrip> clamp_grip;
      if (grip)
        {
          ClampGripParameters c = fabric.grip;
          c.mirror_x            = g.mirror_x;
          c.mirror_z            = g.mirror_z;
          clamp_grip =
            std::make_shared<ClampGrip>(c,
                                        whole,
                                        gripped_end_boundary_id,
                                        density,
                                        YarnImpact::Parameters::symmetry_factor(
                                          shared.general.symmetry));
          p.extra_forces.push_back(clamp_grip);
        }

      return std::make_unique<FabricModel>(std::move(copy),
                                           p,
                                           yarn_contact,
                                           clamp_grip,
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
