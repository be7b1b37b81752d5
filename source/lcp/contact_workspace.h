// Internal to the LCP module: the storage of ContactSolver, shared by the
// LCP forms (contact_problem.cc) and the block pivoting on contact states
// (block_pivoting.cc). Every member is sized with assign()/resize()/
// reinit(), which keep the capacity, so a solve of a size that was seen
// before allocates nothing.
#ifndef impactfe_lcp_contact_workspace_h
#define impactfe_lcp_contact_workspace_h

#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/lemke.h>
#include <impactfe/lcp/lu.h>

#include <string>
#include <vector>

namespace impactfe
{
  namespace lcp
  {
    struct ContactSolver::Workspace
    {
      ContactSolution   solution;
      ContactLCP        lcp;
      LemkeSolver       lemke;
      std::vector<bool> guess;

      // The Klarbring form: blocks of W, W_TT^{-1} and its products.
      DenseMatrix         W_TT, W_NT, W_TN, AW_TN, W_NT_A, W_NT_AW_TN;
      LUFactorization     W_TT_lu;
      std::vector<double> V_T, AV_T;

      // Impulses, states and verification from an LCP solution.
      std::vector<double> tangential_residual, velocity, verification_velocity;

      // Block pivoting on the contact states (2D friction).
      std::vector<ContactState> states, visited_states;
      std::vector<double>       P, z, w, q, residual, Mz_q, slip_factor, rhs;
      std::vector<double>       slip_impulses;
      std::vector<unsigned int> rows, unknown_column, unknown_contact;
      std::vector<unsigned int> stick_rows, slip_contacts;
      DenseMatrix               W_SS, Z, Z_rhs, schur, G;
      CholeskyFactorization     cholesky;
      LUFactorization           schur_lu, G_lu;
      std::string               why_not_block_pivoting;

      // The system whose factors are held above (cholesky, Z = W_SS^{-1} B
      // and schur_lu; or G_lu): the states, slip factors and W it was
      // made from. A time loop whose contacts keep their states and whose
      // W does not change solves with the same factors, bit for bit. The
      // copy of W costs 8 (2 n_c)^2 bytes (3.3 MB at 321 contacts),
      // about as much as the factors it keeps.
      enum class FactoredSystem
      {
        none,
        cholesky,
        lu
      };
      FactoredSystem            factored_system = FactoredSystem::none;
      unsigned int              reused_factors  = 0;
      std::vector<ContactState> factored_states;
      std::vector<double>       factored_slip_factor, factored_W;

      std::size_t
      memory_consumption() const
      {
        std::size_t bytes =
          lemke.memory_consumption() + lcp::memory_consumption(solution.P) +
          lcp::memory_consumption(solution.lcp.z) +
          lcp::memory_consumption(solution.lcp.w) +
          lcp::memory_consumption(solution.states) +
          solution.lcp.message.capacity() + solution.message.capacity() +
          lcp.M.memory_consumption() + lcp::memory_consumption(lcp.q) +
          lcp.W_TT_inverse.memory_consumption() +
          lcp::memory_consumption(lcp.directions) + lcp.message.capacity() +
          guess.capacity() / 8 + why_not_block_pivoting.capacity() +
          lcp::memory_consumption(states) +
          lcp::memory_consumption(visited_states) +
          lcp::memory_consumption(factored_states);
        for (const auto &d : lcp.directions)
          bytes += lcp::memory_consumption(d);
        for (const auto *v : {&V_T,
                              &AV_T,
                              &tangential_residual,
                              &velocity,
                              &verification_velocity,
                              &P,
                              &z,
                              &w,
                              &q,
                              &residual,
                              &Mz_q,
                              &slip_factor,
                              &rhs,
                              &slip_impulses,
                              &factored_slip_factor,
                              &factored_W})
          bytes += lcp::memory_consumption(*v);
        for (const auto *v : {&rows,
                              &unknown_column,
                              &unknown_contact,
                              &stick_rows,
                              &slip_contacts})
          bytes += lcp::memory_consumption(*v);
        for (const auto *m : {&W_TT,
                              &W_NT,
                              &W_TN,
                              &AW_TN,
                              &W_NT_A,
                              &W_NT_AW_TN,
                              &W_SS,
                              &Z,
                              &Z_rhs,
                              &schur,
                              &G})
          bytes += m->memory_consumption();
        return bytes + W_TT_lu.memory_consumption() +
               cholesky.memory_consumption() + schur_lu.memory_consumption() +
               G_lu.memory_consumption();
      }
    };

    namespace internal
    {
      /// The unit tangent directions d_j of the facet form: +t, -t in 2D,
      /// k directions at angles 2 pi j / k in the (t1, t2) plane in 3D.
      void
      facet_directions(const unsigned int                dim,
                       const unsigned int                k,
                       std::vector<std::vector<double>> &D);

      /// assemble_contact_lcp() into @p lcp with the storage of @p ws.
      void
      assemble_contact_lcp(const ContactProblem     &p,
                           const ContactOptions     &options,
                           ContactSolver::Workspace &ws,
                           ContactLCP               &lcp);

      /// impulses_from_lcp() into @p P.
      void
      impulses_from_lcp(const ContactProblem      &p,
                        const ContactLCP          &lcp,
                        const std::vector<double> &z,
                        std::vector<double>       &tangential_residual,
                        std::vector<double>       &P);

      /// contact_states() into @p states (V: work vector).
      void
      contact_states(const ContactProblem      &p,
                     const std::vector<double> &P,
                     double                     tolerance,
                     std::vector<double>       &V,
                     std::vector<ContactState> &states);

      /// guess_from_states() into @p guess.
      void
      guess_from_states(const ContactLCP                &lcp,
                        const std::vector<ContactState> &states,
                        std::vector<bool>               &guess);

      /// verify_contact_solution() with the work vector @p V.
      ContactVerification
      verify_contact_solution(const ContactProblem      &p,
                              const std::vector<double> &P,
                              double                     tolerance,
                              std::vector<double>       &V);

      /**
       * The end of every solve that ran Lemke on ws.lcp, with the result in
       * s.lcp: impulses and states if it solved, "<form>; <Lemke>" appended
       * to s.message (which holds what came before, or is empty), and, for
       * the automatic form, the other routes if it did not solve.
       */
      void
      finish_lemke_route(const ContactProblem     &p,
                         const ContactOptions     &options,
                         ContactSolver::Workspace &ws,
                         ContactSolution          &s);

      /**
       * 2D friction: the impulses of Lemke's answer s.P solved again at its
       * contact states s.states, by one solve of block_pivoting_2d()
       * (block_pivoting.cc). Lemke's impulses satisfy the equations of their
       * states only to the accuracy of the form's pivots (Klarbring's P_T
       * goes through W_TT^{-1}: |P_T| = mu P_N to ~1e-8 relative when W has
       * entries of very different sizes, as with massless contact nodes).
       * The re-solved point has P_T = -+mu P_N exactly for sliding contacts
       * and replaces s.P only if it passes the block pivoting's
       * verification; s.lcp (z, w, pivots) stays Lemke's. Done only when
       * some contact misses |P_T| <= mu P_N, or a sliding one |P_T| = mu P_N,
       * by more than 1e-12 max|P| (a solve costs about as much as Lemke's
       * method on these sizes). True if replaced.
       */
      bool
      polish_2d_impulses(const ContactProblem     &p,
                         const ContactOptions     &options,
                         ContactSolver::Workspace &ws,
                         ContactSolution          &s);

      /**
       * How far the impulses s.P miss the cone's equations of their states
       * s.states, over max|P|: |P_T| - mu P_N > 0 for any contact, or
       * | |P_T| - mu P_N | for a sliding one (2D). 0 without friction.
       */
      double
      cone_equation_miss(const ContactProblem &p, const ContactSolution &s);

      /**
       * Why the impulses @p P of a solve in Klarbring's form are not an
       * answer, or "" if they are: the contact conditions checked on P itself
       * (verify_contact_solution(), work vector @p V), to the tolerance of
       * the other routes. Klarbring's P_T goes through W_TT^{-1}: an LCP
       * answer verified to the rounding of its M can still leave the cone
       * when W's entries span many orders (massless contact nodes).
       */
      std::string
      klarbring_objection(const ContactProblem      &p,
                          const ContactOptions      &options,
                          const std::vector<double> &P,
                          std::vector<double>       &V);

      /// The form solve_contact_problem() uses for @p requested.
      FrictionForm
      resolved_form(const ContactProblem &p, FrictionForm requested);
    } // namespace internal
  }   // namespace lcp
} // namespace impactfe

#endif
