// The scalable MCP families (mcp_families.h), written once on the scalar type like the classic ones.
#include "problems/mcp/mcp_families.h"

#include <cstdlib>
#include <memory>
#include <string>
#include <utility>

#include "problems/mcp/builtin_mcp.h"
#include "problems/mcp/scalar_math.h"

namespace smcbench {
namespace {

enum class Physics { kObstacle, kBratu };

constexpr int kMaxUnknowns = 1000000;
constexpr double kBratuUpper = 0.3;

// −Δu + f(u) on an nx × ny grid of interior points (ny = 1: the 1-D problem), rows times h².
class GridMcp final : public BuiltinMcp<GridMcp> {
 public:
  GridMcp(Physics physics, int nx, int ny, Vector l, Vector u, std::string name)
      : BuiltinMcp(std::move(l), std::move(u), std::move(name), JacobianKind::kSparse,
                   SolutionSetProperty::kStronglyMonotone),
        physics_(physics), nx_(nx), ny_(ny), h2_(1.0 / ((nx + 1.0) * (nx + 1.0))),
        load_(ny == 1 ? -10.0 : -20.0), lambda_(ny == 1 ? 3.0 : 5.0) {}

  template <class T>
  void Function(const T* u, T* F) const {
    const T h2 = h2_;
    for (int j = 0; j < ny_; ++j) {
      for (int i = 0; i < nx_; ++i) {
        const int k = i + nx_ * j;
        T v = (ny_ == 1 ? 2 : 4) * u[k];
        if (i > 0) v -= u[k - 1];
        if (i + 1 < nx_) v -= u[k + 1];
        if (ny_ > 1 && j > 0) v -= u[k - nx_];
        if (ny_ > 1 && j + 1 < ny_) v -= u[k + nx_];
        if (physics_ == Physics::kObstacle) {
          v += h2 * (u[k] * u[k] * u[k] - T(load_));
        } else {
          v -= h2 * T(lambda_) * mcp_math::Exp(u[k]);
        }
        F[k] = v;
      }
    }
  }
  template <class T, class Add>
  void Jacobian(const T* u, Add&& add) const {
    const T h2 = h2_;
    for (int j = 0; j < ny_; ++j) {
      for (int i = 0; i < nx_; ++i) {
        const int k = i + nx_ * j;
        T diagonal = ny_ == 1 ? 2 : 4;
        if (physics_ == Physics::kObstacle) {
          diagonal += h2 * 3 * u[k] * u[k];
        } else {
          diagonal -= h2 * T(lambda_) * mcp_math::Exp(u[k]);
        }
        add(k, k, diagonal);
        if (i > 0) add(k, k - 1, T(-1));
        if (i + 1 < nx_) add(k, k + 1, T(-1));
        if (ny_ > 1 && j > 0) add(k, k - nx_, T(-1));
        if (ny_ > 1 && j + 1 < ny_) add(k, k + nx_, T(-1));
      }
    }
  }

 private:
  Physics physics_;
  int nx_, ny_;
  double h2_, load_, lambda_;
};

// ψ at the grid's points.
Vector Obstacle(int nx, int ny) {
  Vector psi(nx * ny);
  const double h = 1.0 / (nx + 1.0);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double x = (i + 1) * h - 0.5, y = ny == 1 ? 0.0 : (j + 1) * h - 0.5;
      psi[i + nx * j] = -0.05 - 0.5 * (x * x + y * y);
    }
  }
  return psi;
}

// "<prefix><digits>" → the number, or -1.
long ParseSize(const std::string& text, const std::string& prefix) {
  if (text.compare(0, prefix.size(), prefix) != 0 || text.size() == prefix.size()) return -1;
  const std::string digits = text.substr(prefix.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 7 || digits[0] == '0') return -1;
  return std::strtol(digits.c_str(), nullptr, 10);
}

}  // namespace

std::vector<std::string> McpFamilyIds(bool quick) {
  std::vector<std::string> ids{"mcp/obstacle1d/n32", "mcp/obstacle2d/m8", "mcp/bratu1d/n32", "mcp/bratu2d/m8"};
  if (!quick) {
    for (const char* id : {"mcp/obstacle1d/n1000", "mcp/obstacle1d/n10000", "mcp/obstacle2d/m32",
                           "mcp/obstacle2d/m100", "mcp/bratu1d/n1000", "mcp/bratu2d/m32", "mcp/bratu2d/m100"}) {
      ids.emplace_back(id);
    }
  }
  return ids;
}

bool MakeFamilyMcp(const std::string& id, BuiltinMcpEntry* out) {
  struct Family {
    const char* prefix;
    Physics physics;
    bool two_d;
  };
  const Family families[] = {{"mcp/obstacle1d/", Physics::kObstacle, false},
                             {"mcp/obstacle2d/", Physics::kObstacle, true},
                             {"mcp/bratu1d/", Physics::kBratu, false},
                             {"mcp/bratu2d/", Physics::kBratu, true}};
  for (const Family& f : families) {
    const std::string prefix = f.prefix;
    if (id.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string size_text = id.substr(prefix.size());
    const long size = ParseSize(size_text, f.two_d ? "m" : "n");
    const long unknowns = f.two_d ? size * size : size;
    if (size < 1 || unknowns > kMaxUnknowns) {
      throw InvalidInputError("MakeBuiltinMcp: id '" + id + "': the size must be " + (f.two_d ? "m<M>" : "n<N>") +
                              " with 1 <= " + (f.two_d ? "M*M" : "N") + " <= " + std::to_string(kMaxUnknowns));
    }
    const int nx = static_cast<int>(size), ny = f.two_d ? nx : 1, n = nx * ny;
    Vector l, u;
    if (f.physics == Physics::kObstacle) {
      l = Obstacle(nx, ny);
      u = Vector::Constant(n, kInf);
    } else {
      l = Vector::Zero(n);
      u = Vector::Constant(n, kBratuUpper);
    }
    McpLibraryProblem& p = out->problem;
    p = {};
    p.id = id;
    p.source = std::string("generated:") + (f.physics == Physics::kObstacle ? "obstacle" : "bratu") +
               (f.two_d ? "2d" : "1d");
    p.problem = std::make_shared<GridMcp>(f.physics, nx, ny, l, u, id);
    p.starts = {Vector::Zero(n)};
    p.start_labels = {"z0=0"};
    if (f.physics == Physics::kObstacle) {
      p.starts.push_back(l);
      p.start_labels.push_back("z0=psi");
    } else {
      p.starts.push_back(u);
      p.start_labels.push_back("z0=upper");
    }
    p.tags = {"family", "sparse", f.physics == Physics::kObstacle ? "strongly-monotone" : "monotone-on-box"};
    p.expected = ExpectedOutcome::kSolvable;
    p.references_complete = true;
    p.metadata["grid"] = std::to_string(nx) + (f.two_d ? "x" + std::to_string(ny) : "");
    out->known_solutions.clear();
    return true;
  }
  return false;
}

}  // namespace smcbench
