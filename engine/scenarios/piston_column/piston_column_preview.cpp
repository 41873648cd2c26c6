// The piston-column preview: the water, the tube, its bottom and the piston as buildPistonColumn
// lays them for the run.
#include "scenarios/scenario_previews.hpp"

#include "rupture/quantity_text.hpp"
#include "scenarios/fluid/fluid_preview.hpp"
#include "scenarios/piston_column/piston_column_lattice.hpp"

namespace rupture {

SamplePreview previewPistonColumn(const PistonColumnSpec& spec, const std::atomic<bool>& cancel, const std::string&) {
  sph::SphSystem s;
  s.cancel = &cancel;
  const ColumnLattice g = buildPistonColumn(s, spec);
  SamplePreview out = fluidLatticePreview(s, spec.dimension, g.dx, 0.0,
                                          spec.dimension == 3 ? "section through the axis" : "side view");
  out.facts.push_back("water column " + formatQuantity(2 * g.R(), "m") + " across, " + formatQuantity(g.H(), "m") +
                      " high; the piston strikes at " +
                      formatQuantity(spec.impactor ? spec.impactor->speed : spec.piston.speed, "m/s"));
  return out;
}

}  // namespace rupture
