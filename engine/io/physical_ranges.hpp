#pragma once
// The ranges of the physical inputs several scenarios share, each with the reason for its bounds.
// Beyond them the models are not valid (and the stable time step, the runs' length or their
// arithmetic leave any meaning: a density of 1e308 kg/m^3 gives a time step of 1e145 s). The JSON
// Schemas (api/schemas/) state the same bounds.
#include "io/spec_reader.hpp"

namespace rupture::io::physical {

/// Mass density (kg/m^3): from foams and aerogels (about 1) to well above the densest element
/// (osmium, 22,590).
inline Range density() { return {1.0, 1e5, false, false}; }
/// A material's Young's modulus (Pa): from soft gels (1 kPa) to well above diamond's (1.2 TPa).
inline Range modulus() { return {1e3, 1e13, false, false}; }
/// A beam's microscopic modulus E_mu (Pa): the material's modulus is about 0.9 E_mu r_mu^2, so two
/// decades above modulus() leave room for radius ratios down to 0.1.
inline Range beamModulus() { return {1e3, 1e15, false, false}; }
/// A strain rate (1/s): up to 1e9, the top of laser-driven spall experiments; above it the loaded
/// face of even a 1 um sample moves faster than any solid's waves.
inline Range strainRate() { return {0.0, 1e9, true, false}; }
/// A wave or sound speed, or an imposed speed (m/s): up to 1e5, five times the fastest solid's
/// waves (diamond, 18 km/s).
inline Range speed() { return {0.0, 1e5, true, false}; }

}  // namespace rupture::io::physical
