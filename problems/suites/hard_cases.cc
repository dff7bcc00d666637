// The hard-case suite. Every case states why it is hard and why its expected outcome is right; the generated ones
// reuse the families (families.h) under their own ids, the Siconos ones are read from the peer collection.
// The paper's labels cited here (eq:..., neuf, Lemma yahoo): docs/glossary.md; its scenes S1-S11: docs/scenes.md.
#include "problems/suites/hard_cases.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include "problems/io/siconos_format.h"
#include "problems/library/matrix_tags.h"
#include "problems/scenes/scene.h"
#include "problems/scenes/registry.h"
#include "problems/suites/families.h"
#include "problems/suites/generation_detail.h"

namespace smcbench {
namespace {

using suites_detail::MakeProblem;
using suites_detail::PlantedRow;
using suites_detail::PlantRow;
using suites_detail::Random;
using suites_detail::PlantedState;
using suites_detail::StepText;

// Gives a problem its hard-suite identity: id "hard/<kind>/<name>", the kind as first tag, the reason.
LibraryProblem Hard(LibraryProblem p, const std::string& kind, const std::string& name, const std::string& why) {
  if (p.id.rfind("hard/", 0) != 0) p.metadata["family_id"] = p.id;
  p.id = "hard/" + kind + "/" + name;
  p.problem.set_name(p.id);
  if (p.tags.empty() || p.tags.front() != kind) p.tags.insert(p.tags.begin(), kind);
  p.metadata["why"] = why;
  return p;
}

LibraryProblem Handmade(const std::string& kind, const std::string& name, BoxMLCP problem, MatrixTags tags,
                        ExpectedOutcome expected, Vector solution, const std::string& why) {
  LibraryProblem p = MakeProblem("hard/" + kind + "/" + name, "handmade:" + name, std::move(problem), tags, expected);
  p.tags = {kind};
  p.solution = std::move(solution);
  p.metadata["why"] = why;
  return p;
}

// The 3×3 "cycling" LCP of Drake's Lemke tests (solvers/test/unrevised_lemke_solver_test.cc, testCycling),
// generalized to odd n: M_ii = 1, M_i,i+1 (cyclically) = 2, q = −e. Every ratio of Lemke's first step ties
// (q/e constant), the degenerate start at which a pivot rule without lexicographic (or least-index) resolution
// can revisit bases (Cottle, Pang & Stone 1992, §4.9). det M = 1 + 2ⁿ > 0 for odd n and every proper principal
// submatrix is, up to a permutation, triangular with unit diagonal, so M is a P-matrix; z* = e/3 (row sums 3).
// The symmetric part I + (S + Sᵀ) (S the cyclic shift) has eigenvalues 1 + 2cos(2πk/n), whose minimum is ≤ 0 for
// n ≥ 3 (exactly 0 for n = 3): not PD.
LibraryProblem Circulant(int n) {
  DenseMatrix M = DenseMatrix::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    M(i, i) = 1.0;
    M(i, (i + 1) % n) = 2.0;
  }
  Vector solution = Vector::Constant(n, 1.0 / 3.0);
  return Handmade("cycling", "circulant-" + std::to_string(n), BoxMLCP::LCP(std::move(M), Vector::Constant(n, -1.0)),
                  {Tristate::kNo, Tristate::kNo, Tristate::kYes}, ExpectedOutcome::kSolvable, std::move(solution),
                  "q = -e ties every ratio of Lemke's first step (degenerate start; Drake's testCycling for n = 3)");
}

// Upper triangular, 1 on the diagonal and 2 above, q = −e: Siconos' lcp_exp_murty.dat (n = 6) and test problem
// 10.2.1 of Floudas et al., "Handbook of Test Problems in Local and Global Optimization" (n = 16). Unique solution
// z* = e_n (w_i = 2 − 1 = 1 above the last row); the first ratio test ties on every row.
LibraryProblem UpperMurtyAllOnes(int n) {
  DenseMatrix M = DenseMatrix::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    M(i, i) = 1.0;
    for (int j = i + 1; j < n; ++j) M(i, j) = 2.0;
  }
  Vector solution = Vector::Zero(n);
  solution[n - 1] = 1.0;
  return Handmade("cycling", "murty-upper-qones-" + std::to_string(n),
                  BoxMLCP::LCP(std::move(M), Vector::Constant(n, -1.0)), {Tristate::kNo, Tristate::kNo, Tristate::kYes},
                  ExpectedOutcome::kSolvable, std::move(solution),
                  "Murty's matrix with q = -e: all n ratios of the first Lemke step tie");
}

// SPD with eigenvalues 10^(−c k/(n−1)), k = 0..n−1 (condition number 10^c), eigenvectors from three Householder
// reflections of random vectors; symmetrized after the product, so exactly symmetric. z* planted, q = w* − M z*
// (z* solves the stored problem to rounding: its free rows may differ from the exact solution by ~10^c·ε, which the
// certified reference, not z*, resolves).
LibraryProblem NearSingular(bool relay, int n, std::uint64_t seed, int log10_condition = 12) {
  Random rng(seed);
  DenseMatrix Q = DenseMatrix::Identity(n, n);
  for (int r = 0; r < 3; ++r) {
    Vector v(n);
    for (int i = 0; i < n; ++i) v[i] = rng.Uniform(-1.0, 1.0);
    const double vv = v.squaredNorm();
    Q -= (2.0 / vv) * (Q * v) * v.transpose();  // Q ← Q (I − 2vvᵀ/vᵀv)
  }
  Vector lambda(n);
  for (int k = 0; k < n; ++k) lambda[k] = std::pow(10.0, -static_cast<double>(log10_condition) * k / (n - 1));
  DenseMatrix M = Q * lambda.asDiagonal() * Q.transpose();
  M = (0.5 * (M + M.transpose())).eval();
  const double l = relay ? -1.0 : 0.0;
  const double u = relay ? 1.0 : kInf;
  Vector z(n), w(n);
  for (int i = 0; i < n; ++i) {
    const int pick = rng.Index(relay ? 3 : 2);
    const PlantedState s =
        pick == 0 ? PlantedState::kInside : (pick == 1 ? PlantedState::kAtLower : PlantedState::kAtUpper);
    const PlantedRow row = PlantRow(l, u, s, rng);
    z[i] = row.z;
    w[i] = row.w;
  }
  Vector q(n);
  for (int i = 0; i < n; ++i) {
    double s = 0.0;
    for (int j = 0; j < n; ++j) s += M(i, j) * z[j];
    q[i] = w[i] - s;
  }
  BoxMLCP problem(std::move(M), std::move(q), Vector::Constant(n, l), Vector::Constant(n, u));
  const MatrixTags tags = ClassifyMatrix(problem);  // symmetric, PD (λ_min ≥ 1e-13 ≫ rounding 1e-15), P
  const std::string bounds = relay ? "relay" : "lcp";
  const std::string condition = "1e" + std::to_string(log10_condition);
  LibraryProblem p =
      MakeProblem("hard/near-singular/spd-" + bounds + "-m" + std::to_string(n) + "-cond" + condition,
                  "generated:near-singular", std::move(problem), tags, ExpectedOutcome::kSolvable);
  p.tags = {"near-singular", bounds};
  p.seed = seed;
  p.solution = std::move(z);
  p.metadata["why"] = "SPD with condition number " + condition + ": Newton systems and pivots lose " +
                      std::to_string(log10_condition) + " digits";
  p.metadata["condition_number"] = condition;
  return p;
}

// A 2×2 box problem with a nonsymmetric P-matrix M0 = [[4, −1], [2, 3]] (symmetric part [[4, ½], [½, 3]], PD) whose
// rows are then scaled by 1e6 and 1e-5. z* = (0.25, 0.5): row 1 strictly inside [−1, 1] (w* = 0), row 2 at its upper
// bound 0.5 of [−2, 0.5] with w* = −0.7 < 0; q0 = w* − M0 z*. A positive row scaling d leaves the solution set alone
// (d_i w_i has the sign of w_i) and keeps every principal minor positive: P-matrix, unique solution z*. The scaled
// matrix's symmetric part is indefinite (its determinant 4e6·3e-5 − (5e5)² < 0). It caught lemke, working on the
// unscaled rows, leaving its pivot path early (z0 negligible) at the wrong vertex.
LibraryProblem RowScaledPMatrix() {
  const double d[2] = {1e6, 1e-5};
  const double M0[2][2] = {{4.0, -1.0}, {2.0, 3.0}};
  const double z[2] = {0.25, 0.5};
  const double w[2] = {0.0, -0.7};
  DenseMatrix M(2, 2);
  Vector q(2), solution(2), l(2), u(2);
  for (int i = 0; i < 2; ++i) {
    double Mz = 0.0;
    for (int j = 0; j < 2; ++j) {
      M(i, j) = d[i] * M0[i][j];
      Mz += M0[i][j] * z[j];
    }
    q[i] = d[i] * (w[i] - Mz);
    solution[i] = z[i];
  }
  l << -1.0, -2.0;
  u << 1.0, 0.5;
  LibraryProblem p = Handmade("row-scaling", "pmatrix-1e6-1e-5", BoxMLCP(std::move(M), std::move(q), l, u),
                              {Tristate::kNo, Tristate::kNo, Tristate::kYes}, ExpectedOutcome::kSolvable,
                              std::move(solution),
                              "a 2x2 P-matrix box problem with rows scaled by 1e6 and 1e-5: lemke left the pivot path "
                              "early at the wrong vertex");
  p.tags.push_back("box");
  p.metadata["row_scales"] = "1e6 1e-5";
  return p;
}

// A P-matrix box-MLCP (families' nonsymmetric P-matrix, mixed bounds: free, LCP, upper-only and box rows) with M and
// q scaled together by `factor`: (factor·M) z + factor·q = factor·(w − v) has the same solutions for factor > 0, and
// factor·M is still a P-matrix. At 1e±150 it caught backends reporting different, wrong points as solved.
LibraryProblem JointlyScaled(double factor, const std::string& name) {
  LibraryProblem base = RandomFamilyProblem(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kMixed, 8, 1);
  DenseMatrix M = factor * base.problem.dense_matrix();
  Vector q = factor * base.problem.q();
  LibraryProblem p = base;
  p.problem = BoxMLCP(std::move(M), std::move(q), base.problem.l(), base.problem.u());
  // The matrix tags of the construction hold for factor·M too (a positive factor changes no sign of a minor).
  p = Hard(std::move(p), "joint-scaling", name,
           "M and q scaled together by " + NumberText(factor) +
               ": same solution; backends reported different, wrong points as solved");
  p.metadata["scale_factor"] = NumberText(factor);
  return p;
}

// S11 at the scene's own initial state: the first implicit step's relay problem, q = −(C (R x0 + p) + D) as the
// stepper builds it (eq:TDS3). m = 1 and W > 0, so the unique solution is z = Π_[−1,1](−q/W).
LibraryProblem ParasiticFirstStep(double h) {
  const std::unique_ptr<Scene> scene = LoadScene("parasitic");
  const LinearPlant* linear = scene->linear_plant();
  if (linear == nullptr) throw InvalidInputError("HardSuite: scene 'parasitic' is not a linear scene");
  SimulationSettings settings = scene->defaults();
  settings.method = Method::kImplicit;
  settings.h = h;
  const OneStepData step = linear->Discretization(settings);
  DenseMatrix W = step.OneStepMatrix();
  Vector x = step.R * settings.x0;
  if (step.p.size() == x.size()) x += step.p;
  Vector q = -(step.C * x);
  if (step.D.size() == q.size()) q -= step.D;
  if (W.rows() != 1 || !(W(0, 0) > 0.0)) {
    throw InvalidInputError("HardSuite: scene 'parasitic' no longer has a 1x1 positive one-step matrix");
  }
  Vector z(1);
  z[0] = std::clamp(-q[0] / W(0, 0), -1.0, 1.0);
  const MatrixTags tags{Tristate::kYes, Tristate::kYes, Tristate::kYes};  // 1×1, positive
  LibraryProblem p = MakeProblem("hard/parasitic/first-step-h" + StepText(h), "capture:parasitic",
                                 BoxMLCP::Relay(std::move(W), std::move(q)), tags, ExpectedOutcome::kSolvable);
  p.tags = {"parasitic", "h-to-zero", "relay"};
  p.solution = std::move(z);
  p.metadata["scene"] = "parasitic";
  p.metadata["h"] = NumberText(h);
  p.metadata["theta"] = NumberText(settings.theta);
  p.metadata["step"] = "0";
  p.metadata["why"] = "S11 relative degree 3: W = O(h^3) against q = O(h^2), the step saturates the sign";
  return p;
}

struct SiconosCase {
  const char* file;
  ExpectedOutcome expected;
  const char* extra_tag;  // or nullptr
  const char* why;
};

// The files some backend fails on in results/siconos-collection.md, and the classics the README names. Expected
// outcome: solvable where a backend reached the tolerance with a residual recomputed by the merit function;
// infeasible only with a proof (given in `why`).
constexpr SiconosCase kSiconosCases[] = {
    {"lcp/lcp_CPS_3.dat", ExpectedOutcome::kSolvable, nullptr,
     "bimatrix game (Cottle-Pang-Stone ex. 4.4.23): Lemke ends on a secondary ray; newton, enum, ipopt solve it"},
    {"lcp/lcp_Pang_isolated_sol_perturbed.dat", ExpectedOutcome::kInfeasible, "infeasible",
     "row 1 has M_1j <= 0 for every j and q_1 = -1e-4 < 0, so w_1 < 0 for every z >= 0: no solution"},
    {"lcp/lcp_Pang_isolated_sol.dat", ExpectedOutcome::kSolvable, nullptr,
     "isolated solution z = (1, 0, 0), the unperturbed twin of the infeasible case (q_1 = 0)"},
    {"lcp/lcp_inf_sol_perturbed.dat", ExpectedOutcome::kSolvable, "non-unique",
     "a ray of solutions z = (1, t, t + 1e-4), t >= 0"},
    {"lcp/lcp_tobenna.dat", ExpectedOutcome::kSolvable, nullptr, "n = 40 LCP: Lemke solves it, newton and ipopt stall"},
    {"lcp/lcp_enum_fails.dat", ExpectedOutcome::kSolvable, nullptr,
     "named by Siconos for a failure of its enumeration solver; solved here by every backend that runs"},
    {"lcp/lcp_exp_murty2.dat", ExpectedOutcome::kSolvable, "murty",
     "Murty's exponential example for Lemke, n = 6 (2^6 pivots)"},
    {"mlcp/Buck2_mlcp.dat", ExpectedOutcome::kSolvable, nullptr,
     "buck converter MLCP (n + m = 32, free rows): newton stalls near 1e-6"},
    {"relay/relay1.dat", ExpectedOutcome::kSolvable, nullptr, "relay n = 15: PSOR stalls near 7e-3"},
};

}  // namespace

std::vector<std::string> HardSiconosFiles() {
  std::vector<std::string> files;
  for (const SiconosCase& c : kSiconosCases) files.emplace_back(c.file);
  return files;
}

ProblemSet HardSuite(const std::string& siconos_dir) {
  ProblemSet set;
  set.name = "hard";
  set.description =
      "named hard cases with expected outcomes: degenerate, cycling-prone, near-singular, h -> 0, "
      "non-unique, infeasible, S11 parasitic, hard Siconos files";
  auto& out = set.problems;

  // Degenerate: z* at a bound with w* = 0.
  out.push_back(Hard(RandomFamilyProblem(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 16, 1, 0.5),
                     "degenerate", "spd-lcp-m16-half", "half the rows have z* = 0 and w* = 0 (weak complementarity)"));
  out.push_back(Hard(RandomFamilyProblem(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kRelay, 12, 2, 1.0),
                     "degenerate", "pmatrix-relay-m12-all", "every row sits at a bound of [-1, 1] with w* = 0"));
  out.push_back(Hard(RandomFamilyProblem(MatrixFamily::kDiagonallyDominant, BoundKind::kMixed, 24, 3, 0.3),
                     "degenerate", "diagdom-mixed-m24",
                     "30% degenerate rows among free, LCP, upper-only and box rows"));
  out.push_back(Hard(RandomFamilyProblem(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kLCP, 8, 4, 1.0),
                     "degenerate", "spd-lcp-m8-q0", "q = 0: z* = 0 and w* = 0 on every row, the fully degenerate LCP"));

  // Cycling-prone for Lemke.
  out.push_back(Circulant(3));
  out.push_back(Circulant(7));
  out.push_back(UpperMurtyAllOnes(8));

  // Near-singular.
  out.push_back(NearSingular(true, 12, 1));
  out.push_back(NearSingular(false, 12, 2));
  {
    LibraryProblem p = NearSingular(false, 3, 3, 13);
    p.id = "hard/near-singular/spd-lcp-cond1e13";
    p.problem.set_name(p.id);
    p.metadata["why"] = "3x3 SPD LCP with condition 1e13: enum answered infeasible, but a P-matrix LCP always has a "
                        "solution";
    out.push_back(std::move(p));
  }

  // Small h: W = h G with every datum O(h) (families.h, small-h family).
  out.push_back(Hard(SmallHPMatrixProblem(4, 2, 1e-8, 12), "small-h", "relay-h1e-8-m4",
                     "W = 1e-8 G (G nonsymmetric PD, condition ~1e2): lemke and enum used to return a wrong active "
                     "set and report solved"));

  // Badly scaled: rows, and M with q together.
  out.push_back(RowScaledPMatrix());
  out.push_back(JointlyScaled(1e-150, "x1e-150"));
  out.push_back(JointlyScaled(1e150, "x1e150"));

  // A free row with M = [0], q = [0]: every z solves it.
  out.push_back(Handmade("free-row", "zero",
                         BoxMLCP(DenseMatrix::Zero(1, 1), Vector::Zero(1), Vector::Constant(1, -kInf),
                                 Vector::Constant(1, kInf)),
                         {Tristate::kYes, Tristate::kNo, Tristate::kNo}, ExpectedOutcome::kSolvable, Vector::Zero(1),
                         "M = [0], q = [0], l = -inf, u = inf: every z solves it; Siconos' mlcp-enum said infeasible"));
  out.back().tags.push_back("non-unique");

  // h → 0 scaling.
  for (const char* scene : {"multi-surface", "filippov", "observer"}) {
    for (double h : {1e-6, 1e-7, 1e-8}) {
      out.push_back(Hard(SceneStepProblem(scene, h, 1), "h-to-zero", std::string(scene) + "-h" + StepText(h),
                         "W = O(h) against q = O(1): a tiny residual says little about z"));
    }
  }

  // Non-unique.
  out.push_back(Hard(PsdSingularProblem(BoundKind::kLCP, 8, 1), "non-unique", "psd-singular-lcp-m8",
                     "M = A^T A singular: a segment of solutions through z*"));
  out.push_back(Hard(PsdSingularProblem(BoundKind::kRelay, 10, 2), "non-unique", "psd-singular-relay-m10",
                     "M = A^T A singular: a segment of solutions through z* inside the box"));
  {
    DenseMatrix M = DenseMatrix::Ones(2, 2);
    Vector solution(2);
    solution << 1.0, 0.0;
    out.push_back(Handmade("non-unique", "ones-2x2", BoxMLCP::LCP(std::move(M), Vector::Constant(2, -1.0)),
                           {Tristate::kYes, Tristate::kNo, Tristate::kNo}, ExpectedOutcome::kSolvable,
                           std::move(solution),
                           "every z >= 0 with z1 + z2 = 1 solves it (Floudas et al. test problem 10.2.2)"));
  }

  // Infeasible: certificate rows (families.cc, NonPInfeasibleProblem).
  out.push_back(Hard(NonPInfeasibleProblem(BoundKind::kLCP, 8, 1), "infeasible", "lcp-m8",
                     "a row with M_ij <= 0 and q_i < 0: w_i < 0 for every z >= 0"));
  out.push_back(Hard(NonPInfeasibleProblem(BoundKind::kMixed, 16, 2), "infeasible", "mixed-m16",
                     "a row with one infinite bound whose (Mz + q)_i has the wrong sign on the whole box"));
  out.push_back(Handmade("infeasible", "negative-1x1",
                         BoxMLCP::LCP(DenseMatrix::Constant(1, 1, -1.0), Vector::Constant(1, -1.0)),
                         {Tristate::kYes, Tristate::kNo, Tristate::kNo}, ExpectedOutcome::kInfeasible, Vector(),
                         "w = -z - 1 < 0 for every z >= 0 (Drake's testFailure)"));
  {
    DenseMatrix M(2, 2);
    M << 0.0, 1.0, -1.0, 0.0;
    out.push_back(Handmade("infeasible", "skew-2x2", BoxMLCP::LCP(std::move(M), Vector::Constant(2, -1.0)),
                           {Tristate::kNo, Tristate::kNo, Tristate::kNo}, ExpectedOutcome::kInfeasible, Vector(),
                           "M skew (PSD, copositive-plus): w_2 = -z_1 - 1 < 0, Lemke must end on a ray"));
  }

  // S11 parasitic.
  for (double h : {1e-3, 1e-4, 1e-5}) out.push_back(ParasiticFirstStep(h));
  out.push_back(Hard(SceneStepProblem("parasitic", 1e-6, 1), "parasitic", "planted-h1e-06",
                     "W = O(h^3) ~ 1e-14 with a planted saturated sign: scaling decides success"));

  // The hard Siconos files.
  if (!siconos_dir.empty()) {
    for (const SiconosCase& c : kSiconosCases) {
      const std::filesystem::path path = std::filesystem::path(siconos_dir) / c.file;
      std::error_code ec;
      if (!std::filesystem::is_regular_file(path, ec)) {
        throw InvalidInputError("HardSuite: Siconos file '" + path.string() + "' not found (siconos_dir = '" +
                                siconos_dir + "')");
      }
      BoxMLCP problem = ReadSiconosFile(path.string());
      const std::string stem = path.stem().string();
      const MatrixTags tags = ClassifyMatrix(problem);
      LibraryProblem p =
          MakeProblem("hard/siconos/" + stem, std::string("siconos:") + c.file, std::move(problem), tags, c.expected);
      p.tags = {"siconos"};
      if (c.extra_tag != nullptr) p.tags.emplace_back(c.extra_tag);
      p.metadata["why"] = c.why;
      p.metadata["file"] = c.file;
      out.push_back(std::move(p));
    }
  }
  set.Validate();
  return set;
}

}  // namespace smcbench
