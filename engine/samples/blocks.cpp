#include "samples/blocks.hpp"

namespace rupture {

std::vector<int> particleBlocks(const SampleSpec& sample, const ParticleStore& p) {
  std::vector<int> block(p.size(), 1);
  for (std::size_t k = 0; k < p.size(); ++k)
    for (const BlockRegion& r : sample.blocks)
      if (r.box.contains(p.x[k], p.y[k], p.z[k])) block[k] = r.id;  // later blocks override earlier ones
  return block;
}

}  // namespace rupture
