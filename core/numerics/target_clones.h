// RAILWEAR_AVX2_CLONES: a function compiled twice, for AVX2 (4 doubles per instruction, chosen
// at load time on CPUs that have it) and for the build's baseline (SSE2, 2 doubles). Only for
// loops whose every multiply and add is rounded on its own and in a fixed order (element-wise
// loops, no reduction the compiler could reorder): AVX2 without the "fma" target contracts
// nothing, so both clones give the same bits (docs/speed.md, the sweeps' column refresh).
// Not under ThreadSanitizer (RAILWEAR_SANITIZE=thread): GCC instruments the clones' load-time
// resolver, which then runs before the sanitizer's runtime is set up and crashes the program
// while librailwear loads; there each function is compiled once.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_THREAD__)
#define RAILWEAR_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define RAILWEAR_AVX2_CLONES
#endif
