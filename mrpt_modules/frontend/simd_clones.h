#pragma once
// Hot loops compiled twice, for AVX2 and for the x86-64 baseline (SSE2), the one for this CPU
// picked when the program loads. The build itself stays portable (no -march=native, DESIGN.md §5).
// AVX2 without FMA contracts nothing: both clones give the same results bit for bit. Not under
// ThreadSanitizer: the clones' resolvers run before its runtime is up (a crash at load).
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__SANITIZE_THREAD__)
#define RPVIO_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define RPVIO_AVX2_CLONES
#endif
