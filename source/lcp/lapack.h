// The few LAPACK and BLAS routines of the LCP module, declared here so that
// the module needs no deal.II header (the library links the LAPACK and BLAS
// that deal.II was built with: LP64, so the integers are int). Matrices are
// column-major.
#ifndef impactfe_source_lcp_lapack_h
#define impactfe_source_lcp_lapack_h

extern "C"
{
  void
  dgetrf_(const int *m,
          const int *n,
          double    *a,
          const int *lda,
          int       *ipiv,
          int       *info);
  void
  dgetrs_(const char   *trans,
          const int    *n,
          const int    *nrhs,
          const double *a,
          const int    *lda,
          const int    *ipiv,
          double       *b,
          const int    *ldb,
          int          *info);
  void
  dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
  void
  dpotrs_(const char   *uplo,
          const int    *n,
          const int    *nrhs,
          const double *a,
          const int    *lda,
          double       *b,
          const int    *ldb,
          int          *info);
  void
  dsyrk_(const char   *uplo,
         const char   *trans,
         const int    *n,
         const int    *k,
         const double *alpha,
         const double *a,
         const int    *lda,
         const double *beta,
         double       *c,
         const int    *ldc);
  void
  dgemv_(const char   *trans,
         const int    *m,
         const int    *n,
         const double *alpha,
         const double *a,
         const int    *lda,
         const double *x,
         const int    *incx,
         const double *beta,
         double       *y,
         const int    *incy);
}

#endif
