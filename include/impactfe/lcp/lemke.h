// Lemke's complementary pivoting method for the linear complementarity problem
//
//     w = M z + q,   w >= 0,  z >= 0,  w . z = 0.
//
// Plain C++17, no deal.II: usable from the stand-alone lcp-solve tool.
#ifndef impactfe_lcp_lemke_h
#define impactfe_lcp_lemke_h

#include <impactfe/lcp/dense_matrix.h>

#include <memory>
#include <string>
#include <vector>

namespace impactfe
{
  namespace lcp
  {
    /// Outcome of a Lemke solve.
    enum class Status
    {
      /// A complementary solution was found and passed verify().
      solved,
      /// The entering column had no positive entry: Lemke's method stops on a
      /// secondary ray. For copositive-plus M this proves that the LCP has no
      /// solution (Cottle-Pang-Stone 1992, Thm 4.4.13); in general it only says
      /// that Lemke's method could not find one.
      ray_termination,
      /// The pivot cap was reached.
      pivot_limit,
      /// The basis became singular, or the final (z, w) failed verify() even
      /// after a refactorisation.
      numerical_failure,
      /// Not returned by solve_lemke(): proven to have no solution, because
      /// there is no z >= 0 with M z + q >= 0 (see lcp_feasibility() in
      /// contact_routes.h).
      infeasible
    };

    /// "solved", "ray-termination", "pivot-limit", "failed" or "infeasible".
    std::string
    to_string(Status status);

    /// Which path a (possibly warm-started) solve took.
    enum class StartPath
    {
      /// Lemke from the all-slack basis (the textbook method).
      cold,
      /// The guessed complementary basis was already feasible: no pivot.
      guess_solved,
      /// Lemke's method started from the guessed complementary basis.
      guess_lemke,
      /// The guess was rejected (singular or Lemke failed from it): cold Lemke.
      guess_fallback_cold,
      /// Not Lemke: block principal pivoting on the contact states (see
      /// solve_contact_problem() with a ContactState guess) found the
      /// complementary basis; its point passed verify().
      block_pivoting
    };

    /// "cold", "guess-solved", "guess-lemke", "guess-fallback-cold",
    /// "block-pivoting".
    std::string
    to_string(StartPath path);

    /**
     * Independent check of a candidate solution (z, w) of LCP(q, M).
     *
     * With s = ||q||_inf + ||M||_inf ||z||_inf (the scale of w) and
     * tol = tolerance_factor * eps * max(n, 1):
     *  - min_z >= -tol ||z||_inf,
     *  - min_w >= -tol s,
     *  - residual = ||w - M z - q||_inf <= tol s,
     *  - max_complementarity = max_i |z_i w_i| <= tol ||z||_inf s.
     * relative_complementarity = sum_i |z_i w_i| / (||z||_inf s) (0 when the
     * numerator is 0): a scale-invariant measure of how far (z, w) is from
     * complementarity. (For Lemke's output it is exactly 0: the complement of
     * every basic variable is nonbasic, hence exactly 0.)
     * relative_error = max(relative_complementarity, residual / s,
     * (-min_z)^+ / ||z||_inf, (-min_w)^+ / s): all conditions in one number,
     * what lcp-solve prints.
     */
    struct Verification
    {
      double min_z                    = 0.;
      double min_w                    = 0.;
      double max_complementarity      = 0.;
      double residual                 = 0.;
      double relative_complementarity = 0.;
      double relative_error           = 0.;
      /// The relative tolerance tol used above.
      double tolerance = 0.;
      bool   ok        = false;
    };

    /// See Verification. Sizes must match (else std::invalid_argument).
    Verification
    verify(const DenseMatrix         &M,
           const std::vector<double> &q,
           const std::vector<double> &z,
           const std::vector<double> &w,
           double                     tolerance_factor = 1e3);

    /**
     * The checks of verify() for a point whose residual r = w - M z - q and
     * ||M||_inf were computed elsewhere, e.g. without forming M (the contact
     * LCP forms in contact_problem.cc). Same tolerance and same numbers as
     * verify(M, q, z, w) would give with that M.
     */
    Verification
    verify_with_residual(double                     norm_M,
                         const std::vector<double> &q,
                         const std::vector<double> &z,
                         const std::vector<double> &w,
                         const std::vector<double> &residual,
                         double                     tolerance_factor = 1e3);

    /// Options of the Lemke solver; the defaults suit the contact LCPs.
    struct LemkeOptions
    {
      /// Covering vector d > 0 (z0 column is -d). Empty: all ones.
      std::vector<double> covering_vector;
      /// Pivot cap. 0: pivot_factor * (n + 1).
      unsigned int max_pivots = 0;
      /// See max_pivots.
      unsigned int pivot_factor = 50;
      /// Recompute the basis inverse from the basis columns (LU with partial
      /// pivoting) every this many pivots. 0: max(100, n).
      unsigned int refactor_interval = 0;
      /// Check ||q - B x_B||_inf every this many pivots; refactorise when it
      /// exceeds the verification tolerance. 0: never.
      unsigned int drift_check_interval = 25;
      /// An entry y_i of the updated entering column y = B^{-1} a is a pivot
      /// candidate if y_i > pivot_tolerance_factor * eps * ||a||_inf *
      /// max|B^{-1}|, i.e. if it is above the rounding error of y_i.
      double pivot_tolerance_factor = 1e2;
      /// Ratios within tie_tolerance_factor * eps (relative) are ties, broken
      /// by the lexicographic rule.
      double tie_tolerance_factor = 1e3;
      /// Passed to verify().
      double verification_tolerance_factor = 1e3;
      /// solve_lemke_warm(): solve cold where the guess fails. false: return
      /// that failure (for a caller whose cold solve already failed).
      bool cold_fallback = true;
    };

    /// The outcome of solve_lemke() / solve_lemke_warm().
    struct Result
    {
      Status status = Status::numerical_failure;
      /// The solution; empty unless status == solved.
      std::vector<double> z;
      /// w = M z + q as carried by the final basis; empty unless solved.
      std::vector<double> w;
      /// Number of basis exchanges, the first one (z0 entering) included.
      /// For a warm start that fell back to cold Lemke: both runs summed.
      unsigned int pivots = 0;
      /// How many times the basis inverse was recomputed from scratch.
      unsigned int refactorisations = 0;
      /// On ray termination: the variable that could not enter, encoded as
      /// i for w_i and n + i for z_i (0 <= i < n). -1 otherwise.
      int driving_variable = -1;
      /// On ray termination: the z part of the ray's direction (the
      /// driving variable 1, the basic variables -B^{-1} a), empty otherwise.
      /// For a copositive-plus M it is the certificate z^h >= 0, M z^h >= 0,
      /// q^T z^h < 0 of CPS Thm 4.4.13, to be checked in floating point.
      std::vector<double> ray_z;
      /// verify() on the returned (z, w); ok == false when z, w are empty.
      Verification verification;
      /// Which start was used.
      StartPath start_path = StartPath::cold;
      /// Human-readable account of what happened (always set).
      std::string message;
    };

    /**
     * Lemke's method (Cottle-Pang-Stone 1992, Section 4.4) from the all-slack
     * basis with covering vector d and the lexicographic minimum-ratio rule
     * (ibid., Section 4.9), which rules out cycling. If z0 ties for leaving it
     * is preferred (this ends the run). Returns immediately if q >= 0.
     *
     * The basis inverse B^{-1} is kept explicitly and updated by a rank-one
     * (product-form) update per pivot; columns of B^{-1} that belong to basic
     * slacks w_i are unit vectors and never stored, so a pivot costs
     * O(n (k + 1)) with k the number of basic z (and z0) variables. B^{-1} is
     * recomputed from the basis columns every refactor_interval pivots, when
     * the drift check fails, and once more if the final point fails verify().
     *
     * Throws std::invalid_argument for inconsistent sizes, non-finite data or
     * a covering vector that is not positive.
     */
    Result
    solve_lemke(const DenseMatrix         &M,
                const std::vector<double> &q,
                const LemkeOptions        &options = {});

    /**
     * Warm-started solve. @p guess[i] says "z_i > 0 expected" (e.g. the active
     * set of the previous time step). The complementary basis with z_i basic
     * for guess[i] and w_i basic otherwise is factorised; if it is feasible the
     * answer is returned without pivoting (StartPath::guess_solved). Otherwise
     * Lemke's method is started from that basis with the covering vector
     * d = B e, i.e. Lemke on the principal pivot transform of the LCP with
     * covering vector e (StartPath::guess_lemke). For P-matrices this always
     * works (principal pivot transforms of P-matrices are P-matrices). If the
     * guessed principal block is singular, or Lemke stops on a ray or the
     * pivot cap from there, the problem is solved cold
     * (StartPath::guess_fallback_cold). options.covering_vector is used by
     * the cold fallback only.
     */
    Result
    solve_lemke_warm(const DenseMatrix         &M,
                     const std::vector<double> &q,
                     const std::vector<bool>   &guess,
                     const LemkeOptions        &options = {});



    /**
     * Lemke's method for a sequence of LCPs, e.g. one per time step: the
     * basis, its inverse, the work vectors and the Result are kept from one
     * solve to the next, so that once an LCP of the largest size has been
     * solved, further solves allocate no memory (tests/lcp/allocations).
     * solve_lemke() and solve_lemke_warm() are this class used once; the
     * results are the same bit for bit.
     */
    class LemkeSolver
    {
    public:
      LemkeSolver();
      ~LemkeSolver();
      LemkeSolver(LemkeSolver &&) noexcept;
      LemkeSolver &
      operator=(LemkeSolver &&) noexcept;

      /// As solve_lemke(); the reference stays valid until the next solve.
      const Result &
      solve(const DenseMatrix         &M,
            const std::vector<double> &q,
            const LemkeOptions        &options = {});

      /// As solve_lemke_warm().
      const Result &
      solve_warm(const DenseMatrix         &M,
                 const std::vector<double> &q,
                 const std::vector<bool>   &guess,
                 const LemkeOptions        &options = {});

      /// The result of the last solve.
      const Result &
      result() const;

      /// Bytes of heap storage held (capacities). A solve allocates only if
      /// this grows: the storage is never given back between solves.
      std::size_t
      memory_consumption() const;

      struct Workspace;

    private:
      std::unique_ptr<Workspace> workspace;
    };

    /// Reset @p result to its default values, keeping the storage of its
    /// vectors and message (no allocation when it is reused).
    void
    clear(Result &result);
  } // namespace lcp
} // namespace impactfe

#endif
