#include "problems/scenes/linear_scene.h"

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include "solvers/avi/affine_vi.h"
#include "solvers/core/number_text.h"

namespace smcbench {

using json = nlohmann::json;

namespace {

constexpr std::string_view kFormat = "smcbench-scene/1";

// A number or an expression over the scene parameters, with the field it came from for error messages.
struct Scalar {
  double value = 0.0;
  std::string expression;  // empty: a literal number
  std::string field;       // "system.E[3][0]"

  // Throws InvalidInputError "<field> = '<expr>': ..." on a bad expression or a non-finite result.
  double Evaluate(const SceneParameters& parameters) const {
    if (expression.empty()) return value;
    double v = 0.0;
    try {
      v = EvaluateExpression(expression, parameters);
    } catch (const InvalidInputError& e) {
      throw InvalidInputError(field + ": " + e.what());
    }
    if (!std::isfinite(v)) {
      std::string with;
      for (const auto& [name, p] : parameters) with += (with.empty() ? " with " : ", ") + name + " = " + NumberText(p);
      throw InvalidInputError(field + " = '" + expression + "' is not finite (" + NumberText(v) + ")" + with);
    }
    return v;
  }
};

struct ScalarMatrix {
  int rows = 0, cols = 0;
  std::vector<Scalar> entries;  // row-major

  DenseMatrix Evaluate(const SceneParameters& parameters) const {
    DenseMatrix A(rows, cols);
    for (int i = 0; i < rows; ++i) {
      for (int j = 0; j < cols; ++j) A(i, j) = entries[static_cast<std::size_t>(i * cols + j)].Evaluate(parameters);
    }
    return A;
  }
};

Vector EvaluateVector(const std::vector<Scalar>& v, const SceneParameters& parameters) {
  Vector out(static_cast<Eigen::Index>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) out[static_cast<Eigen::Index>(i)] = v[i].Evaluate(parameters);
  return out;
}

// One component of the forcing g(t): constant, or offset + amplitude sin(omega t + phase).
struct ForcingEntry {
  bool is_sin = false;
  Scalar constant;  // when !is_sin
  Scalar amplitude, omega, phase, offset;
};

struct SinTerm {
  double amplitude, omega, phase;
};

// One sinusoid of a disturbance: amplitude (q entries) sin(omega t + phase).
struct SinusoidSpec {
  std::vector<Scalar> amplitude;
  Scalar omega, phase;
};

// A plant disturbance W d(t) (linear_system.h: Disturbance); no matrix means W = G (matched).
struct DisturbanceSpec {
  bool present = false;
  bool matched = true;
  ScalarMatrix W;
  std::vector<Scalar> constant;  // empty: 0
  std::vector<SinusoidSpec> sinusoids;
};

// system.law = {"polytope": {"H": r×m, "K": r}}: s ∈ P = {s : H s ≥ K}. Entries may use h, the time step.
struct LawSpec {
  ScalarMatrix H;
  std::vector<Scalar> K;
};

// The name the law's expressions use for the time step (implicit twisting's parallelogram depends on it).
constexpr std::string_view kTimeStepName = "h";

// S1's closed form needs x' ∈ −b sgn(c x) with bc > 0: |x| decreases at rate |b| until t* = |x0|/|b|.
constexpr std::string_view kExactSign = "sign";

}  // namespace

struct LinearScene::Spec {
  SceneInfo info;
  SimulationSettings defaults;
  std::string type;  // "sign" or "zoh"
  // sign: E, B, C, D, forcing. zoh: F (in E), G (in B), C, alpha.
  ScalarMatrix E, B, C;
  std::vector<Scalar> D;         // empty: zero
  std::vector<ForcingEntry> forcing;  // empty: none
  std::vector<ForcingEntry> relation_offset;  // e(t) of y = C x + D + e(t), m entries (sign and zoh); empty: none
  Scalar alpha;
  std::string exact;             // "" or "sign"
  bool control_input = false;    // sign: u = −s through B is reported
  std::optional<Scalar> equivalent_control_theta;  // zoh: Siconos' scheme when present
  DisturbanceSpec disturbance;   // zoh
  bool switching_only = false;   // zoh: u = −α s alone
  std::optional<LawSpec> law;    // absent: the box
};

namespace {

// Reads a scene document, tracking the field path for error messages.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& field, const std::string& what) const {
    throw InvalidInputError("scene file '" + source_ + "': " + (field.empty() ? "" : field + ": ") + what);
  }
  // For messages that start with the field ("system.B has 3 rows ...").
  [[noreturn]] void FailSentence(const std::string& sentence) const {
    throw InvalidInputError("scene file '" + source_ + "': " + sentence);
  }

  static std::string Join(const std::string& path, std::string_view key) {
    return path.empty() ? std::string(key) : path + "." + std::string(key);
  }

  void RequireObject(const json& node, const std::string& path) const {
    if (!node.is_object()) Fail(path.empty() ? "document" : path, std::string("expected an object, got ") + node.type_name());
  }

  void CheckKeys(const json& object, const std::string& path, std::initializer_list<std::string_view> allowed) const {
    for (auto it = object.begin(); it != object.end(); ++it) {
      bool ok = false;
      for (std::string_view key : allowed) ok = ok || key == it.key();
      if (!ok) {
        std::string list;
        for (std::string_view key : allowed) list += (list.empty() ? "" : ", ") + std::string(key);
        Fail(path.empty() ? "document" : path, "unknown key '" + it.key() + "' (allowed: " + list + ")");
      }
    }
  }

  const json& Require(const json& object, const std::string& path, std::string_view key) const {
    const auto it = object.find(key);
    if (it == object.end()) FailSentence("missing key '" + Join(path, key) + "'");
    return *it;
  }

  const json* Optional(const json& object, std::string_view key) const {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }

  std::string String(const json& node, const std::string& field) const {
    if (!node.is_string()) Fail(field, std::string("expected a string, got ") + node.type_name());
    return node.get<std::string>();
  }

  double Number(const json& node, const std::string& field) const {
    if (!node.is_number()) Fail(field, std::string("expected a number, got ") + node.type_name());
    const double v = node.get<double>();
    if (!std::isfinite(v)) Fail(field, "is not finite (" + NumberText(v) + ")");
    return v;
  }

  // A number or an expression string, evaluated once with the default parameters to catch defects at load.
  Scalar ScalarValue(const json& node, const std::string& field, const SceneParameters& parameters) const {
    Scalar s;
    s.field = field;
    if (node.is_number()) {
      s.value = node.get<double>();
      if (!std::isfinite(s.value)) Fail(field, "is not finite (" + NumberText(s.value) + ")");
      return s;
    }
    if (!node.is_string()) {
      Fail(field, std::string("expected a number or an expression string, got ") + node.type_name());
    }
    s.expression = node.get<std::string>();
    try {
      s.value = s.Evaluate(parameters);
    } catch (const InvalidInputError& e) {
      FailSentence(e.what());
    }
    return s;
  }

  std::vector<Scalar> ScalarVector(const json& node, const std::string& field, const SceneParameters& parameters) const {
    if (!node.is_array()) Fail(field, std::string("expected an array, got ") + node.type_name());
    std::vector<Scalar> out;
    for (std::size_t i = 0; i < node.size(); ++i) {
      out.push_back(ScalarValue(node[i], field + "[" + std::to_string(i) + "]", parameters));
    }
    return out;
  }

  std::vector<double> NumberVector(const json& node, const std::string& field) const {
    if (!node.is_array()) Fail(field, std::string("expected an array of numbers, got ") + node.type_name());
    std::vector<double> out;
    for (std::size_t i = 0; i < node.size(); ++i) out.push_back(Number(node[i], field + "[" + std::to_string(i) + "]"));
    return out;
  }

  // An array of rows, all of the same length; a matrix with no rows or no columns is an error.
  ScalarMatrix Matrix(const json& node, const std::string& field, const SceneParameters& parameters) const {
    if (!node.is_array()) {
      Fail(field, std::string("expected a matrix (an array of rows), got ") + node.type_name());
    }
    if (node.empty()) Fail(field, "has no rows");
    ScalarMatrix A;
    A.rows = static_cast<int>(node.size());
    for (std::size_t i = 0; i < node.size(); ++i) {
      const std::string row_field = field + "[" + std::to_string(i) + "]";
      const json& row = node[i];
      if (!row.is_array()) {
        Fail(row_field, std::string("expected a row (an array of numbers), got ") + row.type_name() +
                            (i == 0 && (row.is_number() || row.is_string())
                                 ? "; write a column vector as [[a], [b]] and a row as [[a, b]]"
                                 : ""));
      }
      if (i == 0) {
        if (row.empty()) Fail(row_field, "is empty");
        A.cols = static_cast<int>(row.size());
      } else if (static_cast<int>(row.size()) != A.cols) {
        FailSentence(row_field + " has " + std::to_string(row.size()) + " entries but " + field + "[0] has " +
                     std::to_string(A.cols) + " (all rows of a matrix must have the same length)");
      }
      for (std::size_t j = 0; j < row.size(); ++j) {
        A.entries.push_back(ScalarValue(row[j], row_field + "[" + std::to_string(j) + "]", parameters));
      }
    }
    return A;
  }

  void CheckShape(const ScalarMatrix& A, const std::string& field, int rows, int cols, const std::string& why) const {
    if (A.rows != rows || A.cols != cols) {
      FailSentence(field + " is " + std::to_string(A.rows) + "x" + std::to_string(A.cols) + " but must be " +
                   std::to_string(rows) + "x" + std::to_string(cols) + " (" + why + ")");
    }
  }

 private:
  std::string source_;
};

SceneParameters ReadParameters(const Reader& r, const json& doc) {
  SceneParameters parameters;
  const json* node = r.Optional(doc, "parameters");
  if (!node) return parameters;
  if (!node->is_object()) r.Fail("parameters", std::string("expected an object {name: number}, got ") + node->type_name());
  for (auto it = node->begin(); it != node->end(); ++it) {
    if (!IsValidParameterName(it.key())) {
      r.Fail("parameters", "'" + it.key() + "' is not a usable name (letters, digits, _; not pi or a function name)");
    }
    parameters[it.key()] = r.Number(it.value(), "parameters." + it.key());
  }
  return parameters;
}

// system.forcing (n entries, size_text "the state has n = 2 (the size of E)") or system.relation_offset (m entries):
// each a number, an expression or {"type": "sin", amplitude, omega, phase, offset}.
std::vector<ForcingEntry> ReadForcing(const Reader& r, const json& node, const std::string& field, int n,
                                      const std::string& size_text, const SceneParameters& parameters) {
  if (!node.is_array()) {
    r.Fail(field, std::string("expected an array of ") + std::to_string(n) + " entries, got " + node.type_name());
  }
  if (static_cast<int>(node.size()) != n) {
    r.FailSentence(field + " has " + std::to_string(node.size()) + " entries but " + size_text);
  }
  std::vector<ForcingEntry> out(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const json& entry = node[static_cast<std::size_t>(i)];
    const std::string f = field + "[" + std::to_string(i) + "]";
    ForcingEntry& e = out[static_cast<std::size_t>(i)];
    if (!entry.is_object()) {
      e.constant = r.ScalarValue(entry, f, parameters);
      continue;
    }
    r.CheckKeys(entry, f, {"type", "amplitude", "omega", "phase", "offset"});
    const std::string type = r.String(r.Require(entry, f, "type"), f + ".type");
    if (type != "sin") r.Fail(f + ".type", "unknown forcing type '" + type + "' (known: sin)");
    e.is_sin = true;
    e.amplitude = r.ScalarValue(r.Require(entry, f, "amplitude"), f + ".amplitude", parameters);
    const auto optional = [&](std::string_view key, double fallback) {
      const json* v = r.Optional(entry, key);
      if (v) return r.ScalarValue(*v, f + "." + std::string(key), parameters);
      Scalar s;
      s.value = fallback;
      s.field = f + "." + std::string(key);
      return s;
    };
    e.omega = optional("omega", 1.0);
    e.phase = optional("phase", 0.0);
    e.offset = optional("offset", 0.0);
  }
  return out;
}

// system.equivalent_control = {"theta": θ}, θ ∈ [0, 1].
Scalar ReadEquivalentControl(const Reader& r, const json& node, const SceneParameters& parameters) {
  const std::string field = "system.equivalent_control";
  if (!node.is_object()) {
    r.Fail(field, std::string("expected an object {\"theta\": number in [0, 1]}, got ") + node.type_name());
  }
  r.CheckKeys(node, field, {"theta"});
  Scalar theta = r.ScalarValue(r.Require(node, field, "theta"), field + ".theta", parameters);
  if (!(theta.value >= 0.0 && theta.value <= 1.0)) {
    r.Fail(field + ".theta", "must lie in [0, 1], got " + NumberText(theta.value));
  }
  return theta;
}

// system.disturbance = {"matrix": n×q (default G), "constant": [q], "sinusoids": [{"amplitude": [q], "omega", "phase"}]}.
DisturbanceSpec ReadDisturbance(const Reader& r, const json& node, int n, int m, const SceneParameters& parameters) {
  const std::string field = "system.disturbance";
  if (!node.is_object()) {
    r.Fail(field, std::string("expected an object {matrix, constant, sinusoids}, got ") + node.type_name());
  }
  r.CheckKeys(node, field, {"matrix", "constant", "sinusoids"});
  DisturbanceSpec d;
  d.present = true;
  int q = m;
  if (const json* W = r.Optional(node, "matrix")) {
    d.matched = false;
    d.W = r.Matrix(*W, field + ".matrix", parameters);
    q = d.W.cols;
    r.CheckShape(d.W, field + ".matrix", n, q, "the disturbance enters as W d(t) with W n x q, n = " +
                                                   std::to_string(n) + " the size of F");
  }
  const std::string q_text = d.matched ? "m = " + std::to_string(m) + " (matched: W = G)"
                                       : "q = " + std::to_string(q) + " (the columns of " + field + ".matrix)";
  const auto check_size = [&](const std::vector<Scalar>& v, const std::string& f) {
    if (static_cast<int>(v.size()) != q) {
      r.FailSentence(f + " has " + std::to_string(v.size()) + " entries but the disturbance has " + q_text);
    }
  };
  if (const json* c = r.Optional(node, "constant")) {
    d.constant = r.ScalarVector(*c, field + ".constant", parameters);
    check_size(d.constant, field + ".constant");
  }
  if (const json* list = r.Optional(node, "sinusoids")) {
    if (!list->is_array()) {
      r.Fail(field + ".sinusoids", std::string("expected an array of {amplitude, omega, phase}, got ") +
                                       list->type_name());
    }
    for (std::size_t j = 0; j < list->size(); ++j) {
      const std::string f = field + ".sinusoids[" + std::to_string(j) + "]";
      const json& term = (*list)[j];
      if (!term.is_object()) r.Fail(f, std::string("expected an object {amplitude, omega, phase}, got ") + term.type_name());
      r.CheckKeys(term, f, {"amplitude", "omega", "phase"});
      SinusoidSpec spec;
      spec.amplitude = r.ScalarVector(r.Require(term, f, "amplitude"), f + ".amplitude", parameters);
      check_size(spec.amplitude, f + ".amplitude");
      spec.omega = r.ScalarValue(r.Require(term, f, "omega"), f + ".omega", parameters);
      if (const json* phase = r.Optional(term, "phase")) {
        spec.phase = r.ScalarValue(*phase, f + ".phase", parameters);
      } else {
        spec.phase.field = f + ".phase";
      }
      d.sinusoids.push_back(std::move(spec));
    }
  }
  if (d.constant.empty() && d.sinusoids.empty()) {
    r.Fail(field, "has neither 'constant' nor 'sinusoids': nothing disturbs the plant");
  }
  return d;
}

// The parameters with the time step h added, for the law's expressions.
SceneParameters WithTimeStep(const SceneParameters& parameters, double h) {
  SceneParameters values = parameters;
  values[std::string(kTimeStepName)] = h;
  return values;
}

// system.law = {"polytope": {"H": [[...]], "K": [...]}} for m sliding surfaces; evaluated with h the time step.
LawSpec ReadLaw(const Reader& r, const json& node, int m, const SceneParameters& parameters, double h) {
  const std::string field = "system.law";
  if (!node.is_object()) {
    r.Fail(field, std::string("expected an object {\"polytope\": {\"H\": [[...]], \"K\": [...]}}, got ") +
                      node.type_name());
  }
  r.CheckKeys(node, field, {"polytope"});
  const json& polytope = r.Require(node, field, "polytope");
  const std::string pfield = field + ".polytope";
  r.RequireObject(polytope, pfield);
  r.CheckKeys(polytope, pfield, {"H", "K"});
  if (parameters.count(std::string(kTimeStepName))) {
    r.Fail("parameters.h", "the name h is the time step in system.law's expressions; rename the parameter");
  }
  const SceneParameters values = WithTimeStep(parameters, h);
  LawSpec law;
  law.H = r.Matrix(r.Require(polytope, pfield, "H"), pfield + ".H", values);
  r.CheckShape(law.H, pfield + ".H", law.H.rows, m, "P = {s : H s >= K} with s of size m = " + std::to_string(m) +
                                                       " (the rows of C)");
  law.K = r.ScalarVector(r.Require(polytope, pfield, "K"), pfield + ".K", values);
  if (static_cast<int>(law.K.size()) != law.H.rows) {
    r.FailSentence(pfield + ".K has " + std::to_string(law.K.size()) + " entries but " + pfield + ".H has " +
                   std::to_string(law.H.rows) + " rows");
  }
  return law;
}

// e(t) of y = C x + D + e(t) from the file's m entries: the constant parts (and the sinusoids' offsets) add to *D
// (made m zeros when empty), the sinusoids become *offset (left null when every amplitude is 0, so such a file runs
// as one without the key).
void BuildRelationOffset(const std::vector<ForcingEntry>& entries, const SceneParameters& values, Vector* D,
                         Forcing* offset) {
  const auto m = static_cast<Eigen::Index>(entries.size());
  if (D->size() == 0) *D = Vector::Zero(m);
  std::vector<SinTerm> terms(entries.size(), SinTerm{0.0, 0.0, 0.0});
  bool time_dependent = false;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const ForcingEntry& e = entries[i];
    const auto row = static_cast<Eigen::Index>(i);
    if (!e.is_sin) {
      (*D)[row] += e.constant.Evaluate(values);
      continue;
    }
    (*D)[row] += e.offset.Evaluate(values);
    terms[i] = {e.amplitude.Evaluate(values), e.omega.Evaluate(values), e.phase.Evaluate(values)};
    time_dependent = time_dependent || terms[i].amplitude != 0.0;
  }
  if (!time_dependent) return;
  *offset = [terms = std::move(terms)](double t, Eigen::Ref<Vector> e) {
    for (std::size_t i = 0; i < terms.size(); ++i) {
      e[static_cast<Eigen::Index>(i)] = terms[i].amplitude * std::sin(terms[i].omega * t + terms[i].phase);
    }
  };
}

}  // namespace

std::unique_ptr<LinearScene> LinearScene::FromJson(const json& doc, const std::string& source) {
  const Reader r(source);
  r.RequireObject(doc, "");
  r.CheckKeys(doc, "", {"format", "name", "description", "reference", "notes", "parameters", "system", "simulation",
                        "exact_solution"});
  if (const json* format = r.Optional(doc, "format")) {
    const std::string f = r.String(*format, "format");
    if (f != kFormat) r.Fail("format", "unsupported format '" + f + "' (this reader knows " + std::string(kFormat) + ")");
  }
  auto spec = std::make_unique<Spec>();
  spec->info.name = r.String(r.Require(doc, "", "name"), "name");
  if (spec->info.name.empty()) r.Fail("name", "is empty");
  spec->info.description = r.String(r.Require(doc, "", "description"), "description");
  if (const json* ref = r.Optional(doc, "reference")) spec->info.reference = r.String(*ref, "reference");
  if (const json* notes = r.Optional(doc, "notes")) r.String(*notes, "notes");
  spec->info.source = source;
  const SceneParameters parameters = ReadParameters(r, doc);

  // The system.
  const json& system = r.Require(doc, "", "system");
  r.RequireObject(system, "system");
  spec->type = r.String(r.Require(system, "system", "type"), "system.type");
  int n = 0, m = 0;
  if (spec->type == "sign") {
    r.CheckKeys(system, "system", {"type", "E", "B", "C", "D", "forcing", "relation_offset", "control_input", "law"});
    if (const json* input = r.Optional(system, "control_input")) {
      if (!input->is_boolean()) r.Fail("system.control_input", std::string("expected true or false, got ") + input->type_name());
      spec->control_input = input->get<bool>();
    }
    spec->E = r.Matrix(r.Require(system, "system", "E"), "system.E", parameters);
    n = spec->E.rows;
    r.CheckShape(spec->E, "system.E", n, n, "E must be square, n x n");
    spec->C = r.Matrix(r.Require(system, "system", "C"), "system.C", parameters);
    m = spec->C.rows;
    r.CheckShape(spec->C, "system.C", m, n, "C is m x n: one row per sliding surface, n = " + std::to_string(n) +
                                               " the size of E");
    spec->B = r.Matrix(r.Require(system, "system", "B"), "system.B", parameters);
    r.CheckShape(spec->B, "system.B", n, m, "B is n x m with n = " + std::to_string(n) + " the size of E and m = " +
                                               std::to_string(m) + " the rows of C");
    if (const json* D = r.Optional(system, "D")) {
      spec->D = r.ScalarVector(*D, "system.D", parameters);
      if (static_cast<int>(spec->D.size()) != m) {
        r.FailSentence("system.D has " + std::to_string(spec->D.size()) + " entries but C has m = " +
                       std::to_string(m) + " rows");
      }
    }
    if (const json* forcing = r.Optional(system, "forcing")) {
      spec->forcing = ReadForcing(r, *forcing, "system.forcing", n,
                                  "the state has n = " + std::to_string(n) + " (the size of E)", parameters);
    }
  } else if (spec->type == "zoh") {
    r.CheckKeys(system, "system", {"type", "F", "G", "C", "alpha", "equivalent_control", "disturbance",
                                   "switching_only", "law", "relation_offset"});
    spec->E = r.Matrix(r.Require(system, "system", "F"), "system.F", parameters);
    n = spec->E.rows;
    r.CheckShape(spec->E, "system.F", n, n, "F must be square, n x n");
    spec->C = r.Matrix(r.Require(system, "system", "C"), "system.C", parameters);
    m = spec->C.rows;
    r.CheckShape(spec->C, "system.C", m, n, "C is m x n with n = " + std::to_string(n) + " the size of F");
    spec->B = r.Matrix(r.Require(system, "system", "G"), "system.G", parameters);
    r.CheckShape(spec->B, "system.G", n, m, "G is n x m with n = " + std::to_string(n) + " the size of F and m = " +
                                               std::to_string(m) + " the rows of C");
    if (const json* alpha = r.Optional(system, "alpha")) {
      spec->alpha = r.ScalarValue(*alpha, "system.alpha", parameters);
    } else {
      spec->alpha.value = 1.0;
    }
    spec->alpha.field = "system.alpha";
    if (const json* ec = r.Optional(system, "equivalent_control")) {
      spec->equivalent_control_theta = ReadEquivalentControl(r, *ec, parameters);
    }
    if (const json* dist = r.Optional(system, "disturbance")) spec->disturbance = ReadDisturbance(r, *dist, n, m, parameters);
    if (const json* only = r.Optional(system, "switching_only")) {
      if (!only->is_boolean()) {
        r.Fail("system.switching_only", std::string("expected true or false, got ") + only->type_name());
      }
      spec->switching_only = only->get<bool>();
      if (spec->switching_only && spec->equivalent_control_theta) {
        r.Fail("system.switching_only", "excludes system.equivalent_control (u = -alpha s has no equivalent part)");
      }
    }
  } else {
    r.Fail("system.type", "unknown system type '" + spec->type + "' (known: sign, zoh)");
  }
  if (const json* offset = r.Optional(system, "relation_offset")) {
    spec->relation_offset = ReadForcing(r, *offset, "system.relation_offset", m,
                                        "C has m = " + std::to_string(m) + " rows (y = C x + D + e(t))", parameters);
  }
  spec->info.n = n;
  spec->info.m = m;

  // The numerical settings.
  const json& sim = r.Require(doc, "", "simulation");
  r.RequireObject(sim, "simulation");
  r.CheckKeys(sim, "simulation", {"method", "h", "T", "theta", "gamma", "x0", "solver", "plant_substeps"});
  SimulationSettings& d = spec->defaults;
  const std::string method = r.String(r.Require(sim, "simulation", "method"), "simulation.method");
  const auto parsed = MethodFromString(method);
  if (!parsed) r.Fail("simulation.method", "unknown method '" + method + "' (known: implicit, explicit, zoh, zoh-explicit)");
  d.method = *parsed;
  if ((d.method == Method::kZoh || d.method == Method::kZohExplicit) && spec->type != "zoh") {
    r.Fail("simulation.method", "'" + method + "' needs a system of type 'zoh' (F, G, C, alpha)");
  }
  d.h = r.Number(r.Require(sim, "simulation", "h"), "simulation.h");
  if (!(d.h > 0.0)) r.Fail("simulation.h", "must be > 0, got " + NumberText(d.h));
  d.T = r.Number(r.Require(sim, "simulation", "T"), "simulation.T");
  if (!(d.T >= 0.0)) r.Fail("simulation.T", "must be >= 0, got " + NumberText(d.T));
  if (const json* theta = r.Optional(sim, "theta")) d.theta = r.Number(*theta, "simulation.theta");
  if (!(d.theta >= 0.0 && d.theta <= 1.0)) r.Fail("simulation.theta", "must lie in [0, 1], got " + NumberText(d.theta));
  if (const json* gamma = r.Optional(sim, "gamma")) d.gamma = r.Number(*gamma, "simulation.gamma");
  if (!(d.gamma >= 0.0 && d.gamma <= 1.0)) r.Fail("simulation.gamma", "must lie in [0, 1], got " + NumberText(d.gamma));
  const std::vector<double> x0 = r.NumberVector(r.Require(sim, "simulation", "x0"), "simulation.x0");
  if (static_cast<int>(x0.size()) != n) {
    r.FailSentence("simulation.x0 has " + std::to_string(x0.size()) + " entries but the state has n = " +
                   std::to_string(n));
  }
  d.x0 = Eigen::Map<const Vector>(x0.data(), n);
  if (const json* solver = r.Optional(sim, "solver")) d.solver = r.String(*solver, "simulation.solver");
  if (const json* substeps = r.Optional(sim, "plant_substeps")) {
    // The plant between a ZOH controller's samples (problems/stepper/sampled_plant.h): a whole number of points.
    const double value = r.Number(*substeps, "simulation.plant_substeps");
    if (!(value >= 1.0 && value <= 1e6) || value != std::floor(value)) {
      r.Fail("simulation.plant_substeps", "must be an integer in [1, 1000000], got " + NumberText(value));
    }
    if (spec->type != "zoh") r.Fail("simulation.plant_substeps", "needs a system of type 'zoh' (a ZOH-sampled plant)");
    d.plant_substeps = static_cast<int>(value);
  }
  d.parameters = parameters;
  if (const json* law = r.Optional(system, "law")) {
    spec->law = ReadLaw(r, *law, m, parameters, d.h);
    if (!IsImplicit(d.method)) {
      r.Fail("simulation.method", "'" + method + "' is explicit, but a polytope law needs an implicit method "
                                  "(implicit or zoh)");
    }
  }
  try {
    NumSteps(d.T, d.h);
  } catch (const InvalidInputError& e) {
    r.Fail("simulation.T", e.what());
  }

  if (const json* exact = r.Optional(doc, "exact_solution")) {
    spec->exact = r.String(*exact, "exact_solution");
    if (spec->exact != kExactSign) r.Fail("exact_solution", "unknown kind '" + spec->exact + "' (known: sign)");
  }

  std::unique_ptr<LinearScene> scene(new LinearScene(std::move(spec)));
  // The assembled model must pass the stepper's own checks (e.g. CG invertible for ZOH), and the exact solution
  // must apply: both with the default parameters, so a broken file fails when it is read, not when it is run.
  try {
    const LinearModel model = scene->ModelWithoutName(parameters);
    if (scene->spec_->law) {
      // P must not be empty: AffineVI's phase-1 check on the law with the default parameters and h.
      const auto law_of = [](const LinearModel& mod) -> const PolytopeLaw& {
        if (const auto* z = std::get_if<ZohSmcSystem>(&mod)) return z->law;
        return std::get<LinearSignSystem>(mod).law;
      };
      const PolytopeLaw& law = law_of(model);
      const int m = scene->spec_->info.m;
      const AffineVI check(DenseMatrix::Identity(m, m), Vector::Zero(m), law.H, law.K, "system.law");
      (void)check;
    }
    if (scene->spec_->exact == kExactSign) scene->Exact(scene->spec_->defaults);
  } catch (const InvalidInputError& e) {
    r.FailSentence(e.what());
  }
  return scene;
}

std::unique_ptr<LinearScene> LinearScene::FromText(std::string_view text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    throw InvalidInputError("scene file '" + source + "': not valid JSON: " + e.what());
  }
  return FromJson(doc, source);
}

std::unique_ptr<LinearScene> LinearScene::FromFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InvalidInputError("scene file '" + path + "': cannot be read");
  std::ostringstream text;
  text << in.rdbuf();
  return FromText(text.str(), path);
}

LinearScene::LinearScene(std::unique_ptr<Spec> spec) : spec_(std::move(spec)) {}
LinearScene::~LinearScene() = default;

const SceneInfo& LinearScene::info() const { return spec_->info; }
const SimulationSettings& LinearScene::defaults() const { return spec_->defaults; }
const std::string& LinearScene::system_type() const { return spec_->type; }
const SceneParameters& LinearScene::parameters() const { return spec_->defaults.parameters; }

bool LinearScene::Supports(Method method) const {
  if (spec_->law && !IsImplicit(method)) return false;  // the explicit sign is the box's
  return spec_->type == "zoh" || method == Method::kImplicit || method == Method::kExplicit;
}

std::string LinearScene::WhyUnsupported(Method method) const {
  if (Supports(method)) return "";
  const std::string name = "method '" + std::string(ToString(method)) + "'";
  if (spec_->law) {
    return "has a polytope law (system.law): " + name +
           " is explicit, whose sign sgn(y_k) is the box's; use an implicit method";
  }
  return "is a sign system (E, B, C): " + name + " needs a ZOH plant (F, G, C, alpha); use implicit or explicit";
}

LinearModel LinearScene::Model(const SceneParameters& overrides, std::optional<double> h) const {
  try {
    return ModelWithoutName(overrides, h);
  } catch (const InvalidInputError& e) {
    throw InvalidInputError("scene '" + spec_->info.name + "': " + e.what());
  }
}

LinearModel LinearScene::ModelWithoutName(const SceneParameters& overrides, std::optional<double> h) const {
  const Spec& s = *spec_;
  SceneParameters values = s.defaults.parameters;
  for (const auto& [name, value] : overrides) {
    const auto it = values.find(name);
    if (it == values.end()) {
      std::string known;
      for (const auto& [k, v] : s.defaults.parameters) known += (known.empty() ? "" : ", ") + k;
      throw InvalidInputError("no parameter '" + name +
                              "' (parameters: " + (known.empty() ? "none" : known) + ")");
    }
    if (!std::isfinite(value)) throw InvalidInputError("parameter " + name + " is not finite (" + NumberText(value) + ")");
    it->second = value;
  }
  PolytopeLaw law;
  if (s.law) {
    const SceneParameters with_h = WithTimeStep(values, h.value_or(s.defaults.h));
    law.H = s.law->H.Evaluate(with_h);
    law.K = EvaluateVector(s.law->K, with_h);
  }
  if (s.type == "zoh") {
    ZohSmcSystem z;
    z.F = s.E.Evaluate(values);
    z.G = s.B.Evaluate(values);
    z.C = s.C.Evaluate(values);
    z.alpha = s.alpha.Evaluate(values);
    if (s.equivalent_control_theta) z.equivalent_control = EquivalentControl{s.equivalent_control_theta->Evaluate(values)};
    z.switching_only = s.switching_only;
    z.law = std::move(law);
    if (!s.relation_offset.empty()) BuildRelationOffset(s.relation_offset, values, &z.D, &z.relation_offset);
    if (s.disturbance.present) {
      const DisturbanceSpec& d = s.disturbance;
      z.disturbance.W = d.matched ? z.G : d.W.Evaluate(values);
      if (!d.constant.empty()) z.disturbance.constant = EvaluateVector(d.constant, values);
      for (const SinusoidSpec& term : d.sinusoids) {
        z.disturbance.sinusoids.push_back(
            {EvaluateVector(term.amplitude, values), term.omega.Evaluate(values), term.phase.Evaluate(values)});
      }
    }
    z.Validate();
    return z;
  }
  LinearSignSystem sys;
  sys.E = s.E.Evaluate(values);
  sys.B = s.B.Evaluate(values);
  sys.C = s.C.Evaluate(values);
  if (!s.D.empty()) sys.D = EvaluateVector(s.D, values);
  sys.control_input = s.control_input;
  sys.law = std::move(law);
  if (!s.forcing.empty()) {
    const int n = s.info.n;
    sys.g = Vector::Zero(n);
    std::vector<SinTerm> terms(static_cast<std::size_t>(n), SinTerm{0.0, 0.0, 0.0});
    bool time_dependent = false;
    for (int i = 0; i < n; ++i) {
      const ForcingEntry& e = s.forcing[static_cast<std::size_t>(i)];
      if (!e.is_sin) {
        sys.g[i] = e.constant.Evaluate(values);
        continue;
      }
      sys.g[i] = e.offset.Evaluate(values);
      terms[static_cast<std::size_t>(i)] = {e.amplitude.Evaluate(values), e.omega.Evaluate(values),
                                            e.phase.Evaluate(values)};
      time_dependent = time_dependent || terms[static_cast<std::size_t>(i)].amplitude != 0.0;
    }
    if (sys.g.isZero(0.0)) sys.g.resize(0);
    // Only the sinusoids are time dependent; the constant parts go into g, which the stepper folds into p once.
    if (time_dependent) {
      sys.forcing = [terms = std::move(terms)](double t, Eigen::Ref<Vector> g) {
        for (std::size_t i = 0; i < terms.size(); ++i) {
          g[static_cast<Eigen::Index>(i)] = terms[i].amplitude * std::sin(terms[i].omega * t + terms[i].phase);
        }
      };
    }
  }
  if (!s.relation_offset.empty()) BuildRelationOffset(s.relation_offset, values, &sys.D, &sys.relation_offset);
  sys.Validate();
  return sys;
}

OneStepData LinearScene::Discretization(const SimulationSettings& settings) const {
  settings.Validate(spec_->info.n);
  if (!Supports(settings.method)) {
    throw InvalidInputError("scene '" + spec_->info.name + "' " + WhyUnsupported(settings.method));
  }
  return Discretize(Model(settings.parameters, settings.h), settings.method, settings.h, settings.theta);
}

void LinearScene::Run(const SimulationSettings& settings, Solver* solver, Trajectory* out) const {
  LinearStepper stepper(Discretization(settings));
  stepper.Run(settings.x0, NumSteps(settings.T, settings.h), solver, settings.stepper, out);
}

std::optional<ExactSolution> LinearScene::Exact(const SimulationSettings& settings) const {
  const Spec& s = *spec_;
  if (s.exact != kExactSign) return std::nullopt;
  const LinearModel model = Model(settings.parameters);
  const auto* sys = std::get_if<LinearSignSystem>(&model);
  const auto fail = [&](const std::string& why) -> std::optional<ExactSolution> {
    throw InvalidInputError("exact_solution 'sign' needs x' ∈ −b sgn(c x) with b c > 0 (n = m = 1, E = 0, D = 0, "
                            "no forcing): " + why);
  };
  if (!sys || sys->n() != 1 || sys->m() != 1) return fail("the system is not scalar");
  if (sys->E(0, 0) != 0.0) return fail("E = " + NumberText(sys->E(0, 0)));
  if (sys->D.size() && sys->D[0] != 0.0) return fail("D = " + NumberText(sys->D[0]));
  if (sys->g.size() || sys->forcing) return fail("the system has a forcing");
  if (sys->relation_offset) return fail("the relation has a time-varying term e(t)");
  const double b = sys->B(0, 0), c = sys->C(0, 0);
  if (!(b * c > 0.0)) return fail("b c = " + NumberText(b * c));
  if (settings.x0.size() != 1) return fail("x0 has " + std::to_string(settings.x0.size()) + " entries");
  const double x0 = settings.x0[0];
  const double rate = std::abs(b);
  const double arrival = std::abs(x0) / rate;       // t* = |x0| / |b|
  const double sx0 = x0 > 0.0 ? 1.0 : (x0 < 0.0 ? -1.0 : 0.0);
  const double s_before = c > 0.0 ? sx0 : -sx0;      // s ∈ Sgn(c x) while x ≠ 0
  ExactSolution exact;
  exact.x = [x0, sx0, rate, arrival](double t, Eigen::Ref<Vector> x) { x[0] = t < arrival ? x0 - sx0 * rate * t : 0.0; };
  // s on (t_{k−1}, t_k] is compared with s(t_k): s(t) = s_before for t ≤ t*, 0 (the sliding value) after.
  exact.s = [s_before, arrival](double t, Eigen::Ref<Vector> v) { v[0] = t <= arrival ? s_before : 0.0; };
  return exact;
}

}  // namespace smcbench
