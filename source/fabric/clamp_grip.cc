// Clamps of finite grip on the clamped yarn ends (doc/fabric.md section
// 11): a spring to an anchor per end-section node, capped by Coulomb's law.

#include <yarn_impact/core/reproducible_sum.h>
#include <yarn_impact/fabric/clamp_grip.h>
#include <yarn_impact/fabric/yarn_contact.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

namespace YarnImpact
{
  namespace Fabric
  {
    ClampGrip::ClampGrip(const ClampGripParameters &parameters,
                         const dealii::Triangulation<3, 3> &mesh,
                         const unsigned int boundary_id,
                         const double density,
                         const double symmetry)
      : parameters(parameters)
      , symmetry(symmetry)
    {
      const ContactSurface s =
        make_contact_surface(mesh, density, {boundary_id});
      reference = s.reference;
      mass      = s.mass;

      // The yarn ends: the end sections, sets of faces joined by their
      // nodes (union-find; the yarns do not touch each other).
      std::vector<unsigned int> root(s.n_nodes());
      std::iota(root.begin(), root.end(), 0u);
      const auto find = [&root](unsigned int i) {
        while (root[i] != i)
          i = root[i] = root[root[i]];
        return i;
      };
      for (const auto &f : s.faces)
        for (unsigned int a = 1; a < 4; ++a)
          root[find(f[a])] = find(f[0]);
      std::map<unsigned int, unsigned int> end_index;
      end_of.resize(s.n_nodes());
      for (unsigned int n = 0; n < s.n_nodes(); ++n)
        end_of[n] = end_index.emplace(find(n), end_index.size()).first->second;
      n_ends = end_index.size();

      // Each end's area, doubled for each symmetry plane that cuts it.
      double size = 0.;
      for (unsigned int n = 0; n < s.n_nodes(); ++n)
        size = std::max(size, std::sqrt(s.area[n]));
      const double tol = 1e-9 * size;
      std::vector<double> end_area(n_ends, 0.);
      std::vector<std::array<bool, 2>> cut(n_ends, {{false, false}});
      for (unsigned int n = 0; n < s.n_nodes(); ++n)
        {
          end_area[end_of[n]] += s.area[n];
          if (parameters.mirror_x && std::abs(s.reference[n][0]) < tol)
            cut[end_of[n]][0] = true;
          if (parameters.mirror_z && std::abs(s.reference[n][2]) < tol)
            cut[end_of[n]][1] = true;
        }
      // A cut end is one of the whole patch's; an end the planes do not
      // cut stands for its mirror images too.
      end_copies.resize(n_ends);
      for (unsigned int e = 0; e < n_ends; ++e)
        {
          const double cuts = (cut[e][0] ? 2. : 1.) * (cut[e][1] ? 2. : 1.);
          end_area[e] *= cuts;
          end_copies[e] = static_cast<unsigned int>(symmetry / cuts + 0.5);
        }

      // A node's lumped mass is rho A_n h / 2 on a flat end cell of
      // length h: E A_n / h = E rho A_n^2 / (2 m_n).
      share.resize(s.n_nodes());
      unit_stiffness.resize(s.n_nodes());
      for (unsigned int n = 0; n < s.n_nodes(); ++n)
        {
          share[n] = s.area[n] / end_area[end_of[n]];
          unit_stiffness[n] =
            density * s.area[n] * s.area[n] / (2. * s.mass[n]);
        }
    }


    void
    ClampGrip::set_axial_modulus(const double modulus)
    {
      axial_modulus = modulus;
    }


    std::vector<unsigned int>
    ClampGrip::setup(const std::vector<double> &x_reference,
                     const MPI_Comm communicator)
    {
      this->communicator = communicator;
      std::vector<unsigned int> nodes;
      owned.clear();
      k.clear();
      cap.clear();
      anchor.clear();
      for (const auto &[n, i] : match_surface_nodes(reference, x_reference))
        {
          owned.push_back(n);
          nodes.push_back(i);
          k.push_back(parameters.stiffness > 0.
                        ? parameters.stiffness * share[n]
                        : axial_modulus * unit_stiffness[n]);
          cap.push_back(parameters.pull_out_force * share[n]);
          for (unsigned int d = 0; d < 3; ++d)
            anchor.push_back(reference[n][d]);
        }
      node_energy.assign(owned.size(), 0.);
      node_dissipated.assign(owned.size(), 0.);
      // Every gripped node must be owned by exactly one rank.
      unsigned long n_found = owned.size();
      MPI_Allreduce(MPI_IN_PLACE,
                    &n_found,
                    1,
                    MPI_UNSIGNED_LONG,
                    MPI_SUM,
                    communicator);
      if (n_found != reference.size())
        throw std::logic_error("ClampGrip: " + std::to_string(n_found) +
                               " of the " + std::to_string(reference.size()) +
                               " gripped nodes found on the ranks");
      return nodes;
    }


    void
    ClampGrip::add_forces(const std::vector<double> &x,
                          const std::vector<double> &,
                          const double,
                          std::vector<double> &force)
    {
      for (unsigned int i = 0; i < owned.size(); ++i)
        {
          double s[3];
          for (unsigned int d = 0; d < 3; ++d)
            s[d] = x[3 * i + d] - anchor[3 * i + d];
          // The jaws press along y: in the fabric's plane (x, z) the
          // spring is capped by Coulomb's law, along y it is not.
          const double length = std::hypot(s[0], s[2]);
          const double limit  = cap[i] / k[i];
          if (length > limit)
            {
              // The anchor follows the node, the spring stays at its cap,
              // and the cap's work on the slip is dissipated.
              const double slip  = length - limit;
              const double scale = limit / length;
              for (const unsigned int d : {0u, 2u})
                {
                  anchor[3 * i + d] += slip * s[d] / length;
                  s[d] *= scale;
                }
              node_dissipated[i] += cap[i] * slip;
            }
          double stretch2 = 0.;
          for (unsigned int d = 0; d < 3; ++d)
            {
              force[3 * i + d] -= k[i] * s[d];
              stretch2 += s[d] * s[d];
            }
          node_energy[i] = 0.5 * k[i] * stretch2;
        }
    }


    double
    ClampGrip::largest_slip() const
    {
      double slip = 0.;
      for (unsigned int i = 0; i < owned.size(); ++i)
        slip = std::max(slip, anchor_slip(i));
      MPI_Allreduce(MPI_IN_PLACE, &slip, 1, MPI_DOUBLE, MPI_MAX, communicator);
      return slip;
    }


    unsigned int
    ClampGrip::n_slipping_ends() const
    {
      std::vector<int> slipping(n_ends, 0);
      for (unsigned int i = 0; i < owned.size(); ++i)
        if (anchor_slip(i) > 1e-3 * cap[i] / k[i])
          slipping[end_of[owned[i]]] = end_copies[end_of[owned[i]]];
      MPI_Allreduce(MPI_IN_PLACE,
                    slipping.data(),
                    n_ends,
                    MPI_INT,
                    MPI_MAX,
                    communicator);
      return std::accumulate(slipping.begin(), slipping.end(), 0u);
    }


    double
    ClampGrip::anchor_slip(const unsigned int i) const
    {
      const unsigned int n = owned[i];
      return std::hypot(anchor[3 * i] - reference[n][0],
                        anchor[3 * i + 2] - reference[n][2]);
    }


    double
    ClampGrip::stable_time_step() const
    {
      // A node of mass m on its spring alone: 2 sqrt(m / k). The whole
      // mesh's nodes, so that every rank finds the same step.
      double dt = std::numeric_limits<double>::max();
      for (unsigned int n = 0; n < reference.size(); ++n)
        {
          const double kn = parameters.stiffness > 0.
                              ? parameters.stiffness * share[n]
                              : axial_modulus * unit_stiffness[n];
          dt              = std::min(dt, 2. * std::sqrt(mass[n] / kn));
        }
      return dt;
    }


    double
    ClampGrip::whole_patch_sum(const std::vector<double> &terms) const
    {
      ReproducibleSum sum(1);
      for (const double e : terms)
        sum.add(0, e);
      return symmetry * sum.sum(communicator)[0];
    }


    double
    ClampGrip::energy() const
    {
      return whole_patch_sum(node_energy);
    }


    double
    ClampGrip::dissipated() const
    {
      return whole_patch_sum(node_dissipated);
    }


    void
    ClampGrip::save(Checkpoint::Writer &out) const
    {
      out.put(anchor);
      out.put(node_energy);
      out.put(node_dissipated);
    }


    void
    ClampGrip::load(Checkpoint::Reader &in)
    {
      in.get_same_size(anchor, "clamp grip anchors");
      in.get_same_size(node_energy, "clamp grip energies");
      in.get_same_size(node_dissipated, "clamp grip dissipation");
    }


    std::string
    ClampGrip::report() const
    {
      double k_end = parameters.stiffness;
      if (!(k_end > 0.))
        {
          // The default stiffness of the first whole end.
          std::vector<double> sum(n_ends, 0.), area(n_ends, 0.);
          for (unsigned int n = 0; n < reference.size(); ++n)
            {
              sum[end_of[n]] += axial_modulus * unit_stiffness[n];
              area[end_of[n]] += share[n];
            }
          k_end = 0.;
          for (unsigned int e = 0; e < n_ends; ++e)
            k_end = std::max(k_end, sum[e] / area[e]);
        }
      std::ostringstream s;
      s << "[fabric] clamp grip: "
        << std::accumulate(end_copies.begin(), end_copies.end(), 0u)
        << " yarn ends of the patch (" << reference.size()
        << " nodes meshed); pull-out force " << parameters.pull_out_force
        << " N and stiffness " << k_end << " N/m a yarn end; stable step alone "
        << stable_time_step() * 1e9 << " ns\n";
      return s.str();
    }
  } // namespace Fabric
} // namespace YarnImpact
