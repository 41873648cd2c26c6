#include "lattice/lattice_geometry.hpp"

#include <cmath>
#include <stdexcept>

namespace rupture {

namespace {
const double kSqrt3 = std::sqrt(3.0);
const double kSqrt2 = std::sqrt(2.0);
}  // namespace

LatticeKind latticeKind(const std::string& name) {
  if (name == "random") return LatticeKind::Random;
  if (name == "triangular") return LatticeKind::Triangular;
  if (name == "square") return LatticeKind::Square;
  if (name == "simple-cubic") return LatticeKind::SimpleCubic;
  if (name == "fcc") return LatticeKind::Fcc;
  throw std::invalid_argument("unknown lattice \"" + name + "\"");
}

std::string toString(LatticeKind kind) {
  switch (kind) {
    case LatticeKind::Random: return "random";
    case LatticeKind::Triangular: return "triangular";
    case LatticeKind::Square: return "square";
    case LatticeKind::SimpleCubic: return "simple-cubic";
    case LatticeKind::Fcc: return "fcc";
  }
  return "random";
}

int latticeDimension(LatticeKind kind) {
  switch (kind) {
    case LatticeKind::Triangular:
    case LatticeKind::Square: return 2;
    case LatticeKind::SimpleCubic:
    case LatticeKind::Fcc: return 3;
    case LatticeKind::Random: return 0;
  }
  return 0;
}

double siteMeasure(LatticeKind kind) {
  switch (kind) {
    case LatticeKind::Triangular: return 0.5 * kSqrt3;
    case LatticeKind::Square:
    case LatticeKind::SimpleCubic: return 1.0;
    case LatticeKind::Fcc: return 1.0 / kSqrt2;
    case LatticeKind::Random: break;
  }
  throw std::invalid_argument("siteMeasure: a random packing has no site measure");
}

std::vector<std::array<double, 3>> springOffsets(LatticeKind kind) {
  const double h = 1.0 / kSqrt2;  // fcc: (±1, ±1, 0)·a/2 with a = √2 l
  switch (kind) {
    case LatticeKind::Triangular: return {{1, 0, 0}, {0.5, 0.5 * kSqrt3, 0}, {-0.5, 0.5 * kSqrt3, 0}};
    case LatticeKind::Square: return {{1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, -1, 0}};
    case LatticeKind::SimpleCubic:
      return {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, -1, 0}, {1, 0, 1}, {1, 0, -1}, {0, 1, 1}, {0, 1, -1}};
    case LatticeKind::Fcc: return {{h, h, 0}, {h, -h, 0}, {h, 0, h}, {h, 0, -h}, {0, h, h}, {0, h, -h}};
    case LatticeKind::Random: break;
  }
  return {};
}

std::vector<std::array<double, 3>> latticeSites(LatticeKind kind, double l, const std::array<double, 3>& size) {
  std::vector<std::array<double, 3>> sites;
  const double m = 0.5 * l;  // half-spacing margin: sites at m, m + l, ... < size − m/2
  auto fits = [&](double c, double edge) { return c <= edge - 0.5 * m + 1e-12 * l; };
  switch (kind) {
    case LatticeKind::Triangular: {
      const double rowHeight = 0.5 * kSqrt3 * l;
      for (int row = 0; fits(m + row * rowHeight, size[1]); ++row) {
        const double shift = (row % 2) ? 0.5 * l : 0.0;
        for (int col = 0; fits(m + shift + col * l, size[0]); ++col)
          sites.push_back({m + shift + col * l, m + row * rowHeight, 0.0});
      }
      break;
    }
    case LatticeKind::Square:
      for (int jy = 0; fits(m + jy * l, size[1]); ++jy)
        for (int ix = 0; fits(m + ix * l, size[0]); ++ix) sites.push_back({m + ix * l, m + jy * l, 0.0});
      break;
    case LatticeKind::SimpleCubic:
      for (int kz = 0; fits(m + kz * l, size[2]); ++kz)
        for (int jy = 0; fits(m + jy * l, size[1]); ++jy)
          for (int ix = 0; fits(m + ix * l, size[0]); ++ix) sites.push_back({m + ix * l, m + jy * l, m + kz * l});
      break;
    case LatticeKind::Fcc: {
      // Conventional cubic cell a = √2 l: a cubic grid of step a/2 keeping sites with an even index sum.
      const double step = l / kSqrt2;
      for (int kz = 0; fits(m + kz * step, size[2]); ++kz)
        for (int jy = 0; fits(m + jy * step, size[1]); ++jy)
          for (int ix = 0; fits(m + ix * step, size[0]); ++ix)
            if ((ix + jy + kz) % 2 == 0) sites.push_back({m + ix * step, m + jy * step, m + kz * step});
      break;
    }
    case LatticeKind::Random: break;
  }
  return sites;
}

double springsCutPerArea(LatticeKind kind, double spacing, double thickness) {
  double crossing = 0;
  for (const auto& o : springOffsets(kind)) crossing += std::fabs(o[0]);
  const int d = latticeDimension(kind);
  // Per site: Σ|ξ_x|/l bonds cross a plane per lattice "column"; divide by the site measure.
  if (d == 2) return crossing / (siteMeasure(kind) * spacing * thickness);
  return crossing / (siteMeasure(kind) * spacing * spacing);
}

}  // namespace rupture
