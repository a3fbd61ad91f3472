#include <yarn_impact/core/parameter_tools.h>
#include <yarn_impact/dem/packing.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <tuple>

namespace YarnImpact
{
  namespace DEM
  {
    FibreCentres
    hexagonal_packing(const unsigned int n,
                      const double d,
                      const double a_y,
                      const double a_z,
                      const double max_scale,
                      const bool symmetric_z)
    {
      const double h = 0.5 * std::sqrt(3.) * d; // row distance
      // Enough rows and columns to hold the ellipse enlarged by max_scale.
      const int rows = static_cast<int>(std::ceil(max_scale * a_y / h)) + 2;
      const int cols = static_cast<int>(std::ceil(max_scale * a_z / d)) + 2;

      struct Site
      {
        double rho, y, z;
      };
      std::vector<Site> sites;
      for (int j = -rows; j <= rows; ++j)
        for (int i = -cols; i <= cols; ++i)
          {
            const double y = j * h;
            const double z = (i + 0.5 * (std::abs(j) % 2)) * d;
            const double rho =
              std::sqrt((y / a_y) * (y / a_y) + (z / a_z) * (z / a_z));
            if (rho <= max_scale * (1. + 1e-12))
              sites.push_back({rho, y, z});
          }
      // Closest first; ties ordered so that mirror images (+-y, +-z) are
      // adjacent, which keeps the selection symmetric whenever it can be.
      std::sort(sites.begin(), sites.end(), [](const Site &a, const Site &b) {
        return std::make_tuple(a.rho, std::abs(a.y), std::abs(a.z), a.y, a.z) <
               std::make_tuple(b.rho, std::abs(b.y), std::abs(b.z), b.y, b.z);
      });
      if (sites.size() < n)
        {
          std::ostringstream s;
          s << "= " << n << ": only " << sites.size() << " fibres of diameter "
            << d
            << " m fit in a hexagonal packing inside the yarn's ellipse "
               "enlarged by DEM/Maximum packing scale = "
            << max_scale;
          Parameters::require(false, "Yarn/Number of fibres", s.str());
        }
      // With symmetric_z, take the closest sites, but never one half of a
      // mirror pair
      // (y, -z), (y, z): when one slot is left, the next site on z = 0 fills
      // it, so that the layout stays symmetric about z = 0 (quarter
      // symmetry) whenever such a site exists.
      FibreCentres result;
      double rho_max  = 0.;
      const auto take = [&](const Site &site) {
        result.y.push_back(site.y);
        result.z.push_back(site.z);
        rho_max = std::max(rho_max, site.rho);
      };
      for (std::size_t k = 0;
           symmetric_z && k < sites.size() && result.size() < n;
           ++k)
        {
          const Site &site = sites[k];
          if (site.z == 0.)
            take(site);
          else if (site.z < 0. && k + 1 < sites.size() &&
                   sites[k + 1].y == site.y && sites[k + 1].z == -site.z)
            {
              if (n - result.size() >= 2)
                {
                  take(site);
                  take(sites[k + 1]);
                }
              ++k;
            }
        }
      if (result.size() < n)
        {
          // No symmetric choice: the n closest sites.
          result  = FibreCentres();
          rho_max = 0.;
          for (unsigned int k = 0; k < n; ++k)
            take(sites[k]);
        }
      result.scale = std::max(1., rho_max);
      return result;
    }


    FibreCentres
    read_fibre_file(const std::string &file,
                    const unsigned int n,
                    const double d,
                    const double a_y,
                    const double a_z,
                    const double max_scale)
    {
      const std::string name = "DEM/Fibre file";
      std::ifstream in(file);
      Parameters::require(static_cast<bool>(in),
                          name,
                          "= '" + file + "' cannot be opened");
      FibreCentres result;
      std::vector<unsigned int> line_of;
      std::string line;
      unsigned int line_number = 0;
      while (std::getline(in, line))
        {
          ++line_number;
          const auto hash = line.find('#');
          if (hash != std::string::npos)
            line.erase(hash);
          if (line.find_first_not_of(" \t\r") == std::string::npos)
            continue;
          std::istringstream s(line);
          double y, z;
          std::string rest;
          const bool ok = static_cast<bool>(s >> y >> z) && !(s >> rest) &&
                          std::isfinite(y) && std::isfinite(z);
          std::string shown = line;
          while (!shown.empty() &&
                 (shown.back() == '\r' || shown.back() == ' '))
            shown.pop_back();
          Parameters::require(ok,
                              name,
                              "= '" + file + "': line " +
                                std::to_string(line_number) +
                                ": expected two numbers 'y z' in metres, "
                                "got '" +
                                shown + "'");
          result.y.push_back(y);
          result.z.push_back(z);
          line_of.push_back(line_number);
        }
      Parameters::require(result.size() == n,
                          name,
                          "= '" + file + "' holds " +
                            std::to_string(result.size()) +
                            " fibre centres but Yarn/Number of fibres = " +
                            std::to_string(n));
      double scale = 1.;
      for (unsigned int k = 0; k < n; ++k)
        {
          const double r = std::sqrt(std::pow(result.y[k] / a_y, 2) +
                                     std::pow(result.z[k] / a_z, 2));
          if (r > max_scale * (1. + 1e-12))
            {
              std::ostringstream s;
              s << "= '" << file << "': the fibre on line " << line_of[k]
                << " lies " << r << " times as far out as the yarn's "
                << "elliptical section (more than DEM/Maximum packing scale "
                << "= " << max_scale
                << "); the centres must be in metres, inside the "
                   "ellipse of Yarn/Thickness and Width semi-axis";
              Parameters::require(false, name, s.str());
            }
          scale = std::max(scale, r);
        }
      result.scale = scale;
      for (unsigned int a = 0; a < n; ++a)
        for (unsigned int b = a + 1; b < n; ++b)
          {
            const double dist =
              std::hypot(result.y[a] - result.y[b], result.z[a] - result.z[b]);
            if (dist < d * (1. - 1e-9))
              {
                std::ostringstream s;
                s << "= '" << file << "': the fibres on lines " << line_of[a]
                  << " and " << line_of[b] << " overlap (centre distance "
                  << dist << " m < Yarn/Fibre diameter = " << d << " m)";
                Parameters::require(false, name, s.str());
              }
          }
      return result;
    }


    double
    min_distance(const FibreCentres &c)
    {
      double m = std::numeric_limits<double>::infinity();
      for (unsigned int a = 0; a < c.size(); ++a)
        for (unsigned int b = a + 1; b < c.size(); ++b)
          m = std::min(m, std::hypot(c.y[a] - c.y[b], c.z[a] - c.z[b]));
      return m;
    }
  } // namespace DEM
} // namespace YarnImpact
