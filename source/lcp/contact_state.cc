#include <impactfe/lcp/contact_state.h>

namespace impactfe
{
  std::string
  to_string(const ContactState state)
  {
    switch (state)
      {
        case ContactState::open:
          return "open";
        case ContactState::stick:
          return "stick";
        case ContactState::slip_positive:
          return "slip+";
        case ContactState::slip_negative:
          return "slip-";
      }
    return "open";
  }
} // namespace impactfe
