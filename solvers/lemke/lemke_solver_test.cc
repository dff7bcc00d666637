// Tests of the Lemke backend. Every success is judged by residuals recomputed here (w = Mz + q, bounds,
// complementarity), never by the solver's own status alone.
#include "solvers/lemke/lemke_solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace smcbench {
namespace {

// ‖z − Π_[l,u](z − (Mz+q))‖∞ / (1 + ‖q‖∞), recomputed from scratch, and z ∈ [l,u].
double RelativeNaturalResidual(const BoxMLCP& problem, const Vector& z) {
  const DenseMatrix& M = problem.dense_matrix();
  const Vector w = M * z + problem.q();
  double r = 0.0;
  for (int i = 0; i < problem.size(); ++i) {
    const double proj = std::min(std::max(z[i] - w[i], problem.l()[i]), problem.u()[i]);
    r = std::max(r, std::abs(z[i] - proj));
    if (std::isnan(z[i])) return kInf;
  }
  return r / (1.0 + problem.q().cwiseAbs().maxCoeff());
}

void ExpectSolved(const BoxMLCP& problem, const SolveResult& result, double tol = 1e-10) {
  ASSERT_EQ(result.status, SolveStatus::kSolved) << problem.name() << ": " << result.message;
  ASSERT_EQ(result.z.size(), problem.size());
  for (int i = 0; i < problem.size(); ++i) {
    EXPECT_GE(result.z[i], problem.l()[i]) << problem.name() << " i=" << i;
    EXPECT_LE(result.z[i], problem.u()[i]) << problem.name() << " i=" << i;
  }
  EXPECT_LE(RelativeNaturalResidual(problem, result.z), tol) << problem.name();
}

// Murty's exponential example for Lemke (Murty 1988, ch. 6; lcp_exp_murty2.dat is n = 6): upper triangular with 1
// on the diagonal and 2 above, q_i = −(2^(n+1) − 2^(i+1)) (0-based i).
BoxMLCP Murty(int n) {
  DenseMatrix M = DenseMatrix::Zero(n, n);
  Vector q(n);
  for (int i = 0; i < n; ++i) {
    M(i, i) = 1.0;
    for (int j = i + 1; j < n; ++j) M(i, j) = 2.0;
    q[i] = -(std::ldexp(1.0, n + 1) - std::ldexp(1.0, i + 1));
  }
  return BoxMLCP::LCP(M, q, "murty" + std::to_string(n));
}

// --- A tiny generator with a known solution: pick z* and a complementary w*, set q = w* − M z*. ---
enum class Family { kSpd, kNonsymmetricPd };
enum class Bounds { kLcp, kRelay, kMixed };

struct Known {
  BoxMLCP problem;
  Vector z_star;
};

Known Generate(int n, Family family, Bounds bounds, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  DenseMatrix A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = normal(rng);
  DenseMatrix M = A * A.transpose() / n + 0.5 * DenseMatrix::Identity(n, n);  // eigenvalues ≥ 0.5
  if (family == Family::kNonsymmetricPd) {
    DenseMatrix B(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) B(i, j) = normal(rng);
    M += B - B.transpose();  // a skew part keeps xᵀMx > 0
  }
  Vector l(n), u(n), z(n), w(n);
  for (int i = 0; i < n; ++i) {
    int kind = 0;  // 0 lower, 1 box, 2 upper, 3 free, 4 fixed
    if (bounds == Bounds::kRelay) kind = 1;
    if (bounds == Bounds::kMixed) kind = static_cast<int>(rng() % 5);
    l[i] = kind == 0 ? 0.0 : kind == 1 ? -1.0 : kind == 4 ? 0.3 : -kInf;
    u[i] = kind == 0 ? kInf : kind == 1 ? 1.0 : kind == 2 ? 2.0 : kind == 4 ? 0.3 : kInf;
    const double t = uni(rng);
    if (kind == 3) {  // free: w = 0
      z[i] = 3.0 * normal(rng), w[i] = 0.0;
    } else if (kind == 4) {  // fixed: any w
      z[i] = 0.3, w[i] = normal(rng);
    } else if (t < 0.35 && l[i] > -kInf) {  // at the lower bound: w > 0
      z[i] = l[i], w[i] = 0.1 + uni(rng);
    } else if (t < 0.7 && u[i] < kInf) {  // at the upper bound: w < 0
      z[i] = u[i], w[i] = -0.1 - uni(rng);
    } else {  // strictly inside: w = 0
      const double lo = l[i] > -kInf ? l[i] : u[i] - 3.0;
      const double hi = u[i] < kInf ? u[i] : lo + 3.0;
      z[i] = lo + (0.1 + 0.8 * uni(rng)) * (hi - lo);
      w[i] = 0.0;
    }
  }
  Vector q = w - M * z;
  return {BoxMLCP(M, q, l, u, "gen_n" + std::to_string(n) + "_s" + std::to_string(seed)), z};
}

// --- Minimal reader for the Siconos LCP and MLCP (storage type 1, dense) files; see tests/data/siconos/README.md. ---
std::vector<double> ReadNumbers(const std::string& path) {
  std::ifstream in(path);
  std::vector<double> v;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '#') break;
    std::istringstream s(line);
    std::string tok;
    while (s >> tok) {
      char* end = nullptr;
      const double x = std::strtod(tok.c_str(), &end);
      if (end == tok.c_str()) return v;  // trailing text
      v.push_back(x);
    }
  }
  return v;
}

std::string PeerPath(const std::string& rel) { return std::string(SMCBENCH_PEER_DATA_DIR) + "/siconos/" + rel; }

bool ReadDense(const std::vector<double>& v, size_t* k, int rows, int cols, DenseMatrix* M) {
  if (v.size() < *k + 5 || v[*k] != 0.0) return false;  // dense storage only
  if (static_cast<int>(v[*k + 1]) != rows || static_cast<int>(v[*k + 2]) != cols) return false;
  *k += 5;
  if (v.size() < *k + size_t(rows) * cols) return false;
  M->resize(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) (*M)(i, j) = v[(*k)++];  // column-major
  return true;
}

bool ReadSiconosLcp(const std::string& rel, DenseMatrix* M, Vector* q) {
  const std::vector<double> v = ReadNumbers(PeerPath(rel));
  if (v.empty()) return false;
  const int n = static_cast<int>(v[0]);
  size_t k = 1;
  if (!ReadDense(v, &k, n, n, M) || v.size() < k + n) return false;
  q->resize(n);
  for (int i = 0; i < n; ++i) (*q)[i] = v[k++];
  return true;
}

// Box-MLCP form of a Siconos MLCP: the first n rows free, the next m rows l = 0, u = ∞.
bool ReadSiconosMlcp(const std::string& rel, DenseMatrix* M, Vector* q, Vector* l, Vector* u) {
  const std::vector<double> v = ReadNumbers(PeerPath(rel));
  if (v.size() < 5 || v[0] != 1.0) return false;
  const int n = static_cast<int>(v[2]), m = static_cast<int>(v[3]);
  size_t k = 4;
  int blocks = 0;
  while (k < v.size() && static_cast<int>(v[k]) != n + m) ++k, ++blocks;
  k += 1 + blocks;  // the final start, then one flag per block
  if (!ReadDense(v, &k, n + m, n + m, M) || v.size() < k + n + m) return false;
  q->resize(n + m);
  for (int i = 0; i < n + m; ++i) (*q)[i] = v[k++];
  *l = Vector::Constant(n + m, 0.0);
  *u = Vector::Constant(n + m, kInf);
  l->head(n).setConstant(-kInf);
  return true;
}

// A deliberately naive Lemke (first row among min-ratio ties, full tableau), used only to show that a problem
// cycles without the lexicographic rule. Returns true if a (basis, entering variable) state repeats.
bool NaiveLemkeCycles(const DenseMatrix& M, const Vector& q) {
  const int n = static_cast<int>(q.size()), cols = 2 * n + 2;
  DenseMatrix T = DenseMatrix::Zero(n, cols);  // [I, −M, −e, q]
  T.leftCols(n).setIdentity();
  T.middleCols(n, n) = -M;
  T.col(2 * n).setConstant(-1.0);
  T.col(2 * n + 1) = q;
  std::vector<int> basis(n);
  for (int i = 0; i < n; ++i) basis[i] = i;
  auto pivot = [&](int r, int e) {
    T.row(r) /= T(r, e);
    for (int i = 0; i < n; ++i)
      if (i != r) T.row(i) -= T(i, e) * T.row(r);
    basis[r] = e;
  };
  int r = 0;
  for (int i = 1; i < n; ++i)
    if (q[i] < q[r]) r = i;
  pivot(r, 2 * n);
  int entering = r + n;
  std::set<std::pair<std::vector<int>, int>> seen;
  for (int it = 0; it < 1000; ++it) {
    std::vector<int> b = basis;
    std::sort(b.begin(), b.end());
    if (!seen.insert({b, entering}).second) return true;
    int row = -1;
    double theta = kInf;
    for (int i = 0; i < n; ++i) {
      if (T(i, entering) > 1e-9 && T(i, 2 * n + 1) / T(i, entering) < theta - 1e-9) {
        theta = T(i, 2 * n + 1) / T(i, entering), row = i;
      }
    }
    if (row < 0) return false;
    const int leaving = basis[row];
    pivot(row, entering);
    if (leaving == 2 * n) return false;
    entering = leaving < n ? leaving + n : leaving - n;
  }
  return false;
}

// Whether LCP(M, q) has a solution, by trying every complementary basis (n ≤ 12): the ground truth for small files.
bool LcpHasSolutionByEnumeration(const DenseMatrix& M, const Vector& q) {
  const int n = static_cast<int>(q.size());
  for (int mask = 0; mask < (1 << n); ++mask) {
    std::vector<int> a;
    for (int i = 0; i < n; ++i)
      if (mask >> i & 1) a.push_back(i);
    const int k = static_cast<int>(a.size());
    DenseMatrix Maa(k, k);
    Vector qa(k);
    for (int i = 0; i < k; ++i) {
      qa[i] = -q[a[i]];
      for (int j = 0; j < k; ++j) Maa(i, j) = M(a[i], a[j]);
    }
    Vector z = Vector::Zero(n);
    if (k > 0) {
      Eigen::FullPivLU<DenseMatrix> lu(Maa);
      if (!lu.isInvertible()) continue;
      const Vector za = lu.solve(qa);
      for (int i = 0; i < k; ++i) z[a[i]] = za[i];
    }
    const Vector w = M * z + q;
    if (z.minCoeff() >= -1e-12 && w.minCoeff() >= -1e-12) return true;
  }
  return false;
}

// ---------------------------------------------------------------------------------------------------------------

TEST(LemkeSolver, InfoAndOptions) {
  LemkeSolver solver;
  EXPECT_EQ(solver.info().name, "lemke");
  EXPECT_TRUE(solver.info().dense);
  EXPECT_FALSE(solver.info().sparse);
  EXPECT_TRUE(solver.info().exact);
  EXPECT_FALSE(solver.info().reference.empty());
  std::string why;
  EXPECT_TRUE(LemkeOptions{}.IsValid(&why));
  std::string error;
  EXPECT_TRUE(solver.SetOption("pivot_tolerance", "1e-10", &error)) << error;
  EXPECT_EQ(solver.options().pivot_tolerance, 1e-10);
  EXPECT_FALSE(solver.SetOption("pivot_tolerance", "-1", &error));
  EXPECT_FALSE(solver.SetOption("covering_vector", "7", &error));
  EXPECT_FALSE(solver.SetOption("lexicographic", "0", &error));  // always on, not an option
  EXPECT_NE(solver.OptionsHelp().find("refactor_interval"), std::string::npos);
  // Named values, with the old numbers still read; the help prints the names.
  EXPECT_TRUE(solver.SetOption("free_row_method", "split", &error)) << error;
  EXPECT_EQ(solver.options().free_row_method, LemkeOptions::FreeRows::kSplit);
  EXPECT_TRUE(solver.SetOption("free_row_method", "1", &error)) << error;
  EXPECT_EQ(solver.options().free_row_method, LemkeOptions::FreeRows::kSchur);
  EXPECT_TRUE(solver.SetOption("covering_vector", "row-scaled", &error)) << error;
  EXPECT_EQ(solver.options().covering_vector, LemkeOptions::Covering::kRowScaled);
  EXPECT_TRUE(solver.SetOption("covering_vector", "0", &error)) << error;
  EXPECT_EQ(solver.options().covering_vector, LemkeOptions::Covering::kOnes);
  EXPECT_FALSE(solver.SetOption("free_row_method", "schur-only", &error));
  EXPECT_NE(error.find("auto, schur, basic, split"), std::string::npos) << error;
  EXPECT_NE(solver.OptionsHelp().find(
                "free_row_method = schur (one of auto schur basic split; old number 0=auto 1=schur 2=basic 3=split)"),
            std::string::npos)
      << solver.OptionsHelp();

  LemkeSolver bad;
  bad.mutable_options().free_block_min_rcond = 2.0;
  const SolveResult r = bad.Solve(BoxMLCP::LCP(DenseMatrix::Identity(1, 1), Vector::Constant(1, -1.0)));
  EXPECT_EQ(r.status, SolveStatus::kInvalidOptions);
  EXPECT_FALSE(r.message.empty());
}

TEST(LemkeSolver, KnownSmallLcps) {
  LemkeSolver solver;
  {  // interior solution of an SPD LCP: M z = −q
    DenseMatrix M(2, 2);
    M << 2, 1, 1, 2;
    const BoxMLCP p = BoxMLCP::LCP(M, Vector{{-5.0, -6.0}}, "spd2");
    const SolveResult r = solver.Solve(p);
    ExpectSolved(p, r);
    EXPECT_NEAR(r.z[0], 4.0 / 3.0, 1e-14);
    EXPECT_NEAR(r.z[1], 7.0 / 3.0, 1e-14);
  }
  {  // one component at zero
    DenseMatrix M(2, 2);
    M << 1, 0.5, 0.5, 1;
    const BoxMLCP p = BoxMLCP::LCP(M, Vector{{-1.0, 2.0}}, "mixed2");
    const SolveResult r = solver.Solve(p);
    ExpectSolved(p, r);
    EXPECT_NEAR(r.z[0], 1.0, 1e-14);
    EXPECT_EQ(r.z[1], 0.0);
  }
  {  // q ≥ 0: z = 0 without a pivot
    const BoxMLCP p = BoxMLCP::LCP(DenseMatrix::Identity(3, 3), Vector{{1.0, 0.0, 2.0}}, "trivial");
    const SolveResult r = solver.Solve(p);
    ExpectSolved(p, r);
    EXPECT_EQ(r.iterations, 0);
    EXPECT_EQ(r.z.cwiseAbs().maxCoeff(), 0.0);
  }
  {  // CPS Example 4.4.7 (lcp_CPS_2.dat, read column-major): skew-symmetric M
    DenseMatrix M(3, 3);
    M << 0, -1, 2, 2, 0, -2, -1, 1, 0;
    const BoxMLCP p = BoxMLCP::LCP(M, Vector{{-3.0, 6.0, -1.0}}, "cps_4_4_7");
    ExpectSolved(p, solver.Solve(p));
  }
}

// A ray's message says what it is and claims no proof: "no solution found by this method", and that a ray proves
// infeasibility only for copositive-plus M, which Lemke does not check.
void ExpectHonestRay(const SolveResult& r) {
  EXPECT_EQ(r.status, SolveStatus::kRayTermination) << r.message;
  EXPECT_NE(r.message.find("secondary ray"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("no solution found by this method"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("copositive-plus"), std::string::npos) << r.message;
  EXPECT_EQ(r.message.find("proves the problem"), std::string::npos) << r.message;
  EXPECT_EQ(r.message.find("a solution exists"), std::string::npos) << r.message;
}

TEST(LemkeSolver, NoSolutionIsRayTermination) {
  LemkeSolver solver;
  const BoxMLCP p = BoxMLCP::LCP(DenseMatrix::Constant(1, 1, -1.0), Vector::Constant(1, -1.0), "infeasible1");
  const SolveResult r = solver.Solve(p);
  ExpectHonestRay(r);
  EXPECT_FALSE(r.solved());
  EXPECT_GT(RelativeNaturalResidual(p, r.z), 1e-3);

  // PSD with infeasible constraints: z1 − z2 ≥ 1 and −z1 + z2 ≥ 1 cannot both hold.
  DenseMatrix M(2, 2);
  M << 1, -1, -1, 1;
  const BoxMLCP p2 = BoxMLCP::LCP(M, Vector{{-1.0, -1.0}}, "infeasible_psd");
  ExpectHonestRay(solver.Solve(p2));
}

// On a class that always has a solution a ray is a failure of the method, not a proof: the message must say so
// rather than "when M is positive semidefinite this proves the problem has no solution", false on these problems.
TEST(LemkeSolver, RayClaimedAProofOnProblemsThatHaveASolution) {
  LemkeSolver solver;
  SolverOptions raw;
  raw.polish = false;  // the method's own verdict
  {  // Every bound finite: M = −1, q = −2 on [0, 2] has the solution z = 2 (w = −4 ≤ 0 at the upper bound), but
     // Lemke leaves on a ray after its first pivot: with z₀ = 2 + x basic, the bound row's slack 2 − x + z₀ = 4 does
     // not move as x enters, so nothing blocks.
    const BoxMLCP p(DenseMatrix::Constant(1, 1, -1.0), Vector::Constant(1, -2.0), Vector::Constant(1, 0.0),
                    Vector::Constant(1, 2.0), "finite_box");
    EXPECT_EQ(RelativeNaturalResidual(p, Vector::Constant(1, 2.0)), 0.0);
    const SolveResult r = solver.Solve(p, raw);
    EXPECT_EQ(r.status, SolveStatus::kNumericalFailure) << r.message;
    EXPECT_NE(r.message.find("a solution exists (every bound is finite)"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("Lemke's method failed"), std::string::npos) << r.message;
    EXPECT_EQ(r.message.find("proves"), std::string::npos) << r.message;
  }
  {  // SPD LCP (so a P-matrix: exactly one solution), made to end on a ray by a coarse pivot tolerance that refuses
     // the small blocking entries of the entering column.
    DenseMatrix M(2, 2);
    M << 2e-6, -1e-3, -1e-3, 1.0;  // det = 1e-6 > 0
    ASSERT_EQ(M.llt().info(), Eigen::Success);
    const BoxMLCP p = BoxMLCP::LCP(M, Vector{{-1.0, 0.5}}, "spd_coarse_pivots");
    LemkeSolver coarse;
    coarse.mutable_options().pivot_tolerance = 1e-3;
    const SolveResult r = coarse.Solve(p, raw);
    EXPECT_EQ(r.status, SolveStatus::kNumericalFailure) << r.message;
    EXPECT_NE(r.message.find("a solution exists"), std::string::npos) << r.message;
    EXPECT_EQ(r.message.find("proves"), std::string::npos) << r.message;
    // The default pivot tolerance solves it.
    ExpectSolved(p, solver.Solve(p, raw));
  }
}

TEST(LemkeSolver, DegenerateCyclingExampleIsSolved) {
  // Found by searching small integer LCPs: with q = −e every ratio test ties, and Lemke with the "first row"
  // tie-break revisits a basis (cycles forever). The lexicographic rule cannot cycle.
  DenseMatrix M(3, 3);
  M << 1, 2, 2, 2, 1, 1, 0, -1, 1;
  const Vector q = Vector::Constant(3, -1.0);
  ASSERT_TRUE(NaiveLemkeCycles(M, q));
  LemkeSolver solver;
  const BoxMLCP p = BoxMLCP::LCP(M, q, "cycling3");
  const SolveResult r = solver.Solve(p);
  ExpectSolved(p, r);
  EXPECT_LT(r.iterations, 20);

  // Fully degenerate: many zero entries of q and a singular PSD matrix.
  DenseMatrix M2 = DenseMatrix::Ones(4, 4);
  const BoxMLCP p2 = BoxMLCP::LCP(M2, Vector{{-1.0, -1.0, 0.0, -1.0}}, "degenerate_ones");
  ExpectSolved(p2, solver.Solve(p2));
}

// Murty's matrix with its last diagonal entry 2: every row's largest entry is then 2, so the row equilibration that
// Solver::Solve applies is a uniform scaling and Lemke (d = e) still walks an exponentially long path (Murty's own
// matrix has a last row of largest entry 1, and equilibration turns d = e into d = row scales, see below).
BoxMLCP MurtyEqualRowScales(int n) {
  BoxMLCP murty = Murty(n);
  DenseMatrix M = murty.dense_matrix();
  M(n - 1, n - 1) = 2.0;
  return BoxMLCP::LCP(M, murty.q(), "murty_equal_rows" + std::to_string(n));
}

TEST(LemkeSolver, MurtyExponentialExample) {
  LemkeSolver solver;
  SolverOptions raw;
  raw.polish = false;  // the pivot count of the algorithm itself
  for (int n : {8, 12, 16}) {
    // Murty's problem as published: its unique solution is z = 2^n e_n (w_i = 2^(i+1) > 0 above it). Lemke gets the
    // row-equilibrated problem, i.e. Murty's with covering vector d = (2, …, 2, 1): z₀ first blocks on the last row
    // (−q_i/d_i is 2^n − 2^i above, 2^n there), so z_n enters and z₀ leaves: two pivots instead of 2^n.
    const BoxMLCP p = Murty(n);
    const SolveResult r = solver.Solve(p, raw);
    ExpectSolved(p, r);
    EXPECT_EQ(r.iterations, 2) << "n = " << n;
    EXPECT_EQ(r.z[n - 1], std::ldexp(1.0, n));
    for (int i = 0; i < n - 1; ++i) EXPECT_EQ(r.z[i], 0.0);
    // With equal row scales the path stays exponential.
    const BoxMLCP e = MurtyEqualRowScales(n);
    const SolveResult re = solver.Solve(e, raw);
    ExpectSolved(e, re);
    EXPECT_GE(re.iterations, 1 << (n - 1)) << "n = " << n;
    EXPECT_LE(re.iterations, (1 << n) + 1) << "n = " << n;
  }
}

TEST(LemkeSolver, PivotLimitIsIterationLimit) {
  LemkeSolver solver;
  SolverOptions options;
  options.max_iterations = 50;
  options.polish = false;  // the raw algorithm's status
  const SolveResult r = solver.Solve(MurtyEqualRowScales(12), options);
  EXPECT_EQ(r.status, SolveStatus::kIterationLimit);
  EXPECT_EQ(r.iterations, 50);
  EXPECT_FALSE(r.message.empty());
}

TEST(LemkeSolver, TimeLimit) {
  LemkeSolver solver;
  SolverOptions options;
  options.time_limit_seconds = 1e-7;
  options.polish = false;
  const SolveResult r = solver.Solve(MurtyEqualRowScales(19), options);
  EXPECT_EQ(r.status, SolveStatus::kTimeLimit);
}

TEST(LemkeSolver, SiconosLcpFiles) {
  // Lemke processes P-, PSD and copositive-plus matrices; these files all have solutions and are solved.
  const char* must_solve[] = {
      "lcp_exp_murty.dat", "lcp_exp_murty2.dat",    "lcp_CPS_1.dat",  "lcp_CPS_2.dat",      "lcp_CPS_4.dat",
      "lcp_CPS_4bis.dat",  "lcp_CPS_5.dat",         "lcp_trivial.dat", "lcp_deudeu.dat",    "lcp_ortiz.dat",
      "lcp_mmc.dat",       "lcp_enum_fails.dat",    "lcp_tobenna.dat", "lcp_Pang_isolated_sol.dat",
      "lcp_inf_sol_perturbed.dat"};
  LemkeSolver solver;
  for (const char* file : must_solve) {
    DenseMatrix M;
    Vector q;
    ASSERT_TRUE(ReadSiconosLcp(std::string("lcp/") + file, &M, &q)) << file;
    const BoxMLCP p = BoxMLCP::LCP(M, q, file);
    ExpectSolved(p, solver.Solve(p), 1e-10);
  }
  {  // The perturbed isolated-solution problem has no solution at all (checked by enumeration): a ray.
    DenseMatrix M;
    Vector q;
    ASSERT_TRUE(ReadSiconosLcp("lcp/lcp_Pang_isolated_sol_perturbed.dat", &M, &q));
    EXPECT_FALSE(LcpHasSolutionByEnumeration(M, q));
    const SolveResult r = solver.Solve(BoxMLCP::LCP(M, q));
    EXPECT_EQ(r.status, SolveStatus::kRayTermination) << r.message;
  }
  {  // A bimatrix game (CPS Example 4.4.23): solutions exist, but with d = e Lemke leaves on a ray at once
     // (z_n enters against a zero diagonal block); Lemke-Howson is the method for games. The class (zero diagonal,
     // infinite bounds) can lack a solution, so the ray is reported as such, without a claim of a proof.
    DenseMatrix M;
    Vector q;
    ASSERT_TRUE(ReadSiconosLcp("lcp/lcp_CPS_3.dat", &M, &q));
    EXPECT_TRUE(LcpHasSolutionByEnumeration(M, q));
    const BoxMLCP p = BoxMLCP::LCP(M, q);
    SolverOptions raw;
    raw.polish = false;
    const SolveResult r = solver.Solve(p, raw);
    EXPECT_EQ(r.status, SolveStatus::kRayTermination) << r.message;
    EXPECT_NE(r.message.find("no solution found by this method"), std::string::npos) << r.message;
    // With the base layer's polish (on by default) any answer is verified: solved with a residual checked here, or
    // not solved.
    const SolveResult polished = solver.Solve(p);
    if (polished.solved()) {
      EXPECT_LE(RelativeNaturalResidual(p, polished.z), 1e-10);
    } else {
      EXPECT_FALSE(polished.message.empty());
    }
  }
}

TEST(LemkeSolver, RelayBox) {
  LemkeSolver solver;
  {  // scalar relay: z = clamp(−q/m, −1, 1)
    for (double qv : {-3.0, -0.5, 0.0, 0.7, 5.0}) {
      const BoxMLCP p = BoxMLCP::Relay(DenseMatrix::Constant(1, 1, 2.0), Vector::Constant(1, qv), -1.0, 1.0, "relay1");
      const SolveResult r = solver.Solve(p);
      ExpectSolved(p, r);
      EXPECT_NEAR(r.z[0], std::clamp(-qv / 2.0, -1.0, 1.0), 1e-15) << qv;
    }
  }
  for (unsigned seed = 1; seed <= 10; ++seed) {
    for (int n : {2, 5, 12}) {
      const Known k = Generate(n, Family::kNonsymmetricPd, Bounds::kRelay, seed);
      const SolveResult r = solver.Solve(k.problem);
      ExpectSolved(k.problem, r);
      EXPECT_LE((r.z - k.z_star).cwiseAbs().maxCoeff(), 1e-9) << k.problem.name();
    }
  }
}

TEST(LemkeSolver, UpperOnlyRows) {
  // z ≤ u, w ≤ 0, (u − z)·w = 0. Scalar: M = 1, q = 1, u = 2 → z = −1 (inside, w = 0); q = −5 → z = 2.
  LemkeSolver solver;
  for (double qv : {1.0, -5.0}) {
    const BoxMLCP p(DenseMatrix::Identity(1, 1), Vector::Constant(1, qv), Vector::Constant(1, -kInf),
                    Vector::Constant(1, 2.0), "upper1");
    const SolveResult r = solver.Solve(p);
    ExpectSolved(p, r);
    EXPECT_NEAR(r.z[0], std::min(-qv, 2.0), 1e-15);
  }
  DenseMatrix M(3, 3);
  M << 3, 1, 0, -1, 2, 0.5, 0, -0.5, 4;
  const BoxMLCP p(M, Vector{{1.0, -7.0, 2.0}}, Vector::Constant(3, -kInf), Vector{{0.5, 1.0, 0.0}}, "upper3");
  ExpectSolved(p, solver.Solve(p));
}

TEST(LemkeSolver, MixedBoundsWithFreeRows) {
  using FreeRows = LemkeOptions::FreeRows;
  for (FreeRows method : {FreeRows::kAutomatic, FreeRows::kSchur, FreeRows::kBasic, FreeRows::kSplit}) {
    LemkeSolver solver;
    solver.mutable_options().free_row_method = method;
    int with_free_rows = 0;
    for (unsigned seed = 1; seed <= 20; ++seed) {
      for (int n : {1, 3, 6, 16, 40}) {
        for (Family family : {Family::kSpd, Family::kNonsymmetricPd}) {
          const Known k = Generate(n, family, Bounds::kMixed, seed);
          const SolveResult r = solver.Solve(k.problem);
          ExpectSolved(k.problem, r);
          if (r.solved()) {
            EXPECT_LE((r.z - k.z_star).cwiseAbs().maxCoeff(), 1e-8 * (1.0 + k.z_star.cwiseAbs().maxCoeff()))
                << k.problem.name() << " method=" << ToString(method);
          }
          // Detail free_row_mode names the method that handled the free rows: the one asked for (a definite
          // M_FF needs no fallback), or under auto never auto itself.
          const bool free_rows = (k.problem.l().array() == -kInf && k.problem.u().array() == kInf).any();
          EXPECT_EQ(FreeRowModeOf(r).has_value(), free_rows) << k.problem.name();
          if (!free_rows) continue;
          ++with_free_rows;
          if (method == FreeRows::kAutomatic) {
            EXPECT_NE(FreeRowModeOf(r), FreeRows::kAutomatic) << k.problem.name();
          } else {
            EXPECT_EQ(FreeRowModeOf(r), method) << k.problem.name();
          }
        }
      }
    }
    EXPECT_GT(with_free_rows, 0) << "the mixed bounds include free rows";
  }
}

TEST(LemkeSolver, FreeRowMethodNamesRoundTrip) {
  using FreeRows = LemkeOptions::FreeRows;
  for (FreeRows method : {FreeRows::kAutomatic, FreeRows::kSchur, FreeRows::kBasic, FreeRows::kSplit}) {
    EXPECT_EQ(FreeRowsFromString(ToString(method)), method);
  }
  EXPECT_FALSE(FreeRowsFromString("schur-only").has_value());
  EXPECT_FALSE(FreeRowsFromString("2").has_value()) << "a name, not the old number";
  // JSON and Python print the detail by its name.
  SolveResult r;
  kFreeRowModeDetail.Set(&r, FreeRows::kBasic);
  ASSERT_EQ(r.num_details, 1);
  EXPECT_EQ(SolveResult::CodeText(r.details[0]), "basic");
}

TEST(LemkeSolver, SingularFreeBlockKeepsFreeVariablesBasic) {
  // PSD M whose free block M_FF = 0 is singular: no Schur complement. The free z enters the starting basis through
  // a 2×2 block pivot with the bounded row. Row 0: z1 = 2; row 1: −z0 + z1 + 1 = 0 (z1 > 0) → z0 = 3.
  DenseMatrix M(2, 2);
  M << 0, 1, -1, 1;
  const BoxMLCP p(M, Vector{{-2.0, 1.0}}, Vector{{-kInf, 0.0}}, Vector{{kInf, kInf}}, "saddle");
  LemkeSolver solver;
  const SolveResult r = solver.Solve(p);
  ExpectSolved(p, r);
  EXPECT_EQ(FreeRowModeOf(r), LemkeOptions::FreeRows::kBasic);
  EXPECT_NEAR(r.z[1], 2.0, 1e-14);
  EXPECT_NEAR(r.z[0], 3.0, 1e-14);

  // A free column of zeros (z0 is arbitrary, row 0 reads 0 = 0): no basis holds z0, the split takes over.
  DenseMatrix M2(2, 2);
  M2 << 0, 0, 0, 1;
  const BoxMLCP p2(M2, Vector{{0.0, -1.0}}, Vector{{-kInf, 0.0}}, Vector{{kInf, kInf}}, "zero_free_column");
  const SolveResult r2 = solver.Solve(p2);
  ExpectSolved(p2, r2);
  EXPECT_EQ(FreeRowModeOf(r2), LemkeOptions::FreeRows::kSplit);
  EXPECT_NEAR(r2.z[1], 1.0, 1e-14);
}

TEST(LemkeSolver, FixedVariables) {
  DenseMatrix M(2, 2);
  M << 2, 1, 1, 2;
  const BoxMLCP p(M, Vector{{-4.0, 1.0}}, Vector{{0.0, 0.5}}, Vector{{kInf, 0.5}}, "fixed");
  LemkeSolver solver;
  const SolveResult r = solver.Solve(p);
  ExpectSolved(p, r);
  EXPECT_EQ(r.z[1], 0.5);
  EXPECT_NEAR(r.z[0], 1.75, 1e-15);  // 2 z0 + 0.5 − 4 = 0
}

TEST(LemkeSolver, AllRowsFixedOrFree) {
  LemkeSolver solver;
  DenseMatrix M(3, 3);
  M << 4, 1, 0, 1, 3, 1, 0, 1, 2;
  const Vector q{{1.0, -2.0, 0.5}};
  {  // every row fixed: nothing to pivot, z = l
    const BoxMLCP p(M, q, Vector{{0.1, 0.2, 0.3}}, Vector{{0.1, 0.2, 0.3}}, "all_fixed");
    const SolveResult r = solver.Solve(p);
    ExpectSolved(p, r);
    EXPECT_EQ(r.iterations, 0);
    EXPECT_EQ(r.z[2], 0.3);
  }
  {  // every row free: the Schur elimination is the whole solve, z = −M⁻¹q
    const BoxMLCP p(M, q, Vector::Constant(3, -kInf), Vector::Constant(3, kInf), "all_free");
    const SolveResult r = solver.Solve(p);
    ExpectSolved(p, r);
    EXPECT_EQ(r.iterations, 0);
    const Vector z_star = -M.partialPivLu().solve(q);
    EXPECT_LE((r.z - z_star).cwiseAbs().maxCoeff(), 1e-14);
  }
}

TEST(LemkeSolver, SchurOnlyReportsSingularFreeBlock) {
  DenseMatrix M(2, 2);
  M << 0, 1, -1, 1;
  const BoxMLCP p(M, Vector{{-2.0, 1.0}}, Vector{{-kInf, 0.0}}, Vector{{kInf, kInf}}, "saddle");
  LemkeSolver solver;
  solver.mutable_options().free_row_method = LemkeOptions::FreeRows::kSchur;
  const SolveResult r = solver.Solve(p);
  EXPECT_EQ(r.status, SolveStatus::kSingular);
  EXPECT_NE(r.message.find("free block"), std::string::npos) << r.message;
}

TEST(LemkeSolver, BadlyScaledRelayIsPolished) {
  // ‖M‖ ~ 1e6 with q ~ 1e-5: the shift z = l + x puts M·l ~ 1e6 into the LCP while the solution |z| ~ 1e-11 sits
  // strictly inside the box. Lemke alone loses the digits of q; the active-set polish recovers z* = −M⁻¹q.
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  LemkeSolver solver;
  for (int n : {3, 9, 20}) {
    DenseMatrix M(n, n);
    for (int i = 0; i < n; ++i) {
      double off = 0.0;
      for (int j = 0; j < n; ++j) {
        M(i, j) = normal(rng);
        if (j != i) off += std::abs(M(i, j));
      }
      M(i, i) = off + 0.1;  // diagonally dominant: a P-matrix
    }
    M *= 1e6;
    Vector q(n);
    for (int i = 0; i < n; ++i) q[i] = 1e-5 * normal(rng);
    const BoxMLCP p = BoxMLCP::Relay(M, q, -1.0, 1.0, "scaled_relay" + std::to_string(n));
    const SolveResult r = solver.Solve(p);
    ExpectSolved(p, r);
    const Vector z_star = -M.partialPivLu().solve(q);
    EXPECT_LE((r.z - z_star).cwiseAbs().maxCoeff(), 1e-6 * z_star.cwiseAbs().maxCoeff());
    EXPECT_EQ(r.GetDetail("polished"), 1.0);
  }
}

TEST(LemkeSolver, RandomPositiveDefiniteAgreeWithKnownSolution) {
  LemkeSolver solver;
  for (Family family : {Family::kSpd, Family::kNonsymmetricPd}) {
    for (Bounds bounds : {Bounds::kLcp, Bounds::kRelay, Bounds::kMixed}) {
      for (int n : {1, 2, 4, 8, 16, 32, 64}) {
        for (unsigned seed = 100; seed < 103; ++seed) {
          const Known k = Generate(n, family, bounds, seed);
          const SolveResult r = solver.Solve(k.problem);
          ExpectSolved(k.problem, r);
          EXPECT_LE((r.z - k.z_star).cwiseAbs().maxCoeff(), 1e-8 * (1.0 + k.z_star.cwiseAbs().maxCoeff()))
              << k.problem.name();
        }
      }
    }
  }
}

TEST(LemkeSolver, SiconosMlcpFiles) {
  // Circuit and relay MLCPs (free block first). Several have a singular free block (diode bridges, buck
  // converters, PD): the automatic method keeps the free variables basic there. All of them are solved.
  const char* files[] = {"Buck2_mlcp.dat",        "BuckConverter_mlcp.dat", "BuckFirstStep_mlcp.dat",
                         "PDSym_mlcp.dat",        "PD_mlcp.dat",            "RCD_mlcp.dat",
                         "RLCD_mlcp.dat",         "deltasigma2_mlcp.dat",   "deltasigma_mlcp.dat",
                         "deudeu_mlcp.dat",       "diodeBridge20_mlcp.dat", "diodeBridge40_mlcp.dat",
                         "diodeBridge_mlcp.dat",  "m2n1_mlcp.dat",          "m3n2_mlcp.dat",
                         "relay2_mlcp.dat",       "relay3_mlcp.dat"};
  using FreeRows = LemkeOptions::FreeRows;
  for (FreeRows method : {FreeRows::kAutomatic, FreeRows::kBasic, FreeRows::kSplit}) {
    LemkeSolver solver;
    solver.mutable_options().free_row_method = method;
    int solved = 0;
    for (const char* file : files) {
      DenseMatrix M;
      Vector q, l, u;
      ASSERT_TRUE(ReadSiconosMlcp(std::string("mlcp/") + file, &M, &q, &l, &u)) << file;
      const BoxMLCP p(M, q, l, u, file);
      const SolveResult r = solver.Solve(p);
      if (method != FreeRows::kSplit) {
        ExpectSolved(p, r);
      }
      if (r.solved()) {
        ++solved;
        EXPECT_LE(RelativeNaturalResidual(p, r.z), 1e-10) << file;
      } else {
        EXPECT_FALSE(r.message.empty()) << file;
      }
    }
    // The x⁺ − x⁻ split loses the structure of these non-monotone circuits: it is only the last resort.
    if (method == FreeRows::kSplit) {
      EXPECT_GE(solved, 4);
    }
  }
}

TEST(LemkeSolver, RepeatedSolveIsBitwiseIdentical) {
  LemkeSolver solver;
  const Known k = Generate(24, Family::kNonsymmetricPd, Bounds::kMixed, 7);
  SolveResult first, again;
  solver.Solve(k.problem, SolverOptions{}, &first);
  ExpectSolved(k.problem, first);
  for (int rep = 0; rep < 3; ++rep) {
    solver.Solve(k.problem, SolverOptions{}, &again);
    ASSERT_EQ(again.status, first.status);
    EXPECT_EQ(again.iterations, first.iterations);
    EXPECT_EQ(std::memcmp(again.z.data(), first.z.data(), sizeof(double) * first.z.size()), 0);
  }
  // A different problem in between, then the first again: still identical.
  solver.Solve(Murty(6), SolverOptions{}, &again);
  solver.Solve(k.problem, SolverOptions{}, &again);
  EXPECT_EQ(std::memcmp(again.z.data(), first.z.data(), sizeof(double) * first.z.size()), 0);
}

TEST(LemkeSolver, WarmStartIsIgnored) {
  LemkeSolver solver;
  const Known k = Generate(10, Family::kSpd, Bounds::kLcp, 3);
  SolverOptions cold, warm;
  warm.warm_start = k.z_star;
  const SolveResult a = solver.Solve(k.problem, cold);
  const SolveResult b = solver.Solve(k.problem, warm);
  ExpectSolved(k.problem, b);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(std::memcmp(a.z.data(), b.z.data(), sizeof(double) * a.z.size()), 0);
}

TEST(LemkeSolver, RowScaledCoveringVector) {
  LemkeSolver solver;
  solver.mutable_options().covering_vector = LemkeOptions::Covering::kRowScaled;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Known k = Generate(20, Family::kNonsymmetricPd, Bounds::kMixed, seed);
    ExpectSolved(k.problem, solver.Solve(k.problem));
  }
  ExpectSolved(Murty(8), solver.Solve(Murty(8)));
}

TEST(LemkeSolver, ReinversionKeepsAccuracy) {
  LemkeSolver solver;
  solver.mutable_options().refactor_interval = 3;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Known k = Generate(30, Family::kNonsymmetricPd, Bounds::kRelay, seed);
    const SolveResult r = solver.Solve(k.problem);
    ExpectSolved(k.problem, r);
    EXPECT_GT(r.GetDetail("reinversions"), 0.0);
    EXPECT_LE((r.z - k.z_star).cwiseAbs().maxCoeff(), 1e-9);
  }
}

// A 2×2 P-matrix box problem whose rows are scaled by 1e6 and 1e-5 can be "solved" at the wrong vertex: leaving the
// pivot path early (z0_negligible_exit) on the relative residual alone, scaled by 1 + ‖q‖∞ ≈ 1e6, cannot see the
// 1e-5 row's sign condition. So Lemke gets the row-equilibrated problem, and the early exit requires the
// residual in units of z as well; the equilibrated analogue (one bound row's multiplier 1e12 times its row, so that
// its q dwarfs the other row's) is covered too. The planted z* must come back to 1e-12, polish on and off.
TEST(LemkeSolver, ScaledRowsLeftThePathEarlyAtTheWrongVertex) {
  DenseMatrix spd(2, 2), nonsymmetric(2, 2);
  spd << 2, 1, 1, 3;
  nonsymmetric << 2, -1, 1, 3;  // a P-matrix: diagonal 2, 3 and determinant 7
  struct RowBounds {
    double l, u;
  };
  const RowBounds kinds[] = {{-1.0, 2.0}, {0.0, kInf}, {-kInf, 1.5}, {-1.0, 1.0}};
  LemkeSolver solver;
  int cases = 0;
  for (const DenseMatrix* A : {&spd, &nonsymmetric}) {
    for (const RowBounds& b0 : kinds) {
      for (const RowBounds& b1 : kinds) {
        for (int interior = 0; interior < 2; ++interior) {
          for (int side = 0; side < 2; ++side) {  // the bound row at its lower (0) or upper (1) bound
          for (double multiplier : {0.7, 1e12}) {
            const Vector l{{b0.l, b1.l}}, u{{b0.u, b1.u}};
            // z*: the interior row 35% into its box (3 below an infinite upper bound); the other row at a finite
            // bound, with w* of the sign that keeps it there.
            Vector z(2), w(2);
            const int bound = 1 - interior;
            const bool at_lower = side == 0;
            if (!std::isfinite(at_lower ? l[bound] : u[bound])) continue;
            const double lo = std::isfinite(l[interior]) ? l[interior] : u[interior] - 3.0;
            const double hi = std::isfinite(u[interior]) ? u[interior] : lo + 3.0;
            z[interior] = lo + 0.35 * (hi - lo), w[interior] = 0.0;
            z[bound] = at_lower ? l[bound] : u[bound], w[bound] = at_lower ? multiplier : -multiplier;
            for (const Vector& d : {Vector{{1e6, 1e-5}}, Vector{{1e-5, 1e6}}}) {
              const DenseMatrix M = d.asDiagonal() * (*A);
              const Vector q = d.asDiagonal() * w - M * z;
              const BoxMLCP p(M, q, l, u, "scaled2x2_" + std::to_string(cases));
              for (bool polish : {false, true}) {
                SolverOptions options;
                options.polish = polish;
                const SolveResult r = solver.Solve(p, options);
                ASSERT_EQ(r.status, SolveStatus::kSolved) << p.name() << " polish " << polish << ": " << r.message;
                EXPECT_LE((r.z - z).cwiseAbs().maxCoeff(), 1e-12)
                    << p.name() << " polish " << polish << ": z = " << r.z.transpose() << ", z* = " << z.transpose();
              }
              ++cases;
            }
          }
          }
        }
      }
    }
  }
  // Per matrix: 4 × 4 bound kinds × 2 interior rows, 6 of the 8 (kind, side) pairs finite, 2 multipliers, 2 scalings.
  EXPECT_EQ(cases, 2 * 4 * 2 * 6 * 2 * 2);
}

// The small-h relay family: W = h·G with G a fixed nonsymmetric 6×6 matrix whose symmetric part is
// positive definite (eigenvalues 1 … 300; G's condition ≈ 230), planted s* with rows at +1, at −1 and inside,
// q = −W s* + h·c with the slack c of the sign that keeps each bound row at its bound. At h = 1e-8 a wrong active
// set (|s − s*|∞ = 1) leaves a residual of order h, small enough to pass as solved; lemke must not return it.
DenseMatrix RelayFamilyG() {
  constexpr int n = 6;
  std::mt19937 rng(2026);
  std::normal_distribution<double> normal(0.0, 1.0);
  DenseMatrix X(n, n), K(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) X(i, j) = normal(rng), K(i, j) = normal(rng);
  }
  const DenseMatrix Q = Eigen::HouseholderQR<DenseMatrix>(X).householderQ();
  Vector lambda(n);
  for (int i = 0; i < n; ++i) lambda[i] = std::pow(300.0, i / (n - 1.0));  // 1 … 300
  return Q * lambda.asDiagonal() * Q.transpose() + 0.5 * (K - K.transpose());
}

TEST(LemkeSolver, SmallStepRelayReturnedAWrongActiveSet) {
  const DenseMatrix G = RelayFamilyG();
  const DenseMatrix S = 0.5 * (G + G.transpose());
  ASSERT_EQ(S.llt().info(), Eigen::Success);
  const Vector sigma = Eigen::JacobiSVD<DenseMatrix>(G).singularValues();
  const double condition = sigma[0] / sigma[sigma.size() - 1];
  EXPECT_GT(condition, 100.0);
  EXPECT_LT(condition, 1000.0);
  const Vector s_star{{1.0, -1.0, 0.3, 1.0, -0.55, -1.0}};
  const Vector c{{-0.8, 0.5, 0.0, -2.0, 0.0, 1.3}};  // ≤ 0 at +1 (w ≤ 0), ≥ 0 at −1, 0 inside
  LemkeSolver solver;
  for (double h : {1e-2, 1e-4, 1e-6, 1e-8, 1e-10}) {
    const DenseMatrix W = h * G;
    const Vector q = -W * s_star + h * c;
    const BoxMLCP p = BoxMLCP::Relay(W, q, -1.0, 1.0, "relay_h" + std::to_string(h));
    for (bool polish : {false, true}) {
      SolverOptions options;
      options.polish = polish;
      const SolveResult r = solver.Solve(p, options);
      ASSERT_EQ(r.status, SolveStatus::kSolved) << "h = " << h << " polish " << polish << ": " << r.message;
      EXPECT_LE((r.z - s_star).cwiseAbs().maxCoeff(), 1e-9) << "h = " << h << " polish " << polish;
    }
  }
}

}  // namespace
}  // namespace smcbench
