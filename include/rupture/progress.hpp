#pragma once
// One estimator of the time a run still needs, shared by the CLI's progress bar and the job
// server's progress documents, so the two never disagree.
namespace rupture {

/// Seconds left if the rate so far holds: elapsed · (1 − f) / f. Negative (unknown) below 1 % done,
/// where the rate says too little, and for a non-finite or negative input.
inline double estimateRemainingSeconds(double elapsedSeconds, double fraction) {
  if (!(elapsedSeconds >= 0) || !(fraction >= 0.01)) return -1.0;
  if (fraction >= 1.0) return 0.0;
  return elapsedSeconds * (1.0 - fraction) / fraction;
}

}  // namespace rupture
