// Every contact law of the list (contact/contact_law.h), through the
// selector the models use: a sphere dropped on a flat while sliding along
// it, with damping and friction. The energy balance closes (kinetic +
// stored + dissipated = the initial energy), the tangential
// force never exceeds the law's Coulomb limit, the sphere leaves the flat
// again, and without damping and friction both laws give the same normal
// force (the physics they share).

#include <yarn_impact/contact/contact_law.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

using namespace YarnImpact;

namespace
{
  /** The constants of a 12 um Kevlar sphere on a steel flat (doc/dem.md
   * section 2 orders of magnitude), damping ratio 0.3, friction 0.2. */
  Contact::ContactConstants
  constants()
  {
    Contact::ContactConstants c;
    c.mass      = 1.9543e-12;
    c.stiffness = 3.99e5;
    c.damping   = Contact::critical_damping(0.3, c.mass, c.stiffness);
    c.tangential_stiffness = 2. / 7. * c.stiffness;
    c.friction             = 0.2;
    return c;
  }

  /** A sphere falling at 10 m/s onto the flat y = 0 while sliding along
   * it at 5 m/s (velocity Verlet, 50 steps per contact time). */
  template <class Law>
  void
  drop_and_slide(const char *name)
  {
    const Contact::ContactConstants c = constants();
    const Law law(c);
    const double m = c.mass, dt = 0.02 * std::sqrt(m / c.stiffness);
    double x[3] = {0., 1e-9, 0.}, v[3] = {4., -10., 3.}, f[3] = {0., 0., 0.};
    double history[3] = {0., 0., 0.}, dissipated = 0., stored = 0.;
    const double E0   = 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    double over_limit = 0.;
    bool touched = false, left = false;
    auto forces = [&]() {
      f[0] = f[1] = f[2] = 0.;
      stored             = 0.;
      const double delta = -x[1];
      if (delta <= 0.)
        {
          // A new contact starts without tangential history.
          for (double &h : history)
            h = 0.;
          return;
        }
      touched           = true;
      const double n[3] = {0., 1., 0.};
      Contact::contact_force(law, delta, n, v, dt, history, f, dissipated);
      const double ft = std::sqrt(f[0] * f[0] + f[2] * f[2]);
      over_limit =
        std::max(over_limit, ft - law.friction_limit(f[1]) * (1. + 1e-12));
      stored = law.energy(delta, history);
    };
    forces();
    for (unsigned int step = 0; step < 20000 && !left; ++step)
      {
        for (unsigned int d = 0; d < 3; ++d)
          {
            v[d] += 0.5 * dt * f[d] / m;
            x[d] += dt * v[d];
          }
        forces();
        for (unsigned int d = 0; d < 3; ++d)
          v[d] += 0.5 * dt * f[d] / m;
        left = touched && x[1] > 0. && v[1] > 0.;
      }
    const double K       = 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double balance = std::abs(K + stored + dissipated - E0) / E0;
    std::printf("%-16s leaves the flat: %s, friction within its limit: %s, "
                "energy balance within 1 %%: %s, dissipates: %s\n",
                name,
                left ? "yes" : "NO",
                over_limit <= 0. ? "yes" : "NO",
                balance < 1e-2 ? "yes" : "NO",
                dissipated > 0. ? "yes" : "NO");
  }

  /** Normal force of @p Law at a given overlap and approach speed,
   * without damping or friction [N]. */
  template <class Law>
  double
  elastic_normal_force()
  {
    Contact::ContactConstants c = constants();
    c.damping                   = 0.;
    c.friction                  = 0.;
    const Law law(c);
    double dissipated = 0.;
    return law.normal_force(1e-7, -3., 1e-9, dissipated);
  }
} // namespace

int
main()
{
  double reference = -1.;
  bool same        = true;
#define YARN_IMPACT_CHECK_LAW(value, Law, name)                          \
  Contact::with_contact_law(Contact::LawType::value, [&](auto tag) {     \
    using L = typename decltype(tag)::type;                              \
    drop_and_slide<L>(name);                                             \
    const double fn = elastic_normal_force<L>();                         \
    same            = same && (reference < 0. || fn == reference);       \
    reference       = fn;                                                \
  });                                                                    \
  std::printf("%-16s selected by its parameter value: %s\n",             \
              name,                                                      \
              Contact::law_type(name) == Contact::LawType::value ? "yes" \
                                                                 : "NO");
  YARN_IMPACT_CONTACT_FOR_EACH_LAW(YARN_IMPACT_CHECK_LAW)
#undef YARN_IMPACT_CHECK_LAW
  std::printf("laws selectable: %s\n", Contact::law_selection().c_str());
  std::printf("same elastic normal force in every law: %s\n",
              same ? "yes" : "NO");
  return 0;
}
