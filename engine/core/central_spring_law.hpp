#pragma once
// Central spring (Hookean lattice springs, docs/references.md#eq-lattice; also the PMB peridynamic
// bond, peridynamics/pmb_law.hpp): F_j = −k (L − L0) n, U = ½ k (L − L0)², with the per-bond stiffness
// k set once from the material (lattice/spring_mapping.hpp or the PMB micromodulus). In core because
// two law families share it.
#include <cmath>

#include "core/bond_law.hpp"

namespace rupture {

struct CentralSpringLaw {
  static constexpr const char* kName = "central_spring";
  static constexpr bool kRotational = false;
  static constexpr bool kReadsRadii = false;  // the central loop need not fetch them

  [[gnu::always_inline]] BondResponse response(const BondGeometry& g) const {
    const double length = std::sqrt(g.dx * g.dx + g.dy * g.dy + g.dz * g.dz);
    const double invL = 1.0 / length;
    const double extension = length - g.restLength;
    const double force = g.stiffness * extension;  // tension positive
    const double energy = 0.5 * force * extension;
    BondResponse r{};
    r.fjx = -force * g.dx * invL;
    r.fjy = -force * g.dy * invL;
    r.fjz = -force * g.dz * invL;
    r.energy = energy;
    r.stretch = extension * g.invRestLength;  // a multiplication: the divider bounds the central loop
    r.normalForce = force;
    r.tensileNormalEnergy = extension > 0 ? energy : 0.0;
    return r;
  }

  BondStiffness stiffness(const BondGeometry& g) const { return {g.stiffness, 0.0}; }
};

}  // namespace rupture
