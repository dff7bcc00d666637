// Bullet Physics 3.24's MLCP solvers (BulletDynamics/MLCPSolvers, Debian libbullet-dev, its float64 build) as the
// backends bullet-dantzig, bullet-pgs and bullet-lemke, all behind btMLCPSolverInterface::solveMLCP(A, b, x, lo, hi,
// limitDependency, numIterations). Compiled only when CMake finds bullet-float64 (no_bullet_backends.cc otherwise).
//
// Convention: ODE's boxed LCP, A x = b + w with x = lo ⇒ w ≥ 0, x = hi ⇒ w ≤ 0, lo < x < hi ⇒ w = 0, lo ≤ 0 ≤ hi,
// which is ours after the shift z = c + x of peer_box_form.h (A = M, b = −(q + Mc), lo = l − c, hi = u − c);
// infinite bounds as BT_INFINITY (= IEEE inf in double). solveMLCP has no nub: btDantzigSolver passes nub = 0 to
// btSolveDantzigLCP, which itself moves the rows with lo = −inf, hi = +inf to the front; the free rows are first
// anyway. limitDependency (friction index) is −1 everywhere: no row's bounds depend on another's solution.
//
// Precision: Debian ships both builds; this file is compiled with BT_USE_DOUBLE_PRECISION and linked with the
// *-float64 libraries (pkg-config bullet-float64), so btScalar is double and nothing is converted (static_assert).
#include <cmath>
#include <memory>

#include "BulletDynamics/MLCPSolvers/btDantzigSolver.h"
#include "BulletDynamics/MLCPSolvers/btLemkeSolver.h"
#include "BulletDynamics/MLCPSolvers/btSolveProjectedGaussSeidel.h"
#include "solvers/peer/peer_solver.h"
#include "solvers/siconos/external_backends.h"

static_assert(sizeof(btScalar) == sizeof(double), "bullet-* adapters need Bullet's double-precision build");

namespace smcbench {
namespace {

enum class BulletMethod { kDantzig, kPgs, kLemke };

// btContactSolverInfo's m_numIterations default: what btMLCPSolver passes as numIterations.
constexpr int kBulletPgsIterations = 10;
// btLemkeSolver::m_maxLoops default.
constexpr int kBulletLemkeLoops = 1000;

const SolverInfo& InfoOf(BulletMethod method) {
  static const SolverInfo kDantzig{
      "bullet-dantzig",
      "Bullet 3.24 btDantzigSolver (float64): ODE's Dantzig-Cottle principal pivoting for the boxed LCP (LDL^T "
      "updates: assumes A symmetric); the box-LCP is our problem shifted into lo <= 0 <= hi",
      "Bullet Physics 3.24 BulletDynamics/MLCPSolvers/btDantzigLCP (from ODE, R. Smith); Cottle & Dantzig 1968; "
      "Cottle, Pang & Stone 1992, sec. 4.2",
      true, false, false, true, false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true};
  static const SolverInfo kPgs{
      "bullet-pgs",
      "Bullet 3.24 btSolveProjectedGaussSeidel (float64): projected Gauss-Seidel sweeps on the boxed LCP, "
      "10 sweeps unless max_iterations (btContactSolverInfo's default); always reports success",
      "Bullet Physics 3.24 BulletDynamics/MLCPSolvers/btSolveProjectedGaussSeidel; Cottle, Pang & Stone 1992, "
      "sec. 5.2",
      true, false, false, false, false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true};
  static const SolverInfo kLemke{
      "bullet-lemke",
      "Bullet 3.24 btLemkeSolver (float64): inverts A (Gauss-Jordan, no pivoting), doubles the box into a 2n LCP "
      "and runs Lemke (Lloyd 2005); needs finite bounds, or an LCP (lo = 0, hi = +inf on every row)",
      "Bullet Physics 3.24 BulletDynamics/MLCPSolvers/btLemkeSolver, btLemkeAlgorithm (K. Grundl, MBSim); "
      "Lloyd 2005, Fast implementation of Lemke's algorithm for rigid body contact simulation, ICRA",
      true, false, false, true, false, 0, /*equilibrate=*/false, /*delegates=*/false, /*external=*/true};
  switch (method) {
    case BulletMethod::kDantzig:
      return kDantzig;
    case BulletMethod::kPgs:
      return kPgs;
    case BulletMethod::kLemke:
      break;
  }
  return kLemke;
}

class BulletSolver final : public PeerBoxSolver {
 public:
  explicit BulletSolver(BulletMethod method) : PeerBoxSolver(Shape::kBox), method_(method) {}
  const SolverInfo& info() const override { return InfoOf(method_); }

 protected:
  int DefaultIterations() const override {
    return method_ == BulletMethod::kPgs ? kBulletPgsIterations : method_ == BulletMethod::kLemke ? kBulletLemkeLoops : 0;
  }

  // btLemkeSolver's bounded form builds q = [−B b₁ − lo; B b₁ + hi] (B = A⁻¹): an infinite bound makes it inf. Its
  // unbounded form solves the plain LCP x ≥ 0, which is our problem when every row is lo = 0, hi = +inf.
  bool Refuses(const Request& r, const double* lo, const double* hi, std::string* why) const override {
    if (method_ != BulletMethod::kLemke || AllFinite(r, lo, hi) || IsLcp(r, lo, hi)) return false;
    *why = "btLemkeSolver's bounded form needs finite lo and hi on every row (it builds q = [-B b - lo; B b + hi]), "
           "and its unbounded form only takes an LCP (lo = 0, hi = +inf on every row); this problem is neither";
    return true;
  }

  Reply Run(const Request& r, double* A, double* b, double* lo, double* hi, double* x) override {
    const int n = r.size;
    A_.resize(n, n);
    double* a = A_.getBufferPointerWritable();  // row-major, as ours
    for (int k = 0; k < n * n; ++k) a[k] = A[k];
    b_.resize(n);
    lo_.resize(n);
    hi_.resize(n);
    x_.resize(n);
    dependency_.resize(n);
    for (int i = 0; i < n; ++i) {
      b_[i] = b[i];
      lo_[i] = lo[i];
      hi_[i] = hi[i];
      x_[i] = x[i];
      dependency_[i] = -1;
    }
    Reply reply;
    switch (method_) {
      case BulletMethod::kDantzig:
        reply.success = dantzig_.solveMLCP(A_, b_, x_, lo_, hi_, dependency_, r.iterations);
        break;
      case BulletMethod::kPgs:
        reply.success = pgs_.solveMLCP(A_, b_, x_, lo_, hi_, dependency_, r.iterations);
        reply.iterations = r.iterations;  // it sweeps its whole budget (threshold 0)
        break;
      case BulletMethod::kLemke:
        lemke_.m_maxLoops = r.iterations;
        lemke_.m_useLoHighBounds = !IsLcp(r, lo, hi);
        reply.success = lemke_.solveMLCP(A_, b_, x_, lo_, hi_, dependency_, r.iterations);
        break;
    }
    for (int i = 0; i < n; ++i) x[i] = x_[i];
    return reply;
  }

  void DescribeFailure(const Reply& /*reply*/, SolveResult* result) const override {
    result->status = SolveStatus::kNumericalFailure;
    switch (method_) {
      case BulletMethod::kDantzig:
        result->message = "btDantzigSolver returned false (btSolveDantzigLCP found no admissible pivot: it assumes "
                          "A symmetric, and fails on some problems that have a solution)";
        return;
      case BulletMethod::kPgs:
        result->message = "btSolveProjectedGaussSeidel returned false";
        return;
      case BulletMethod::kLemke:
        result->message = "btLemkeSolver returned false (|x| above its m_maxValue 1e5, or a ray, which it resets to "
                          "x = 0)";
        return;
    }
  }

 private:
  static bool AllFinite(const Request& r, const double* lo, const double* hi) {
    for (int i = 0; i < r.size; ++i) {
      if (!std::isfinite(lo[i]) || !std::isfinite(hi[i])) return false;
    }
    return true;
  }
  static bool IsLcp(const Request& r, const double* lo, const double* hi) {
    for (int i = 0; i < r.size; ++i) {
      if (lo[i] != 0.0 || !(std::isinf(hi[i]) && hi[i] > 0)) return false;
    }
    return true;
  }

  BulletMethod method_;
  btMatrixXu A_;
  btVectorXu b_, lo_, hi_, x_;
  btAlignedObjectArray<int> dependency_;
  // Kept like btMLCPSolver keeps its solver: their scratch memory (no answers) survives between solves.
  btDantzigSolver dantzig_;
  btSolveProjectedGaussSeidel pgs_;
  btLemkeSolver lemke_;
};

template <BulletMethod kMethod>
std::unique_ptr<Solver> MakeBullet() {
  return std::make_unique<BulletSolver>(kMethod);
}

}  // namespace

void AppendBulletBackends(std::vector<ExternalBackend>* backends) {
  backends->push_back({InfoOf(BulletMethod::kDantzig).name, &MakeBullet<BulletMethod::kDantzig>});
  backends->push_back({InfoOf(BulletMethod::kPgs).name, &MakeBullet<BulletMethod::kPgs>});
  backends->push_back({InfoOf(BulletMethod::kLemke).name, &MakeBullet<BulletMethod::kLemke>});
}

}  // namespace smcbench
