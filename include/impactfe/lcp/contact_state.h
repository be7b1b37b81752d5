// The state of one contact: the one vocabulary of the LCP module, the time
// loop's warm start, the ContactMonitor and the output files.
#ifndef impactfe_lcp_contact_state_h
#define impactfe_lcp_contact_state_h

#include <string>

namespace impactfe
{
  /**
   * The state of a contact at a solution, or a guess of it. A sliding
   * contact carries the direction of its slip along the first tangent t1:
   * in 2D with friction the four states are the four complementary bases
   * of one contact (in the facet form with k = 2: which of P_N, beta_+,
   * beta_-, sigma are basic). Frictionless contacts, whose tangential
   * motion is free, slide; the LCP module's frictionless and 3D forms use
   * open and stick only (stick meaning "closed": P_N > 0 expected).
   */
  enum class ContactState : unsigned char
  {
    /// P = 0: the contact separates (or grazes).
    open = 0,
    /// Closed and sticking: V_N + b_N = 0, V_T = 0, |P_T| <= mu P_N.
    stick = 1,
    /// Closed and sliding with V_T1 > 0: P_T = -mu P_N (2D).
    slip_positive = 2,
    /// Closed and sliding with V_T1 < 0: P_T = +mu P_N (2D).
    slip_negative = 3
  };

  /** Whether the contact is closed (P_N > 0). */
  inline bool
  is_closed(const ContactState state)
  {
    return state != ContactState::open;
  }

  /** Whether the contact slides, in either direction. */
  inline bool
  is_sliding(const ContactState state)
  {
    return state == ContactState::slip_positive ||
           state == ContactState::slip_negative;
  }

  /**
   * 0 open, 1 stick, 2 slip: the state without the slip direction, as the
   * output files write it and as state changes are counted.
   */
  inline unsigned int
  contact_mode(const ContactState state)
  {
    return is_sliding(state) ? 2u : static_cast<unsigned int>(state);
  }

  /** "open", "stick", "slip+", "slip-". */
  std::string
  to_string(ContactState state);
} // namespace impactfe

#endif
