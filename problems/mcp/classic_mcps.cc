// The classic and hard built-in MCPs (classic_mcps.h). Every F is written once, on the scalar type T (double for
// the backends, __float128 for the certifier), with its Jacobian entries; constants are the double values of the
// published decimals, the same in both precisions.
#include "problems/mcp/classic_mcps.h"

#include <cmath>
#include <memory>
#include <utility>

#include "problems/mcp/builtin_mcp.h"
#include "problems/mcp/scalar_math.h"

namespace smcbench {
namespace {

using mcp_math::Pow;
using mcp_math::Sqrt;

Vector Values(std::initializer_list<double> values) {
  Vector v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double x : values) v[i++] = x;
  return v;
}
Vector Constant(int n, double value) { return Vector::Constant(n, value); }
Vector Nonnegative(int n) { return Vector::Zero(n); }
Vector Unbounded(int n) { return Vector::Constant(n, kInf); }

// Kojima & Shindo (1986), "Extensions of Newton and quasi-Newton methods to systems of PC¹ equations", J. Oper.
// Res. Soc. Japan 29; MCPLIB `kojshin` (Dirkse & Ferris 1995). NCP in R⁴ with two solutions, (1, 0, 3, 0) and
// (√6/2, 0, 0, 1/2); the second is degenerate (x3 = 0 and F3 = 0).
class KojimaShindo final : public BuiltinMcp<KojimaShindo> {
 public:
  KojimaShindo() : BuiltinMcp(Nonnegative(4), Unbounded(4), "kojshin") {}
  template <class T>
  void Function(const T* x, T* F) const {
    F[0] = 3 * x[0] * x[0] + 2 * x[0] * x[1] + 2 * x[1] * x[1] + x[2] + 3 * x[3] - 6;
    F[1] = 2 * x[0] * x[0] + x[0] + x[1] * x[1] + 10 * x[2] + 2 * x[3] - 2;
    F[2] = 3 * x[0] * x[0] + x[0] * x[1] + 2 * x[1] * x[1] + 2 * x[2] + 9 * x[3] - 9;
    F[3] = x[0] * x[0] + 3 * x[1] * x[1] + 2 * x[2] + 3 * x[3] - 3;
  }
  template <class T, class Add>
  void Jacobian(const T* x, Add&& add) const {
    add(0, 0, 6 * x[0] + 2 * x[1]), add(0, 1, 2 * x[0] + 4 * x[1]), add(0, 2, T(1)), add(0, 3, T(3));
    add(1, 0, 4 * x[0] + 1), add(1, 1, 2 * x[1]), add(1, 2, T(10)), add(1, 3, T(2));
    add(2, 0, 6 * x[0] + x[1]), add(2, 1, x[0] + 4 * x[1]), add(2, 2, T(2)), add(2, 3, T(9));
    add(3, 0, 2 * x[0]), add(3, 1, 6 * x[1]), add(3, 2, T(2)), add(3, 3, T(3));
  }
};

// Josephy (1979), "Newton's method for generalized equations", MRC TSR 1965 (Kojima's example); MCPLIB `josephy`.
// The Kojima–Shindo F with rows 2 and 3 changed; solution (√6/2, 0, 0, 1/2).
class Josephy final : public BuiltinMcp<Josephy> {
 public:
  Josephy() : BuiltinMcp(Nonnegative(4), Unbounded(4), "josephy") {}
  template <class T>
  void Function(const T* x, T* F) const {
    F[0] = 3 * x[0] * x[0] + 2 * x[0] * x[1] + 2 * x[1] * x[1] + x[2] + 3 * x[3] - 6;
    F[1] = 2 * x[0] * x[0] + x[0] + x[1] * x[1] + 3 * x[2] + 2 * x[3] - 2;
    F[2] = 3 * x[0] * x[0] + x[0] * x[1] + 2 * x[1] * x[1] + 2 * x[2] + 3 * x[3] - 1;
    F[3] = x[0] * x[0] + 3 * x[1] * x[1] + 2 * x[2] + 3 * x[3] - 3;
  }
  template <class T, class Add>
  void Jacobian(const T* x, Add&& add) const {
    add(0, 0, 6 * x[0] + 2 * x[1]), add(0, 1, 2 * x[0] + 4 * x[1]), add(0, 2, T(1)), add(0, 3, T(3));
    add(1, 0, 4 * x[0] + 1), add(1, 1, 2 * x[1]), add(1, 2, T(3)), add(1, 3, T(2));
    add(2, 0, 6 * x[0] + x[1]), add(2, 1, x[0] + 4 * x[1]), add(2, 2, T(2)), add(2, 3, T(3));
    add(3, 0, 2 * x[0]), add(3, 1, 6 * x[1]), add(3, 2, T(2)), add(3, 3, T(3));
  }
};

// Mathiesen (1987), "An algorithm based on a sequence of linear complementarity problems applied to a Walrasian
// equilibrium model: an example", Math. Prog. 37 (also the GAMS EMP model `mopec_mathiesen`): three goods, one
// activity y turning goods 2 and 3 into good 1 (technology (1, −1, −1)), one consumer with Cobb–Douglas shares
// s = (0.9, 0.1, 0) and endowment b = (0, 5, 3). With the explicit demand s_i (p·b)/p_i, z = (y, p1, p2, p3):
//   F1 = −p1 + p2 + p3,  F_{1+i} = b_i + A_i y − s_i (p·b)/p_i  (excess supply of good i).
// Good 2 is the numéraire (p2 = 1, as in the GAMS model); p1 and p3 are bounded below by 1e-8 (F is undefined at
// p1 = 0). Solution (3, 6, 1, 5), the paper's y* = 3, p* = (6, 1, 5). Unique, by cases: y > 0 gives p1 = 1 + p3;
// p3 at its floor would need y ≤ 3 while F2 = 0 gives y = 0.9(5 + 3p3)/p1 ≈ 4.5; p1 at its floor would need
// y ≥ 4.5e8 > 3; so y = 3 and 3(1 + p3) = 0.9(5 + 3p3), p3 = 5. And y = 0 leaves F2 < 0 for every p1 > 0.
class Mathiesen final : public BuiltinMcp<Mathiesen> {
 public:
  static constexpr double kPriceFloor = 1e-8;
  static constexpr double kShare[3] = {0.9, 0.1, 0.0}, kEndowment[3] = {0.0, 5.0, 3.0}, kTechnology[3] = {1, -1, -1};
  Mathiesen()
      : BuiltinMcp(Values({0.0, kPriceFloor, 1.0, kPriceFloor}), Values({kInf, kInf, 1.0, kInf}), "mathiesen",
                   JacobianKind::kDense, SolutionSetProperty::kUniqueByProof) {}
  template <class T>
  void Function(const T* z, T* F) const {
    const T* p = z + 1;
    const T income = Income(p);
    F[0] = -p[0] + p[1] + p[2];
    for (int i = 0; i < 3; ++i) F[1 + i] = T(kEndowment[i]) + T(kTechnology[i]) * z[0] - T(kShare[i]) * income / p[i];
  }
  template <class T, class Add>
  void Jacobian(const T* z, Add&& add) const {
    const T* p = z + 1;
    const T income = Income(p);
    add(0, 0, T(0)), add(0, 1, T(-1)), add(0, 2, T(1)), add(0, 3, T(1));
    for (int i = 0; i < 3; ++i) {
      add(1 + i, 0, T(kTechnology[i]));
      for (int k = 0; k < 3; ++k) {
        T v = -T(kShare[i]) * T(kEndowment[k]) / p[i];
        if (k == i) v += T(kShare[i]) * income / (p[i] * p[i]);
        add(1 + i, 1 + k, v);
      }
    }
  }

 private:
  template <class T>
  static T Income(const T* p) {
    T income = 0;
    for (int k = 0; k < 3; ++k) income += p[k] * T(kEndowment[k]);
    return income;
  }
};

// Cournot–Nash oligopoly (Murphy, Sherali & Soyster 1982, Math. Prog. 24; Harker 1984, Math. Prog. 30; the GAMS
// model `oligomcp`, whose 5-firm data and start q = 10 are used; its equilibrium is (36.933, 41.818, 43.707,
// 42.659, 39.179)). The 10-firm version keeps the model with the costs c = (5, 3, 8, 5, 1, 3, 7, 4, 6, 3),
// L = 10, β = (1.2, 1, 0.9, 0.6, 1.5, 1, 0.7, 1.1, 0.95, 0.75), γ = 1.2 (our instance: no published solution is
// used). Firm i's marginal cost c_i + (q_i/L_i)^{1/β_i}, inverse demand p(Q) = (5000/Q)^{1/γ},
// F_i(q) = c_i + (q_i/L_i)^{1/β_i} − p(Q)(1 − q_i/(γQ)) (the first-order condition of firm i's profit). Outputs are
// bounded below by 1e-8 (F is undefined at Q = 0). Unique: p is decreasing and convex, Q p(Q) = 5000^{1/γ}Q^{1−1/γ}
// concave and every cost convex (the uniqueness theorem of Murphy–Sherali–Soyster); the equilibrium is interior.
class Cournot final : public BuiltinMcp<Cournot> {
 public:
  static constexpr double kOutputFloor = 1e-8;
  Cournot(std::vector<double> c, std::vector<double> L, std::vector<double> beta, double gamma, std::string name)
      : BuiltinMcp(Constant(static_cast<int>(c.size()), kOutputFloor), Unbounded(static_cast<int>(c.size())),
                   std::move(name), JacobianKind::kDense, SolutionSetProperty::kUniqueByProof),
        c_(std::move(c)), L_(std::move(L)), beta_(std::move(beta)), gamma_(gamma) {}
  template <class T>
  void Function(const T* q, T* F) const {
    const int n = size();
    const T gamma = gamma_;
    T Q = 0;
    for (int i = 0; i < n; ++i) Q += q[i];
    const T p = Pow(T(5000) / Q, 1 / gamma);
    for (int i = 0; i < n; ++i) {
      F[i] = T(c_[i]) + Pow(q[i] / T(L_[i]), 1 / T(beta_[i])) - p * (1 - q[i] / (gamma * Q));
    }
  }
  template <class T, class Add>
  void Jacobian(const T* q, Add&& add) const {
    const int n = size();
    const T gamma = gamma_;
    T Q = 0;
    for (int i = 0; i < n; ++i) Q += q[i];
    const T p = Pow(T(5000) / Q, 1 / gamma), dp = -p / (gamma * Q);
    for (int i = 0; i < n; ++i) {
      const T share = 1 - q[i] / (gamma * Q);
      for (int j = 0; j < n; ++j) {
        // ∂share/∂q_j = −δ_ij/(γQ) + q_i/(γQ²).
        T v = -dp * share - p * (q[i] / (gamma * Q * Q));
        if (i == j) {
          const T e = 1 / T(beta_[i]);
          v += p / (gamma * Q) + e * Pow(q[i] / T(L_[i]), e - 1) / T(L_[i]);
        }
        add(i, j, v);
      }
    }
  }

 private:
  std::vector<double> c_, L_, beta_;
  double gamma_;
};

// A pure exchange economy with Cobb–Douglas consumers (the textbook general-equilibrium MCP, e.g. Mathiesen 1985,
// Rutherford 1995): consumer h owns e_h and spends the share a_hj of its income p·e_h on good j, so
// F_j(p) = Σ_h e_hj − Σ_h a_hj (p·e_h)/p_j (excess supply) ⟂ p_j. Good 1 is the numéraire (p1 = 1), the other
// prices are bounded below by 1e-8 (F is undefined at p_j = 0). Cobb–Douglas demand has gross substitutes, so the
// normalized equilibrium is unique (Arrow, Block & Hurwicz 1959); it solves the linear system
// p_j Σ_h e_hj = Σ_k (Σ_h a_hj e_hk) p_k, the known solution below. Our data (3 consumers, 3 goods).
class Exchange final : public BuiltinMcp<Exchange> {
 public:
  static constexpr int kGoods = 3, kConsumers = 3;
  static constexpr double kPriceFloor = 1e-8;
  static constexpr double kShare[kConsumers][kGoods] = {{0.5, 0.3, 0.2}, {0.2, 0.6, 0.2}, {0.3, 0.2, 0.5}};
  static constexpr double kEndowment[kConsumers][kGoods] = {{1, 0, 2}, {0, 3, 1}, {2, 1, 0}};
  Exchange()
      : BuiltinMcp(Values({1.0, kPriceFloor, kPriceFloor}), Values({1.0, kInf, kInf}), "exchange",
                   JacobianKind::kDense, SolutionSetProperty::kUniqueByProof) {}
  template <class T>
  void Function(const T* p, T* F) const {
    for (int j = 0; j < kGoods; ++j) {
      T excess = 0;
      for (int h = 0; h < kConsumers; ++h) excess += T(kEndowment[h][j]) - T(kShare[h][j]) * Income(p, h) / p[j];
      F[j] = excess;
    }
  }
  template <class T, class Add>
  void Jacobian(const T* p, Add&& add) const {
    for (int j = 0; j < kGoods; ++j) {
      for (int k = 0; k < kGoods; ++k) {
        T v = 0;
        for (int h = 0; h < kConsumers; ++h) {
          v -= T(kShare[h][j]) * T(kEndowment[h][k]) / p[j];
          if (j == k) v += T(kShare[h][j]) * Income(p, h) / (p[j] * p[j]);
        }
        add(j, k, v);
      }
    }
  }
  // The equilibrium from its linear system with p1 = 1 (rows 2 and 3; Walras' law makes row 1 dependent).
  static Vector Equilibrium() {
    double B[kGoods][kGoods] = {}, S[kGoods] = {};
    for (int j = 0; j < kGoods; ++j) {
      for (int h = 0; h < kConsumers; ++h) {
        S[j] += kEndowment[h][j];
        for (int k = 0; k < kGoods; ++k) B[j][k] += kShare[h][j] * kEndowment[h][k];
      }
    }
    Eigen::Matrix2d A;
    A << S[1] - B[1][1], -B[1][2], -B[2][1], S[2] - B[2][2];
    const Eigen::Vector2d rest = A.lu().solve(Eigen::Vector2d(B[1][0], B[2][0]));
    return Values({1.0, rest[0], rest[1]});
  }

 private:
  template <class T>
  static T Income(const T* p, int h) {
    T income = 0;
    for (int k = 0; k < kGoods; ++k) income += p[k] * T(kEndowment[h][k]);
    return income;
  }
};

// Billups (1995), "Algorithms for complementarity problems and generalized equations", PhD thesis, Wisconsin: the
// one-dimensional NCP x ≥ 0, F(x) = (x − 1)² − 1.01, on which Newton's method on the Fischer–Burmeister function
// from x = 0 stalls at a local minimizer of its merit function near x = 1. Unique solution 1 + √1.01: x = 0 fails
// (F(0) = −0.01 < 0) and the other root 1 − √1.01 is negative.
class Billups final : public BuiltinMcp<Billups> {
 public:
  Billups() : BuiltinMcp(Nonnegative(1), Unbounded(1), "billups", JacobianKind::kDense,
                         SolutionSetProperty::kUniqueByProof) {}
  template <class T>
  void Function(const T* x, T* F) const {
    F[0] = (x[0] - 1) * (x[0] - 1) - T(1.01);
  }
  template <class T, class Add>
  void Jacobian(const T* x, Add&& add) const {
    add(0, 0, 2 * (x[0] - 1));
  }
};

// Constructed degenerate NCP: F1 = x1 + x1³ − 2, F2 = x2 + x1² − 1, x ≥ 0. ∇F = [[1 + 3x1², 0], [2x1, 1]] is a
// P-matrix everywhere, so F is a P-function (Moré & Rheinboldt 1973) and the solution (1, 0) is unique; there
// x2 = 0 and F2 = 0: not strictly complementary.
class Degenerate final : public BuiltinMcp<Degenerate> {
 public:
  Degenerate() : BuiltinMcp(Nonnegative(2), Unbounded(2), "degenerate", JacobianKind::kDense,
                            SolutionSetProperty::kPFunction) {}
  template <class T>
  void Function(const T* x, T* F) const {
    F[0] = x[0] + x[0] * x[0] * x[0] - 2;
    F[1] = x[1] + x[0] * x[0] - 1;
  }
  template <class T, class Add>
  void Jacobian(const T* x, Add&& add) const {
    add(0, 0, 1 + 3 * x[0] * x[0]), add(0, 1, T(0));
    add(1, 0, 2 * x[0]), add(1, 1, T(1));
  }
};

// Constructed: x ≥ 0, F(x) = (x − 1)(x − 2). Exactly three solutions, 0 (F(0) = 2 > 0), 1 and 2 (the roots of F);
// a one-dimensional NCP has no others. Each is strictly complementary with F' ≠ 0: isolated.
class ThreeSolutions final : public BuiltinMcp<ThreeSolutions> {
 public:
  ThreeSolutions() : BuiltinMcp(Nonnegative(1), Unbounded(1), "three-solutions") {}
  template <class T>
  void Function(const T* x, T* F) const {
    F[0] = (x[0] - 1) * (x[0] - 2);
  }
  template <class T, class Add>
  void Jacobian(const T* x, Add&& add) const {
    add(0, 0, 2 * x[0] - 3);
  }
};

// Constructed, no solution: z ≥ 0, F1 = z1 − z2, F2 = −1 − z1² − z2². F2 < 0 everywhere, so row 2 can neither
// sit at its bound z2 = 0 (which needs F2 ≥ 0) nor be free (which needs F2 = 0). Nor is there an asymptotic
// solution: |F2|/max_j|∂F2/∂z_j| = (1 + z1² + z2²)/(2 max(|z1|, |z2|)) ≥ max(1, ‖z‖∞)/2, so the scale-free
// residual stays above about 1/4 however far a backend runs.
class NoSolution final : public BuiltinMcp<NoSolution> {
 public:
  NoSolution() : BuiltinMcp(Nonnegative(2), Unbounded(2), "no-solution") {}
  template <class T>
  void Function(const T* z, T* F) const {
    F[0] = z[0] - z[1];
    F[1] = -1 - z[0] * z[0] - z[1] * z[1];
  }
  template <class T, class Add>
  void Jacobian(const T* z, Add&& add) const {
    add(0, 0, T(1)), add(0, 1, T(-1));
    add(1, 0, -2 * z[0]), add(1, 1, -2 * z[1]);
  }
};

// Constructed, F undefined outside the box (NaN for a negative argument of the square roots): x ≥ 0,
// F1 = √x1 + x1 − 2, F2 = √x2 + x2 − 6 x1. F1 is increasing with F1(0) = −2, so x1 = 1; then F2 is increasing in
// x2 with F2(1, 0) = −6, so x2 = 4: the unique solution (1, 4), strictly inside the box. A backend stepping below
// 0 meets NaN and must step back; the Jacobian is infinite on the bounds.
class UndefinedOutside final : public BuiltinMcp<UndefinedOutside> {
 public:
  UndefinedOutside() : BuiltinMcp(Nonnegative(2), Unbounded(2), "undefined-outside", JacobianKind::kDense,
                                  SolutionSetProperty::kUniqueByProof) {}
  template <class T>
  void Function(const T* x, T* F) const {
    F[0] = Sqrt(x[0]) + x[0] - 2;
    F[1] = Sqrt(x[1]) + x[1] - 6 * x[0];
  }
  template <class T, class Add>
  void Jacobian(const T* x, Add&& add) const {
    add(0, 0, 1 / (2 * Sqrt(x[0])) + 1), add(0, 1, T(0));
    add(1, 0, T(-6)), add(1, 1, 1 / (2 * Sqrt(x[1])) + 1);
  }
};

struct Classic {
  const char* id;
  const char* source;
  std::shared_ptr<const MCP> (*make)();
  std::vector<std::pair<std::string, Vector>> starts;
  std::vector<std::string> tags;
  ExpectedOutcome expected;
  std::vector<Vector> known_solutions;
  bool complete;  // known_solutions is the whole solution set
};

std::shared_ptr<const MCP> MakeNash5() {
  return std::make_shared<Cournot>(std::vector<double>{10, 8, 6, 4, 2}, std::vector<double>(5, 5.0),
                                   std::vector<double>{1.2, 1.1, 1.0, 0.9, 0.8}, 1.1, "nash5");
}
std::shared_ptr<const MCP> MakeNash10() {
  return std::make_shared<Cournot>(std::vector<double>{5, 3, 8, 5, 1, 3, 7, 4, 6, 3}, std::vector<double>(10, 10.0),
                                   std::vector<double>{1.2, 1, 0.9, 0.6, 1.5, 1, 0.7, 1.1, 0.95, 0.75}, 1.2,
                                   "nash10");
}

// The eight starting points of MCPLIB's `kojshin` and `josephy` (the same for both; the AMPL versions of the
// collection list them as columns 1-8).
std::vector<std::pair<std::string, Vector>> KojimaStarts() {
  return {{"start1=(0,0,0,0)", Values({0, 0, 0, 0})},       {"start2=(1,1,1,1)", Values({1, 1, 1, 1})},
          {"start3=(100,100,100,100)", Values({100, 100, 100, 100})}, {"start4=(1,0,1,0)", Values({1, 0, 1, 0})},
          {"start5=(1,0,0,0)", Values({1, 0, 0, 0})},       {"start6=(0,1,1,0)", Values({0, 1, 1, 0})},
          {"start7=(0,1,0,1)", Values({0, 1, 0, 1})},       {"start8=(1.25,0,0,0.5)", Values({1.25, 0, 0, 0.5})}};
}

std::vector<Classic> Table() {
  const double r6 = std::sqrt(6.0) / 2;
  return {
      {"mcp/classic/kojshin", "literature:Kojima-Shindo 1986; MCPLIB kojshin (Dirkse-Ferris 1995)",
       [] { return std::shared_ptr<const MCP>(std::make_shared<KojimaShindo>()); },
       KojimaStarts(), {"classic", "several-solutions"}, ExpectedOutcome::kSolvable,
       {Values({1, 0, 3, 0}), Values({r6, 0, 0, 0.5})}, true},
      {"mcp/classic/josephy", "literature:Josephy 1979 (Kojima's example); MCPLIB josephy (Dirkse-Ferris 1995)",
       [] { return std::shared_ptr<const MCP>(std::make_shared<Josephy>()); },
       KojimaStarts(), {"classic"}, ExpectedOutcome::kSolvable, {Values({r6, 0, 0, 0.5})}, false},
      {"mcp/classic/mathiesen", "literature:Mathiesen 1987 Walrasian model (Math. Prog. 37), numeraire p2 = 1",
       [] { return std::shared_ptr<const MCP>(std::make_shared<Mathiesen>()); },
       {{"z0=1", Values({1, 1, 1, 1})}, {"z0=Pi(0)", Values({0, Mathiesen::kPriceFloor, 1, Mathiesen::kPriceFloor})}},
       {"classic", "price-floor"}, ExpectedOutcome::kSolvable, {Values({3, 6, 1, 5})}, true},
      {"mcp/classic/nash5", "literature:Murphy-Sherali-Soyster 1982 Cournot-Nash, 5 firms (GAMS oligomcp)",
       MakeNash5, {{"q=10", Vector::Constant(5, 10.0)}, {"q=1", Vector::Ones(5)}},
       {"classic", "cournot", "output-floor"}, ExpectedOutcome::kSolvable,
       {Values({36.933, 41.818, 43.707, 42.659, 39.179})}, true},
      {"mcp/classic/nash10", "constructed:Cournot-Nash, 10 firms (the oligomcp model with 10 firms' costs)",
       MakeNash10, {{"q=1", Vector::Ones(10)}, {"q=10", Vector::Constant(10, 10.0)}},
       {"classic", "cournot", "output-floor"}, ExpectedOutcome::kSolvable, {}, true},
      {"mcp/classic/exchange", "literature:Cobb-Douglas exchange economy (textbook general equilibrium), our data",
       [] { return std::shared_ptr<const MCP>(std::make_shared<Exchange>()); },
       {{"p=1", Vector::Ones(3)}, {"p=Pi(0)", Values({1, Exchange::kPriceFloor, Exchange::kPriceFloor})}},
       {"classic", "price-floor"}, ExpectedOutcome::kSolvable, {Exchange::Equilibrium()}, true},
      {"mcp/classic/billups", "literature:Billups 1995 PhD thesis, one-dimensional example",
       [] { return std::shared_ptr<const MCP>(std::make_shared<Billups>()); },
       {{"z0=0", Vector::Zero(1)}}, {"classic", "fb-newton-trap"}, ExpectedOutcome::kSolvable,
       {Values({1 + std::sqrt(1.01)})}, true},
  };
}

std::vector<Classic> HardTable() {
  return {
      {"mcp/hard/degenerate", "constructed:P-function NCP with F2 = 0 at x2 = 0",
       [] { return std::shared_ptr<const MCP>(std::make_shared<Degenerate>()); },
       {{"z0=0", Vector::Zero(2)}, {"z0=2", Vector::Constant(2, 2.0)}}, {"hard", "degenerate"},
       ExpectedOutcome::kSolvable, {Values({1, 0})}, true},
      {"mcp/hard/three-solutions", "constructed:(x-1)(x-2) on x >= 0",
       [] { return std::shared_ptr<const MCP>(std::make_shared<ThreeSolutions>()); },
       {{"z0=0.4", Values({0.4})}, {"z0=1.5", Values({1.5})}, {"z0=3", Values({3.0})}},
       {"hard", "several-solutions"}, ExpectedOutcome::kSolvable, {Values({0}), Values({1}), Values({2})}, true},
      {"mcp/hard/no-solution", "constructed:F2 < 0 everywhere",
       [] { return std::shared_ptr<const MCP>(std::make_shared<NoSolution>()); },
       {{"z0=0", Vector::Zero(2)}, {"z0=1", Vector::Ones(2)}}, {"hard", "no-solution"},
       ExpectedOutcome::kInfeasible, {}, true},
      {"mcp/hard/undefined-outside", "constructed:square roots, NaN below the bounds",
       [] { return std::shared_ptr<const MCP>(std::make_shared<UndefinedOutside>()); },
       {{"z0=0.01", Vector::Constant(2, 0.01)}, {"z0=9", Vector::Constant(2, 9.0)}},
       {"hard", "undefined-outside"}, ExpectedOutcome::kSolvable, {Values({1, 4})}, true},
  };
}

std::vector<std::string> Ids(const std::vector<Classic>& table) {
  std::vector<std::string> ids;
  for (const Classic& c : table) ids.emplace_back(c.id);
  return ids;
}

}  // namespace

std::vector<std::string> ClassicMcpIds() { return Ids(Table()); }
std::vector<std::string> HardMcpIds() { return Ids(HardTable()); }

bool MakeClassicMcp(const std::string& id, BuiltinMcpEntry* out) {
  for (const auto& table : {Table(), HardTable()}) {
    for (const Classic& c : table) {
      if (id != c.id) continue;
      McpLibraryProblem& p = out->problem;
      p = {};
      p.id = c.id;
      p.source = c.source;
      p.problem = c.make();
      for (const auto& [label, start] : c.starts) {
        p.start_labels.push_back(label);
        p.starts.push_back(start);
      }
      p.tags = c.tags;
      p.expected = c.expected;
      p.references_complete = c.complete;
      p.metadata["known_solutions"] = std::to_string(c.known_solutions.size());
      if (const auto* e = dynamic_cast<const ExtendedPrecisionMCP*>(p.problem.get())) {
        p.metadata["solution_set"] = std::string(ToString(e->solution_set_property()));
      }
      out->known_solutions = c.known_solutions;
      return true;
    }
  }
  return false;
}

}  // namespace smcbench
