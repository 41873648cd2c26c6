// The tank-impact preview: the plate's nodes from plateGeometry (its rings, the refined band about
// the step, the hole and the pre-cracks) seen from above, and the water column, cylinder and
// piston from buildTankLattice in the section through the axis, each laid as runTankImpact lays it.
#include "scenarios/scenario_previews.hpp"

#include <cmath>

#include "rupture/quantity_text.hpp"
#include "scenarios/fluid/fluid_preview.hpp"
#include "scenarios/tank_impact/plate_geometry.hpp"
#include "scenarios/tank_impact/tank_lattice.hpp"

namespace rupture {

SamplePreview previewTankImpact(const TankImpactSpec& spec, const std::atomic<bool>& cancel, const std::string&) {
  sph::SphSystem s;
  s.model = io::fluidModel(spec.fluid, spec.resolution, 3, spec.soundSpeed, spec.gravity);
  s.cancel = &cancel;
  const TankLattice g = buildTankLattice(s, tankLatticeParams(spec));
  s.cancel.throwIfRequested();
  const PlateGeometry plate = plateGeometry(spec.plate);
  const ShellNodes& nodes = plate.nodes;

  SamplePreview out = fluidLatticePreview(s, 3, g.dx, 0.0, "water, cylinder and piston: section through the axis");
  const auto plateGroup = static_cast<std::uint8_t>(out.groups.size());
  out.groups.insert(out.groups.end(), {"plate node", "plate node, refined band", "plate node, clamped"});
  out.plateNodes = nodes.size();
  PreviewPanel top;
  top.title = "plate, top view";
  PreviewPanel& side = out.panels.front();
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const double spacing = nodes.nodeSpacing.empty() ? nodes.spacing : nodes.nodeSpacing[n];
    std::uint8_t group = plateGroup;
    if (n < nodes.clamped.size() && nodes.clamped[n]) group = plateGroup + 2;
    else if (spacing < 0.99 * nodes.spacing) group = plateGroup + 1;
    top.u.push_back(nodes.x[n]);
    top.v.push_back(nodes.y[n]);
    top.radius.push_back(0.5 * spacing);
    top.group.push_back(group);
    // The nodes within a spacing of the section (each ring has one there, whatever its phase), on
    // the mid-surface z = 0.
    if (std::fabs(nodes.y[n]) < spacing) {
      side.u.push_back(nodes.x[n]);
      side.v.push_back(0.0);
      side.radius.push_back(0.5 * spacing);
      side.group.push_back(group);
    }
  }
  // The plate's thickness about its mid-surface, across the spot face.
  const double t = spec.plate.shell.thickness, r = 0.5 * spec.plate.diameter;
  side.boxes.push_back({{-r, -0.5 * t, r, 0.5 * t}, "plate, " + formatQuantity(t, "m") + " thick"});
  if (plate.holeRadius > 0) top.circles.push_back({{0.0, 0.0, plate.holeRadius}, "hole"});
  // With the thick bottom, the spot face's rim is the step where the plate tears.
  if (spec.plate.bottom) top.circles.push_back({{0.0, 0.0, 0.5 * spec.plate.diameter}, "spot face (the step)"});
  for (const PlateSegment& c : plate.precracks) top.segments.push_back({{c.a[0], c.a[1], c.b[0], c.b[1]}, "pre-crack"});
  out.panels.insert(out.panels.begin(), std::move(top));

  out.facts.push_back(formatQuantity(static_cast<double>(nodes.size()), "1") + " plate nodes (spacing " +
                      formatQuantity(nodes.spacing, "m") +
                      (plateRefinedAtStep(spec.plate) ? ", refined about the step" : std::string()) +
                      "), spot face " + formatQuantity(spec.plate.diameter, "m") + ", thickness " +
                      formatQuantity(spec.plate.shell.thickness, "m") + ", pre-crack: " + toString(spec.plate.precrack.shape) +
                      (plate.holeRadius > 0 ? " of " + formatQuantity(2 * plate.holeRadius, "m") : std::string()));
  out.facts.push_back("water column " + formatQuantity(2 * g.R(), "m") + " across, " + formatQuantity(g.H(), "m") +
                      " high; carriage " + formatQuantity(spec.impactor.mass, "kg") + " at " +
                      formatQuantity(spec.impactor.speed, "m/s"));
  return out;
}

}  // namespace rupture
