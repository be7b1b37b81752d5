// Internal to the LCP module: printf-style messages written into a string
// that is reused from one solve to the next. Unlike std::ostringstream this
// allocates nothing once the string has the capacity, so the messages of
// the LCP solves in a time loop cost no allocation.
#ifndef impactfe_lcp_text_h
#define impactfe_lcp_text_h

#include <cstdarg>
#include <cstdio>
#include <string>
#include <vector>

namespace impactfe
{
  namespace lcp
  {
    namespace internal
    {
      /// Append the printf-formatted text to @p out.
      inline void
      vappend_text(std::string &out, const char *format, std::va_list args)
      {
        char         buffer[512];
        std::va_list copy;
        va_copy(copy, args);
        const int length = std::vsnprintf(buffer, sizeof(buffer), format, args);
        if (length < 0)
          {
            va_end(copy);
            return;
          }
        if (static_cast<std::size_t>(length) < sizeof(buffer))
          out.append(buffer, static_cast<std::size_t>(length));
        else
          {
            // longer than the buffer (rare, e.g. long failure messages)
            std::vector<char> large(static_cast<std::size_t>(length) + 1);
            std::vsnprintf(large.data(), large.size(), format, copy);
            out.append(large.data(), static_cast<std::size_t>(length));
          }
        va_end(copy);
      }

      /// Append the printf-formatted text to @p out.
      inline void
      append_text(std::string &out, const char *format, ...)
        __attribute__((format(printf, 2, 3)));

      inline void
      append_text(std::string &out, const char *format, ...)
      {
        std::va_list args;
        va_start(args, format);
        vappend_text(out, format, args);
        va_end(args);
      }

      /// Replace @p out by the printf-formatted text.
      inline void
      set_text(std::string &out, const char *format, ...)
        __attribute__((format(printf, 2, 3)));

      inline void
      set_text(std::string &out, const char *format, ...)
      {
        out.clear();
        std::va_list args;
        va_start(args, format);
        vappend_text(out, format, args);
        va_end(args);
      }
    } // namespace internal
  }   // namespace lcp
} // namespace impactfe

#endif
