// The BLAS's thread count, for programs with or without deal.II (lcp-solve
// has none of deal.II's headers).
#ifndef impactfe_utilities_blas_threads_h
#define impactfe_utilities_blas_threads_h

namespace impactfe
{
  /**
   * Limit the BLAS to @p n_threads (> 0). Debian's deal.II links the
   * pthreads OpenBLAS, whose idle workers spin in sched_yield after each
   * BLAS call: with one core's worth of work that doubles the process CPU
   * and takes a core from anything else running; the workers OpenBLAS starts
   * when it is loaded spin for about 0.1 s even if never used, so with one
   * thread they are stopped. The OpenBLAS calls are found at run time, so
   * another BLAS is left as it is.
   */
  void
  set_blas_thread_limit(const unsigned int n_threads);
} // namespace impactfe

#endif
