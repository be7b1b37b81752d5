#ifndef impactfe_utilities_vectorized_kernel_h
#define impactfe_utilities_vectorized_kernel_h

/**
 * @file
 * IMPACTFE_VECTORIZED_KERNEL marks a function whose loop runs over
 * independent entries (no sums across entries): a step's F~ rows and
 * vector updates of a few hundred entries. Debian builds with -O2 for
 * generic x86-64, where GCC 12 vectorises no loop of unknown length and
 * uses no AVX. The attribute asks GCC to vectorise this function's loops
 * and to compile an AVX2 version beside the generic one, chosen at load
 * time by the processor. Neither changes the arithmetic of an entry: no
 * reordering, and no FMA contraction (AVX2 does not enable FMA, and
 * fp-contract=off keeps it so under -march=native), so the results are
 * the same to the bit on every processor.
 */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#  define IMPACTFE_VECTORIZED_KERNEL                   \
    __attribute__((optimize("tree-loop-vectorize",     \
                            "vect-cost-model=dynamic", \
                            "fp-contract=off"),        \
                   target_clones("avx2", "default")))
#else
#  define IMPACTFE_VECTORIZED_KERNEL
#endif

#endif
