// The LAPACK and BLAS routines the library calls directly (those that
// deal.II's lapack_templates.h lacks, or in single precision), declared once
// here so that a module needs no deal.II header for them (the library links
// the LAPACK and BLAS that deal.II was built with: LP64, so the integers are
// int). Matrices are column-major.
#ifndef impactfe_source_utilities_blas_lapack_h
#define impactfe_source_utilities_blas_lapack_h

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
  // y = alpha A x + beta y, A symmetric (one triangle read)
  void
  dsymv_(const char   *uplo,
         const int    *n,
         const double *alpha,
         const double *a,
         const int    *lda,
         const double *x,
         const int    *incx,
         const double *beta,
         double       *y,
         const int    *incy);
  void
  ssymv_(const char  *uplo,
         const int   *n,
         const float *alpha,
         const float *a,
         const int   *lda,
         const float *x,
         const int   *incx,
         const float *beta,
         float       *y,
         const int   *incy);
  // dot products and y += a x, double and single precision
  double
  ddot_(const int    *n,
        const double *x,
        const int    *incx,
        const double *y,
        const int    *incy);
  float
  sdot_(const int   *n,
        const float *x,
        const int   *incx,
        const float *y,
        const int   *incy);
  void
  daxpy_(const int    *n,
         const double *a,
         const double *x,
         const int    *incx,
         double       *y,
         const int    *incy);
  void
  saxpy_(const int   *n,
         const float *a,
         const float *x,
         const int   *incx,
         float       *y,
         const int   *incy);
  // triangular solves and products, double and single precision
  void
  dtrsm_(const char   *side,
         const char   *uplo,
         const char   *transa,
         const char   *diag,
         const int    *m,
         const int    *n,
         const double *alpha,
         const double *a,
         const int    *lda,
         double       *b,
         const int    *ldb);
  void
  dtrsv_(const char   *uplo,
         const char   *trans,
         const char   *diag,
         const int    *n,
         const double *a,
         const int    *lda,
         double       *x,
         const int    *incx);
  void
  dtrmv_(const char   *uplo,
         const char   *trans,
         const char   *diag,
         const int    *n,
         const double *a,
         const int    *lda,
         double       *x,
         const int    *incx);
  void
  strsv_(const char  *uplo,
         const char  *trans,
         const char  *diag,
         const int   *n,
         const float *a,
         const int   *lda,
         float       *x,
         const int   *incx);
  void
  sgemv_(const char  *trans,
         const int   *m,
         const int   *n,
         const float *alpha,
         const float *a,
         const int   *lda,
         const float *x,
         const int   *incx,
         const float *beta,
         float       *y,
         const int   *incy);
}

#endif
