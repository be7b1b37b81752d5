// Internal to the LCP module: a scope in which subnormal numbers are flushed
// to zero.
//
// Delassus operators of finite element bodies decay exponentially with the
// distance between contacts (the implicit step couples nodes over a few
// wave lengths c h), so far-apart entries of W and of everything computed
// from it (LU factors, basis inverses, Klarbring blocks) reach the subnormal
// range, 1e-308 and below. On x86 every operation on a subnormal takes a
// slow microcode path (one to two orders of magnitude slower), and these
// operations then dominate the dense kernels. Values below 2.2e-308 are far
// below the verification tolerances (1e3 eps n relative): flushing them to
// zero does not change which answers are accepted, only how long the
// arithmetic takes. Outside x86 with SSE this is a no-op.
#ifndef impactfe_source_lcp_floating_point_mode_h
#define impactfe_source_lcp_floating_point_mode_h

#if defined(__SSE2__) || defined(_M_X64)
#  include <xmmintrin.h>
#  define IMPACTFE_LCP_HAVE_MXCSR 1
#endif

namespace impactfe
{
  namespace lcp
  {
    namespace internal
    {
      /// Sets flush-to-zero and denormals-are-zero for the lifetime of the
      /// object and restores the previous mode afterwards.
      class FlushSubnormalsScope
      {
      public:
        FlushSubnormalsScope()
        {
#ifdef IMPACTFE_LCP_HAVE_MXCSR
          saved_mode = _mm_getcsr();
          // bit 15: flush to zero (results), bit 6: denormals are zero (inputs)
          _mm_setcsr(saved_mode | 0x8040u);
#endif
        }

        ~FlushSubnormalsScope()
        {
#ifdef IMPACTFE_LCP_HAVE_MXCSR
          _mm_setcsr(saved_mode);
#endif
        }

        FlushSubnormalsScope(const FlushSubnormalsScope &) = delete;
        FlushSubnormalsScope &
        operator=(const FlushSubnormalsScope &) = delete;

      private:
        unsigned int saved_mode = 0;
      };
    } // namespace internal
  }   // namespace lcp
} // namespace impactfe

#endif
