#pragma once
// How SPH water particles and the nodes of a shell touch (Caleyron et al. 2013 §4.3; docs/fsi-contact.md).
#include <string>

namespace rupture {

/// Fluid–structure contact between water particles and plate nodes (seed §5.2, eq. 7).
enum class ContactMethod {
  Pinball,     ///< cylindrical pinball per node, sphere per particle; impulse cancelling the normal approach
  MasterSlave  ///< fluid particles (slaves) kept on the plate's interpolated surface (master), free to slide
};

inline std::string contactMethodName(ContactMethod m) {
  return m == ContactMethod::Pinball ? "pinball" : "master_slave";
}

}  // namespace rupture
