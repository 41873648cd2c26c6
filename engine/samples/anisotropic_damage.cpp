#include "samples/anisotropic_damage.hpp"

#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include "samples/blocks.hpp"

namespace rupture {

namespace {

/// A uniform number in [0, 1) from 53 bits of the generator (the same on every standard library).
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

/// A uniformly random rotation's axes (Shoemake 1992, "Uniform random rotations", Graphics Gems III:
/// a unit quaternion from three uniforms).
FrameAxes randomRotation(std::mt19937_64& rng) {
  const double u1 = unit(rng), u2 = 2 * std::numbers::pi * unit(rng), u3 = 2 * std::numbers::pi * unit(rng);
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  const double w = a * std::sin(u2), x = a * std::cos(u2), y = b * std::sin(u3), z = b * std::cos(u3);
  // Columns of the rotation matrix of (w, x, y, z).
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)},
           {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)},
           {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)}}};
}

}  // namespace

std::vector<FrameAxes> materialFrames(const AnisotropicDamageSpec& spec, const SampleSpec& sample,
                                      const ParticleStore& p, const std::vector<std::int32_t>& grain) {
  std::vector<FrameAxes> frames(p.size());
  if (spec.randomGrainFrames) {
    std::mt19937_64 rng(sample.seed ^ 0x6A09E667F3BCC909ull);  // a stream of its own of sample.seed
    std::vector<FrameAxes> perGrain(static_cast<std::size_t>(sample.grains.count));
    for (FrameAxes& f : perGrain)
      f = sample.dimension == 2 ? frameAxes({180.0 * unit(rng), 0, 0}, 2) : randomRotation(rng);
    for (std::size_t k = 0; k < p.size(); ++k) frames[k] = perGrain[static_cast<std::size_t>(grain[k])];
    return frames;
  }
  const FrameAxes fallback = frameAxes(spec.angles, sample.dimension);
  std::map<int, FrameAxes> byBlock;
  for (const auto& [id, angles] : spec.blockAngles) byBlock[id] = frameAxes(angles, sample.dimension);
  const std::vector<int> block = byBlock.empty() ? std::vector<int>() : particleBlocks(sample, p);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto found = byBlock.empty() ? byBlock.end() : byBlock.find(block[k]);
    frames[k] = found != byBlock.end() ? found->second : fallback;
  }
  return frames;
}

void assignFibres(const AnisotropicDamageSpec& spec, int dimension, const std::vector<FrameAxes>& frames,
                  BondStore& bonds) {
  for (std::size_t c = 0; c < bonds.fibreFactor.size(); ++c) {
    bonds.fibreFactor[c].resize(bonds.size());
    bonds.fibreIntegrity[c].resize(bonds.size());
  }
  for (std::size_t b = 0; b < bonds.size(); ++b) {
    const BondFibres fibres = bondFibres({bonds.n0x[b], bonds.n0y[b], bonds.n0z[b]}, frames[bonds.i[b]],
                                         frames[bonds.j[b]], spec.criticalFactors, dimension);
    for (std::size_t c = 0; c < 3; ++c) {
      bonds.fibreFactor[c][b] = fibres.factor[c];
      bonds.fibreIntegrity[c][b] = fibres.integrity[c];
    }
  }
}

}  // namespace rupture
