// FFT lengths for the FFTW transforms of the influence and rolling operators.
#pragma once

namespace railwear::internal {

// Smallest L >= n of the form 2^a 3^b 5^c 7^d (radices FFTW has fast codelets for) that is a
// multiple of `multiple`, and at least 2.
inline int NextFftSize(int n, int multiple) {
  for (int l = multiple;; l += multiple) {
    int m = l;
    for (int p : {2, 3, 5, 7}) {
      while (m % p == 0) m /= p;
    }
    if (m == 1 && l >= n && l >= 2) return l;
  }
}

// Length of the zero-padded transform along a Toeplitz direction of `cells` cells: at least
// 2 cells - 1, so that the circulant embedding gives a linear, not a periodic, convolution.
// Real-input (r2c) transforms take even lengths (FFTW's r2c is fastest there), complex ones any.
inline int RealFftSize(int cells) { return NextFftSize(2 * cells - 1, 2); }
inline int ComplexFftSize(int cells) { return NextFftSize(2 * cells - 1, 1); }

}  // namespace railwear::internal
