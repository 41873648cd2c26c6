#include "scenarios/bonded/bonded_preview.hpp"

#include <cmath>

#include "rupture/quantity_text.hpp"

namespace rupture {

std::string boxText(const std::array<double, 3>& size, int dimension) {
  std::string text = formatQuantity(size[0], "m") + " x " + formatQuantity(size[1], "m");
  if (dimension == 3) text += " x " + formatQuantity(size[2], "m");
  return text;
}

SamplePreview bondedSamplePreview(const BondedSystem& system, const SampleSpec& sample, const SampleReport& report,
                                  const std::vector<std::uint8_t>& group, std::vector<std::string> groups) {
  SamplePreview out;
  out.dimension = sample.dimension;
  out.size = sample.size;
  if (sample.dimension == 2) out.size[2] = 0;
  out.elements = report.elements;
  out.bonds = report.bonds;
  out.groups = std::move(groups);
  const ParticleStore& p = system.particles;
  PreviewPanel panel;
  const bool section = sample.dimension == 3;
  const double zMid = 0.5 * sample.size[2];
  panel.title = section ? "section at mid-depth z = " + formatQuantity(zMid, "m") : "sample (x-y plane)";
  for (std::size_t k = 0; k < p.size(); ++k) {
    double r = p.radius[k];
    if (section) {  // the disc the plane z = zMid cuts from the sphere, if it cuts it
      const double dz = p.z[k] - zMid;
      if (std::fabs(dz) >= r) continue;
      r = std::sqrt(r * r - dz * dz);
    }
    panel.u.push_back(p.x[k]);
    panel.v.push_back(p.y[k]);
    panel.radius.push_back(r);
    panel.group.push_back(k < group.size() ? group[k] : 0);
  }
  for (const Notch& n : sample.notches)
    panel.segments.push_back({{n.start[0], n.start[1], n.end[0], n.end[1]}, "notch"});
  out.panels.push_back(std::move(panel));

  const std::string grain = sample.lattice == "random"
                                ? "random packing, mean radius " + formatQuantity(sample.elementRadius, "m")
                                : sample.lattice + " lattice, spacing " + formatQuantity(sample.spacing, "m");
  out.facts.push_back(formatQuantity(static_cast<double>(report.elements), "1") + " elements, " +
                      formatQuantity(static_cast<double>(report.bonds), "1") + " bonds (" + grain + ")");
  std::string sizeLine = "sample " + boxText(out.size, sample.dimension);
  if (report.porosity > 0)
    sizeLine += ", porosity " + formatQuantity(100 * report.porosity, "1") + " % in " +
                formatQuantity(static_cast<double>(report.pores.size()), "1") + " pores";
  if (!sample.notches.empty()) sizeLine += ", " + std::to_string(sample.notches.size()) + " notch(es) in red";
  out.facts.push_back(sizeLine);
  return out;
}

}  // namespace rupture
