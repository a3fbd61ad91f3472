// The FE model's state in a checkpoint: what save_state() writes and
// load_state() reads (doc/user-guide.md, "Checkpoint and restart").

#include <yarn_impact/fe/constitutive_law.h>

#include <algorithm>
#include <vector>

#include "yarn_model.h"

namespace YarnImpact
{
  namespace FE
  {
    using namespace dealii;


    namespace
    {
      /** The owned entries of @p v. */
      void
      save_owned(Checkpoint::Writer &out,
                 const LinearAlgebra::distributed::Vector<double> &v)
      {
        out.put(
          std::vector<double>(v.begin(), v.begin() + v.locally_owned_size()));
      }

      /** Read the owned entries of @p v (the same partition). */
      void
      load_owned(Checkpoint::Reader &in,
                 LinearAlgebra::distributed::Vector<double> &v,
                 const char *what)
      {
        std::vector<double> owned(v.locally_owned_size());
        in.get_same_size(owned, what);
        std::copy(owned.begin(), owned.end(), v.begin());
      }
    } // namespace


    template <class Law>
    void
    YarnModel<Law>::save_state(Checkpoint::Writer &out) const
    {
      out.tag("fe dofs");
      save_owned(out, displacement);
      save_owned(out, velocity);
      save_owned(out, force);
      out.tag("fe cells");
      out.put(cells.failed);
      out.put(cells.damage);
      out.put(cells.kappa);
      out.put(cells.log_stretch);
      out.put(cells.mean_log_stretch);
      out.put(cells.compaction);
      out.put(cells.energy);
      out.put(cells.dissipated);
      out.tag("fe energies");
      out.put(projectile_speed);
      contact.save(out);
      if (!parameters.extra_forces.empty())
        out.tag("fe extra forces");
      for (const auto &forces : parameters.extra_forces)
        forces->save(out);
    }


    template <class Law>
    void
    YarnModel<Law>::load_state(Checkpoint::Reader &in)
    {
      in.tag("fe dofs");
      load_owned(in, displacement, "displacement of the owned dofs");
      load_owned(in, velocity, "velocity of the owned dofs");
      load_owned(in, force, "force of the owned dofs");
      // The ghosts as the step before the checkpoint left them.
      displacement.update_ghost_values();
      velocity.update_ghost_values();
      in.tag("fe cells");
      in.get_same_size(cells.failed, "failure state of the owned cells");
      in.get_same_size(cells.damage, "fibre damage of the owned cells");
      in.get_same_size(cells.kappa, "largest fibre stretch of the owned cells");
      in.get_same_size(cells.log_stretch, "fibre stretch of the owned cells");
      in.get_same_size(cells.mean_log_stretch,
                       "mean fibre stretch of the owned cells");
      in.get_same_size(cells.compaction, "compaction of the owned cells");
      in.get_same_size(cells.energy, "strain energy of the cells");
      in.get_same_size(cells.dissipated, "energy released by the cells");
      in.tag("fe energies");
      in.get(projectile_speed);
      contact.load(in);
      if (!parameters.extra_forces.empty())
        in.tag("fe extra forces");
      for (const auto &forces : parameters.extra_forces)
        forces->load(in);
      // The extra forces learn the cells failed before the checkpoint
      // again, as they did when each failed.
      failure_reported.assign(cells.failed.size(), 0);
      report_failed_cells(true);
    }


    // The members defined here, for each law.
#define YARN_IMPACT_FE_INSTANTIATE(type, Law, member)                   \
  template void YarnModel<Law>::save_state(Checkpoint::Writer &) const; \
  template void YarnModel<Law>::load_state(Checkpoint::Reader &);
    YARN_IMPACT_FE_FOR_EACH_LAW(YARN_IMPACT_FE_INSTANTIATE)
#undef YARN_IMPACT_FE_INSTANTIATE
  } // namespace FE
} // namespace YarnImpact
