// The observables of the DEM impact model for the history: energies,
// failed trusses, strains, cut-through and the station profile (analysis
// measures the wave fronts on it).

#include <yarn_impact/core/reproducible_sum.h>
#include <yarn_impact/dem/contact_kernels.h>
#include <yarn_impact/dem/integration.h>
#include <yarn_impact/dem/observables.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace YarnImpact
{
  namespace DEM
  {
    namespace internal
    {
      namespace
      {
        constexpr double infinity = std::numeric_limits<double>::infinity();
      }


      ObservablesMeter::ObservablesMeter(
        const FibreChains &chains,
        const Decomposition &decomposition,
        const Spheres &spheres,
        const NeighbourLists &lists,
        const FibreContactLaw &fibre_law,
        const Contact::LawType projectile_law,
        const Contact::ContactConstants &projectile_constants)
        : chains(chains)
        , decomposition(decomposition)
        , spheres(spheres)
        , lists(lists)
        , fibre_law(fibre_law)
        , projectile_law(projectile_law)
        , projectile_constants(projectile_constants)
      {}


      void
      ObservablesMeter::record_initial_width()
      {
        const unsigned int nf = chains.nf, s_impact = chains.s_impact;
        const std::vector<double> &fibre_z0 = chains.fibre_z0;
        initial_width.assign(chains.n_prof, 0.);
        for (unsigned int s = decomposition.st_begin; s < decomposition.st_end;
             ++s)
          {
            double zmin = infinity, zmax = -infinity;
            for (unsigned int f = 0; f < nf; ++f)
              {
                zmin = std::min(zmin, fibre_z0[f]);
                zmax = std::max(zmax, fibre_z0[f]);
              }
            const unsigned int k = (s > s_impact ? s - s_impact : s_impact - s);
            initial_width[k]     = std::max(initial_width[k],
                                        chains.z_sym ? 2. * zmax : zmax - zmin);
          }
        dealii::Utilities::MPI::max(initial_width,
                                    decomposition.comm,
                                    initial_width);
      }


      Observables
      ObservablesMeter::measure(const ProjectileContactState &contact_at) const
      {
        const unsigned int nf = chains.nf, n_st = chains.n_st,
                           n_prof = chains.n_prof, s_impact = chains.s_impact;
        const unsigned int st_begin = decomposition.st_begin,
                           st_end   = decomposition.st_end;
        const unsigned int n_ranks  = decomposition.n_ranks;
        const MPI_Comm comm         = decomposition.comm;
        const double d = chains.d, L0 = chains.L0, truss_k = chains.truss_k,
                     sphere_mass = chains.sphere_mass, factor = chains.factor;
        const bool z_sym = chains.z_sym;
        const std::vector<double> &fibre_symmetry_weight =
          chains.fibre_symmetry_weight;
        const std::vector<double> &station_symmetry_weight =
          chains.station_symmetry_weight;
        const std::vector<double> &fibre_y0     = chains.fibre_y0;
        const std::vector<double> &pos          = spheres.pos;
        const double *x                         = pos.data();
        const std::vector<std::uint8_t> &broken = spheres.broken;
        const std::vector<double> &projectile_tangential_displacement =
          spheres.projectile_tangential_displacement;
        const std::vector<std::uint64_t> &proj_step = spheres.proj_step;
        const std::uint64_t step_count              = spheres.step_count;

        Observables o;
        // Reproducible sums: kinetic, elastic, contact, dissipated, failed,
        // the momentum along -y (each sum exact, so one more leaves the
        // others' bits as they were), then per profile station the second
        // moment of the fibre centres about z = 0 and its weight.
        enum : unsigned int
        {
          kinetic,
          elastic,
          contact,
          dissipated,
          failed,
          momentum,
          second_moment
        };
        ReproducibleSum sums(second_moment + 2 * n_prof);
        // Maxima: max strain, then the profile (strain, deflection, width,
        // position) of n_prof stations.
        auto &buf = profile_buffer;
        buf.assign(1 + 4 * n_prof + nf, -infinity);
        double *fibre_cut = buf.data() + 1 + 4 * n_prof;
        double *pstrain = buf.data() + 1, *pdefl = pstrain + n_prof,
               *pwidth = pdefl + n_prof, *ppos = pwidth + n_prof;

        for (unsigned int s = st_begin; s < st_end; ++s)
          {
            const unsigned int k = (s > s_impact ? s - s_impact : s_impact - s);
            double smax = -infinity, defl = -infinity, zmin = infinity,
                   zmax = -infinity, xsum = 0.;
            for (unsigned int f = 0; f < nf; ++f)
              {
                const std::size_t i = decomposition.local_index(s, f);
                const double m      = sphere_mass * fibre_symmetry_weight[f] *
                                 station_symmetry_weight[s] * chains.cw[s];
                double v[3], v2 = 0.;
                for (unsigned int c = 0; c < 3; ++c)
                  {
                    v[c] =
                      kicked_velocity(chains, decomposition, spheres, i, c);
                    v2 += v[c] * v[c];
                  }
                sums.add(kinetic, 0.5 * m * v2);
                sums.add(momentum, -m * v[1]);
                sums.add(dissipated, spheres.dissipated[i]);
                defl = std::max(defl, fibre_y0[f] - pos[3 * i + 1]);
                sums.add(second_moment + k,
                         fibre_symmetry_weight[f] * pos[3 * i + 2] *
                           pos[3 * i + 2]);
                sums.add(second_moment + n_prof + k, fibre_symmetry_weight[f]);
                zmin = std::min(zmin, pos[3 * i + 2]);
                zmax = std::max(zmax, pos[3 * i + 2]);
                xsum += std::abs(pos[3 * i]);
                // Truss to the next station (the last station uses the one
                // before it for the profile).
                if (s + 1 < n_st)
                  {
                    if (broken[i])
                      {
                        sums.add(failed, factor * fibre_symmetry_weight[f]);
                        fibre_cut[f] = 1.;
                      }
                    else
                      {
                        double l;
                        const double e = truss_strain(x, i, nf, L0, &l);
                        sums.add(elastic,
                                 0.5 * truss_k * fibre_symmetry_weight[f] *
                                   chains.tw[s] * (l - L0) * (l - L0));
                        smax = std::max(smax, e);
                      }
                  }
                else if (!broken[i - nf])
                  smax = std::max(smax, truss_strain(x, i - nf, nf, L0));
              }
            pstrain[k] = std::max(pstrain[k], smax);
            pdefl[k]   = std::max(pdefl[k], defl);
            pwidth[k]  = std::max(pwidth[k], z_sym ? 2. * zmax : zmax - zmin);
            ppos[k]    = std::max(ppos[k], xsum / nf);
            buf[0]     = std::max(buf[0], smax);
          }
        // Truss (st_begin - 1, st_begin) belongs to the rank on the left.

        // Contacts: the energy twins of the forces (contact_kernels.h),
        // weighted as the forces, each pair on the rank that owns its lower
        // sphere (the row of its list).
        for (const ListBlock &B : lists.blocks)
          {
            const std::uint32_t *pstart    = B.pstart.data();
            const std::vector<Pair> &pairs = B.pairs;
            const std::vector<double> &pair_tangential_displacement =
              B.pair_tangential_displacement;
            const std::vector<MirrorPair> &mpairs = B.mpairs;
            const std::vector<double> &mirror_tangential_displacement =
              B.mirror_tangential_displacement;
            for (std::size_t i = B.row_sphere_begin; i < B.row_sphere_end; ++i)
              for (std::uint32_t p = pstart[i - B.row_sphere_begin];
                   p < pstart[i - B.row_sphere_begin + 1];
                   ++p)
                if (pairs[p].w < 0.f && decomposition.owned(i))
                  {
                    const std::size_t j = pairs[p].j;
                    sums.add(contact,
                             -pairs[p].w *
                               pair_contact_energy(
                                 fibre_law,
                                 d,
                                 x + 3 * i,
                                 x + 3 * j,
                                 1.,
                                 1.,
                                 &pair_tangential_displacement[3 * p]));
                  }
            for (std::size_t p = 0; p < mpairs.size(); ++p)
              if (mpairs[p].active && decomposition.owned(mpairs[p].i))
                {
                  const std::size_t i = mpairs[p].i, j = mpairs[p].j;
                  const double sx = (mpairs[p].axes & 1) ? -1. : 1.,
                               sz = (mpairs[p].axes & 2) ? -1. : 1.;
                  sums.add(contact,
                           mpairs[p].w * (i == j ? 0.5 : 1.) *
                             pair_contact_energy(
                               fibre_law,
                               d,
                               x + 3 * i,
                               x + 3 * j,
                               sx,
                               sz,
                               &mirror_tangential_displacement[3 * p]));
                }
          }
        // Projectile contacts of the last force evaluation (the positions
        // have not moved since), by the law of the forces.
        Contact::with_contact_law(projectile_law, [&](auto tag) {
          using Law = typename decltype(tag)::type;
          const Law law(projectile_constants);
          for (std::size_t i = decomposition.own_b; i < decomposition.own_e;
               ++i)
            if (proj_step[i] == step_count && step_count > 0)
              {
                const unsigned int s = decomposition.station_of(i), f = i % nf;
                const double ex = pos[3 * i],
                             ey = pos[3 * i + 1] - contact_at.yc;
                const double delta =
                  std::max(0., contact_at.Rr - std::sqrt(ex * ex + ey * ey));
                sums.add(
                  contact,
                  fibre_symmetry_weight[f] * station_symmetry_weight[s] *
                    chains.cw[s] *
                    law.energy(delta,
                               &projectile_tangential_displacement[3 * i]));
              }
        });

        const std::vector<double> total = sums.sum(comm);
        if (n_ranks > 1)
          MPI_Allreduce(MPI_IN_PLACE,
                        buf.data(),
                        buf.size(),
                        MPI_DOUBLE,
                        MPI_MAX,
                        comm);
        o.kinetic_energy    = factor * total[kinetic];
        o.elastic_energy    = factor * total[elastic];
        o.contact_energy    = factor * total[contact];
        o.dissipated_energy = factor * total[dissipated];
        o.momentum          = factor * total[momentum];
        o.n_failed          = static_cast<unsigned long>(total[failed] + 0.5);
        o.max_strain        = std::max(0., buf[0]);

        StationProfile &profile = o.profile;
        profile.resize(n_prof);
        for (unsigned int k = 0; k < n_prof; ++k)
          {
            profile.position[k]      = ppos[k];
            profile.axial_strain[k]  = pstrain[k];
            profile.deflection[k]    = pdefl[k];
            profile.width[k]         = pwidth[k];
            profile.initial_width[k] = initial_width[k];
            profile.rms_width[k] =
              4. *
              std::sqrt(total[second_moment + k] /
                        std::max(total[second_moment + n_prof + k], 1e-300));
          }
        bool all_cut = nf > 0;
        for (unsigned int f = 0; f < nf; ++f)
          all_cut = all_cut && fibre_cut[f] > 0.;
        o.cut_through = all_cut;
        return o;
      }


      std::vector<FibreBreak>
      gather_fibre_breaks(const FibreChains &chains,
                          const Decomposition &decomposition,
                          const Spheres &spheres)
      {
        std::vector<FibreBreak> own;
        const unsigned int nf = chains.nf;
        const unsigned int end =
          std::min(decomposition.st_end, chains.n_st - 1);
        for (unsigned int s = decomposition.st_begin; s < end; ++s)
          for (unsigned int f = 0; f < nf; ++f)
            {
              const std::size_t i = decomposition.local_index(s, f);
              if (spheres.broken[i])
                {
                  FibreBreak b;
                  b.time  = spheres.break_time[i];
                  b.fibre = f;
                  b.x = 0.5 * (chains.station_x0[s] + chains.station_x0[s + 1]);
                  b.y = chains.fibre_y0[f];
                  b.z = chains.fibre_z0[f];
                  own.push_back(b);
                }
            }
        return YarnImpact::gather_fibre_breaks(own, "dem", decomposition.comm);
      }
    } // namespace internal
  }   // namespace DEM
} // namespace YarnImpact
