#pragma once
// Functions compiled for AVX2 as well and picked at run time where the processor has it (GCC's function
// multi-versioning; x86-64 Linux): 4 doubles per instruction in their loops instead of SSE2's 2. Their
// files are compiled with -ffp-contract=off (libpcr/CMakeLists.txt): every entry takes the same operations
// in the same order in both versions (AVX2 does not include fused multiply-add), so they give the same bits.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define PCR_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define PCR_AVX2_CLONES
#endif
