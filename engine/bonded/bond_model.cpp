#include "bonded/bond_model.hpp"

namespace rupture {

std::string describe(const BondModel& model) {
  return std::visit(
      [](const auto& m) {
        using M = std::decay_t<decltype(m)>;
        return std::string(M::Law::kName) + "/" + M::Criterion::kName;
      },
      model);
}

}  // namespace rupture
