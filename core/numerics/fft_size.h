// FFT sizes for Eigen's kissfft backend.
#pragma once

namespace railwear::internal {

// Smallest L >= n of the form 2^a 3^b 5^c (kissfft's fast radices) that is a multiple of
// `multiple` (4 for real transforms: kissfft's packed real FFT needs it), and at least 2.
inline int NextFftSize(int n, int multiple) {
  for (int l = multiple;; l += multiple) {
    int m = l;
    for (int p : {2, 3, 5}) {
      while (m % p == 0) m /= p;
    }
    if (m == 1 && l >= n && l >= 2) return l;
  }
}

}  // namespace railwear::internal
