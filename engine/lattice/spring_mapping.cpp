#include "lattice/spring_mapping.hpp"

#include <cmath>
#include <stdexcept>

namespace rupture {

PoissonRange poissonRange(LatticeKind lattice, bool born) {
  const double upper = lattice == LatticeKind::SimpleCubic ? 0.25 : 1.0 / 3.0;
  if (lattice == LatticeKind::Random) throw std::invalid_argument("poissonRange: lattice models need a regular lattice");
  return born ? PoissonRange{-1.0, upper, false} : PoissonRange{upper, upper, true};
}

SpringConstants springConstants(LatticeKind lattice, bool born, double E, double nu, double l, double t) {
  if (!born) nu = poissonRange(lattice, false).max;
  switch (lattice) {
    case LatticeKind::Triangular:
    case LatticeKind::Square: {
      const double r = (1.0 - 3.0 * nu) / (1.0 + nu);
      const double g = lattice == LatticeKind::Triangular ? 2.0 * std::sqrt(3.0) : 4.0;
      return {E * t * (3.0 + r) / (g * (1.0 + r)), born ? r : 0.0};
    }
    case LatticeKind::SimpleCubic:
      return {E * l / (5.0 * (1.0 - 2.0 * nu)), born ? (1.0 - 4.0 * nu) / (1.0 + nu) : 0.0};
    case LatticeKind::Fcc:
      return {E * l / (2.0 * std::sqrt(2.0) * (1.0 - 2.0 * nu)), born ? (1.0 - 3.0 * nu) / (1.0 + nu) : 0.0};
    case LatticeKind::Random: break;
  }
  throw std::invalid_argument("springConstants: lattice models need a regular lattice");
}

double familyStiffnessFactor(LatticeKind lattice, double restLength, double spacing) {
  return lattice == LatticeKind::Square && restLength > 1.2 * spacing ? 0.5 : 1.0;
}

LatticeElasticity latticeElasticity(LatticeKind lattice, double kn, double r, double l, double t) {
  switch (lattice) {
    case LatticeKind::Triangular: return {2.0 * std::sqrt(3.0) * kn * (1 + r) / ((3 + r) * t), (1 - r) / (3 + r)};
    case LatticeKind::Square: return {4.0 * kn * (1 + r) / ((3 + r) * t), (1 - r) / (3 + r)};
    case LatticeKind::SimpleCubic: return {5.0 * kn * (2 + 3 * r) / ((4 + r) * l), (1 - r) / (4 + r)};
    case LatticeKind::Fcc: return {2.0 * std::sqrt(2.0) * kn * (1 + 3 * r) / ((3 + r) * l), (1 - r) / (3 + r)};
    case LatticeKind::Random: break;
  }
  throw std::invalid_argument("latticeElasticity: lattice models need a regular lattice");
}

}  // namespace rupture
