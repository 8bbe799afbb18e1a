// Radical inverse in base b: coordinate `index` of the Halton sequence in [0, 1), deterministic
// and well spread. Shared by the optimiser's starts and the adaptive loop's candidates.
#pragma once

namespace repose::stats {

inline double radical_inverse(int index, int base) {
  double f = 1, r = 0;
  for (int i = index; i > 0; i /= base) {
    f /= base;
    r += f * (i % base);
  }
  return r;
}

}  // namespace repose::stats
