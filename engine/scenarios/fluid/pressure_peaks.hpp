#pragma once
// The two peaks the seed's drop tests compare (Caleyron et al. 2013, section 5.1): a pressure's
// largest value over the run, and its first peak, the largest value while the impact wave makes
// its first transit (the caller's window), with the time it came.
#include <algorithm>

namespace rupture {

/// The first transit's window for a water column of height H and sound speed c0: the bottom holds
/// the doubled pressure from H/c0 until the wave reflected there comes back from the piston at
/// 3H/c0 (a little earlier: the compressed column is faster); the window stops halfway, at 2.5 H/c0.
inline double firstTransitWindow(double height, double soundSpeed) { return 2.5 * height / soundSpeed; }

struct PressurePeaks {
  /// `window`: end of the first transit (s); `initial`: the pressure at t = 0 (Pa).
  PressurePeaks(double window, double initial) : window(window), peak(initial), first(initial) {}

  void observe(double time, double pressure) {
    peak = std::max(peak, pressure);
    if (time <= window && pressure > first) {
      first = pressure;
      firstTime = time;
    }
  }

  double window;         ///< s
  double peak;           ///< largest pressure so far (Pa)
  double first;          ///< largest pressure up to `window` (Pa)
  double firstTime = 0;  ///< when it came (s)
};

}  // namespace rupture
