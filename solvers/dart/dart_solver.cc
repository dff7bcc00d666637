// DART 6.12's box-LCP solvers (Debian libdart-dev) as the backends dart-dantzig, dart-pgs and dart-lemke.
// Compiled only when CMake finds DART (no_dart_backends.cc otherwise).
//
// dart-dantzig, dart-pgs: dart::constraint::DantzigBoxedLcpSolver / PgsBoxedLcpSolver, behind
// BoxedLcpSolver::solve(n, A, x, b, nub, lo, hi, findex, earlyTermination). Convention (ODE's): A x = b + w with
// x = lo ⇒ w ≥ 0, x = hi ⇒ w ≤ 0, lo < x < hi ⇒ w = 0, lo ≤ 0 ≤ hi, the first nub rows unbounded; ours after the
// shift z = c + x of peer_box_form.h. A is row-major with ODE's padded stride nskip = dPAD(n) (n rounded up to a
// multiple of 4 for n > 1), as DART's BoxedLcpConstraintSolver lays it out; findex = −1 on every row (no friction
// coupling); earlyTermination = false (DART's default). Both solvers may overwrite A and b. In 6.12 the Dantzig
// solver ignores nub (it calls dSolveLCP with nub = 0, which moves the free rows to the front itself); the PGS
// solver uses it only when every row is free (then it solves A x = b by LDL^T).
//
// dart-lemke: dart::lcpsolver::Lemke(M, q, &z) solves the LCP w = M z + q ≥ 0, z ≥ 0 ⟂ w; it has no bounds, so it
// gets the box → LCP rewriting of standard_form.h (the Siconos LCP form: shifted or negated one-sided rows, box rows
// doubled), no free rows. Its return code (0 ok, 1 iteration limit, 3 its own check failed, 4 diverged) is detail
// peer_code.
//
// Precision: DART's scalars are double; nothing is converted.
#include <memory>

#include <dart/constraint/DantzigBoxedLcpSolver.hpp>
#include <dart/constraint/PgsBoxedLcpSolver.hpp>
#include <dart/lcpsolver/Lemke.hpp>

#include "solvers/peer/peer_solver.h"
#include "solvers/siconos/external_backends.h"

namespace smcbench {
namespace {

enum class DartMethod { kDantzig, kPgs, kLemke };

// ODE's row stride (dPAD in dart/external/odelcpsolver/common.h).
int OdeStride(int n) { return n > 1 ? ((n - 1) | 3) + 1 : n; }

const SolverInfo& InfoOf(DartMethod method) {
  static const SolverInfo kDantzig{
      "dart-dantzig",
      "DART 6.12 DantzigBoxedLcpSolver: ODE's Dantzig-Cottle principal pivoting for the boxed LCP (LDL^T updates: "
      "assumes A symmetric); the box-LCP is our problem shifted into lo <= 0 <= hi",
      "DART 6.12 dart/constraint/DantzigBoxedLcpSolver, dart/external/odelcpsolver (ODE, R. Smith); Cottle & "
      "Dantzig 1968; Cottle, Pang & Stone 1992, sec. 4.2",
      true, false, false, true, false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true};
  static const SolverInfo kPgs{
      "dart-pgs",
      "DART 6.12 PgsBoxedLcpSolver: projected Gauss-Seidel on the boxed LCP with DART's stopping test (relative "
      "change of x <= 1e-3), 30 sweeps unless max_iterations; rows with A_ii < 1e-9 are set to 0",
      "DART 6.12 dart/constraint/PgsBoxedLcpSolver; Cottle, Pang & Stone 1992, sec. 5.2", true, false, false,
      false, false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true};
  static const SolverInfo kLemke{
      "dart-lemke",
      "DART 6.12 lcpsolver::Lemke on the box -> LCP rewriting (shifted / negated one-sided rows, doubled box "
      "rows); no free rows; at most 1000 pivots, zero tolerance 1e-5, its own check at 1e-4",
      "DART 6.12 dart/lcpsolver/Lemke; Lemke 1965; Cottle, Pang & Stone 1992, ch. 4", true, false, false, true,
      false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true};
  switch (method) {
    case DartMethod::kDantzig:
      return kDantzig;
    case DartMethod::kPgs:
      return kPgs;
    case DartMethod::kLemke:
      break;
  }
  return kLemke;
}

class DartSolver final : public PeerBoxSolver {
 public:
  explicit DartSolver(DartMethod method)
      : PeerBoxSolver(method == DartMethod::kLemke ? Shape::kLcp : Shape::kBox), method_(method) {}
  const SolverInfo& info() const override { return InfoOf(method_); }

 protected:
  // PgsBoxedLcpSolver::Option's default mMaxIteration; Lemke's 1000 pivots are fixed inside DART.
  int DefaultIterations() const override { return method_ == DartMethod::kPgs ? 30 : 1000; }
  bool HasCode() const override { return method_ == DartMethod::kLemke; }

  Reply Run(const Request& r, double* A, double* b, double* lo, double* hi, double* x) override {
    const int n = r.size;
    Reply reply;
    if (method_ == DartMethod::kLemke) {
      M_.resize(n, n);
      q_.resize(n);
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) M_(i, j) = A[static_cast<std::size_t>(i) * n + j];
        q_[i] = -b[i];
      }
      reply.code = dart::lcpsolver::Lemke(M_, q_, &z_);
      reply.success = reply.code == 0;
      for (int i = 0; i < n; ++i) x[i] = i < z_.size() ? z_[i] : 0.0;
      return reply;
    }
    // ODE's padded row-major layout; the padding columns are zero.
    const int stride = OdeStride(n);
    padded_.assign(static_cast<std::size_t>(n) * stride, 0.0);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        padded_[static_cast<std::size_t>(i) * stride + j] = A[static_cast<std::size_t>(i) * n + j];
      }
    }
    findex_.assign(n, -1);
    if (method_ == DartMethod::kDantzig) {
      reply.success = dantzig_.solve(n, padded_.data(), x, b, r.nub, lo, hi, findex_.data(), false);
    } else {
      dart::constraint::PgsBoxedLcpSolver::Option option;  // DART's defaults, with our budget
      option.mMaxIteration = r.iterations;
      pgs_.setOption(option);
      reply.success = pgs_.solve(n, padded_.data(), x, b, r.nub, lo, hi, findex_.data(), false);
    }
    return reply;
  }

  void DescribeFailure(const Reply& reply, SolveResult* result) const override {
    switch (method_) {
      case DartMethod::kDantzig:
        result->status = SolveStatus::kNumericalFailure;
        result->message = "DantzigBoxedLcpSolver returned false (dSolveLCP found no admissible pivot: it assumes A "
                          "symmetric, and fails on some problems that have a solution)";
        return;
      case DartMethod::kPgs:
        result->status = SolveStatus::kIterationLimit;
        result->message = "PgsBoxedLcpSolver returned false: its relative-change test was not met within its sweep "
                          "budget (Option::mMaxIteration)";
        return;
      case DartMethod::kLemke:
        break;
    }
    const std::string code = " (DART Lemke code " + std::to_string(reply.code) + ")";
    switch (reply.code) {
      case 1:
        result->status = SolveStatus::kIterationLimit;
        result->message = "DART's Lemke used its 1000 pivots" + code;
        return;
      case 3:
        result->status = SolveStatus::kInaccurate;
        result->message = "DART's Lemke ended but its own check (|w_i z_i|, -w_i, -z_i <= 1e-4) rejected the answer; "
                          "a secondary ray ends this way too" + code;
        return;
      default:
        result->status = SolveStatus::kNumericalFailure;
        result->message = "DART's Lemke diverged or found no pivot" + code;
        return;
    }
  }

 private:
  DartMethod method_;
  dart::constraint::DantzigBoxedLcpSolver dantzig_;
  dart::constraint::PgsBoxedLcpSolver pgs_;  // kept: its scratch vectors survive between solves (no answers)
  std::vector<double> padded_;
  std::vector<int> findex_;
  Eigen::MatrixXd M_;
  Eigen::VectorXd q_, z_;
};

template <DartMethod kMethod>
std::unique_ptr<Solver> MakeDart() {
  return std::make_unique<DartSolver>(kMethod);
}

}  // namespace

void AppendDartBackends(std::vector<ExternalBackend>* backends) {
  backends->push_back({InfoOf(DartMethod::kDantzig).name, &MakeDart<DartMethod::kDantzig>});
  backends->push_back({InfoOf(DartMethod::kPgs).name, &MakeDart<DartMethod::kPgs>});
  backends->push_back({InfoOf(DartMethod::kLemke).name, &MakeDart<DartMethod::kLemke>});
}

}  // namespace smcbench
