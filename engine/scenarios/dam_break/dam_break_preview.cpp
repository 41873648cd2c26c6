// The dam-break preview: the column and the tank as buildDamBreak lays them for the run.
#include "scenarios/scenario_previews.hpp"

#include "rupture/quantity_text.hpp"
#include "scenarios/dam_break/dam_break_lattice.hpp"
#include "scenarios/fluid/fluid_preview.hpp"

namespace rupture {

SamplePreview previewDamBreak(const DamBreakSpec& spec, const std::atomic<bool>& cancel, const std::string&) {
  sph::SphSystem s;
  s.cancel = &cancel;
  const DamBreakLattice g = buildDamBreak(s, spec);
  SamplePreview out = fluidLatticePreview(s, spec.dimension, g.dx, 0.5 * g.W(),
                                          spec.dimension == 3 ? "side view, the layer at mid-width" : "side view");
  out.facts.push_back("water column " + formatQuantity(g.a(), "m") + " wide, " + formatQuantity(g.H(), "m") +
                      " high in a tank " + formatQuantity(g.L(), "m") + " long" +
                      (spec.dimension == 3 ? ", " + formatQuantity(g.W(), "m") + " across" : std::string()));
  return out;
}

}  // namespace rupture
