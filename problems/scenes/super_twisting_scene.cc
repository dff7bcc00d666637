#include "problems/scenes/super_twisting_scene.h"

#include <cmath>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "solvers/core/number_text.h"

namespace smcbench {

using json = nlohmann::json;

namespace {

// A number or an expression over the parameters (expression.h), with its field for messages.
struct Value {
  double number = 0.0;
  std::string expression;  // empty: the number
  std::string field;

  double Evaluate(const SceneParameters& parameters) const {
    if (expression.empty()) return number;
    double v = 0.0;
    try {
      v = EvaluateExpression(expression, parameters);
    } catch (const InvalidInputError& e) {
      throw InvalidInputError(field + ": " + e.what());
    }
    if (!std::isfinite(v)) throw InvalidInputError(field + " = '" + expression + "' is not finite");
    return v;
  }
};

struct SinusoidValue {
  Value amplitude, omega, phase;
};

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}
  [[noreturn]] void Fail(const std::string& field, const std::string& what) const {
    throw InvalidInputError("scene file '" + source_ + "': " + field + ": " + what);
  }
  void Object(const json& node, const std::string& field) const {
    if (!node.is_object()) Fail(field, std::string("expected an object, got ") + node.type_name());
  }
  void Keys(const json& node, const std::string& field, std::initializer_list<std::string_view> allowed) const {
    for (auto it = node.begin(); it != node.end(); ++it) {
      bool ok = false;
      for (std::string_view key : allowed) ok = ok || key == it.key();
      if (ok) continue;
      std::string list;
      for (std::string_view key : allowed) list += (list.empty() ? "" : ", ") + std::string(key);
      Fail(field, "unknown key '" + it.key() + "' (allowed: " + list + ")");
    }
  }
  const json& Require(const json& node, const std::string& field, const char* key) const {
    const auto it = node.find(key);
    if (it == node.end()) Fail(field, std::string("missing key '") + key + "'");
    return *it;
  }
  const json* Optional(const json& node, const char* key) const {
    const auto it = node.find(key);
    return it == node.end() ? nullptr : &*it;
  }
  std::string String(const json& node, const std::string& field) const {
    if (!node.is_string()) Fail(field, std::string("expected a string, got ") + node.type_name());
    return node.get<std::string>();
  }
  double Number(const json& node, const std::string& field) const {
    if (!node.is_number()) Fail(field, std::string("expected a number, got ") + node.type_name());
    const double v = node.get<double>();
    if (!std::isfinite(v)) Fail(field, "is not finite");
    return v;
  }
  // Evaluated once with the default parameters, so a broken expression fails when the file is read.
  Value ValueOf(const json& node, const std::string& field, const SceneParameters& parameters) const {
    Value v;
    v.field = field;
    if (node.is_number()) {
      v.number = Number(node, field);
      return v;
    }
    if (!node.is_string()) Fail(field, std::string("expected a number or an expression, got ") + node.type_name());
    v.expression = node.get<std::string>();
    try {
      v.number = v.Evaluate(parameters);
    } catch (const InvalidInputError& e) {
      throw InvalidInputError("scene file '" + source_ + "': " + e.what());
    }
    return v;
  }

 private:
  std::string source_;
};

}  // namespace

struct SuperTwistingScene::Spec {
  SceneInfo info;
  SimulationSettings defaults;
  Value k1, k2, constant;
  std::vector<SinusoidValue> sinusoids;
  double band = 1e-6;
};

bool IsSuperTwistingDocument(const json& document) {
  if (!document.is_object()) return false;
  const auto system = document.find("system");
  if (system == document.end() || !system->is_object()) return false;
  const auto type = system->find("type");
  return type != system->end() && type->is_string() && type->get<std::string>() == "super-twisting";
}

std::unique_ptr<SuperTwistingScene> SuperTwistingScene::FromJson(const json& doc, const std::string& source) {
  const Reader r(source);
  r.Object(doc, "document");
  r.Keys(doc, "document", {"format", "name", "description", "reference", "notes", "parameters", "system", "simulation"});
  if (const json* format = r.Optional(doc, "format")) {
    if (r.String(*format, "format") != "smcbench-scene/1") r.Fail("format", "unsupported (this reader knows smcbench-scene/1)");
  }
  auto spec = std::make_unique<Spec>();
  spec->info.name = r.String(r.Require(doc, "document", "name"), "name");
  if (spec->info.name.empty()) r.Fail("name", "is empty");
  spec->info.description = r.String(r.Require(doc, "document", "description"), "description");
  if (const json* ref = r.Optional(doc, "reference")) spec->info.reference = r.String(*ref, "reference");
  if (const json* notes = r.Optional(doc, "notes")) r.String(*notes, "notes");
  spec->info.source = source;
  spec->info.n = 2;
  spec->info.m = 1;

  SceneParameters parameters;
  if (const json* node = r.Optional(doc, "parameters")) {
    r.Object(*node, "parameters");
    for (auto it = node->begin(); it != node->end(); ++it) {
      if (!IsValidParameterName(it.key())) r.Fail("parameters", "'" + it.key() + "' is not a usable name");
      parameters[it.key()] = r.Number(it.value(), "parameters." + it.key());
    }
  }

  const json& system = r.Require(doc, "document", "system");
  r.Object(system, "system");
  r.Keys(system, "system", {"type", "k1", "k2", "disturbance", "convergence_band"});
  spec->k1 = r.ValueOf(r.Require(system, "system", "k1"), "system.k1", parameters);
  spec->k2 = r.ValueOf(r.Require(system, "system", "k2"), "system.k2", parameters);
  spec->constant.field = "system.disturbance.constant";
  if (const json* band = r.Optional(system, "convergence_band")) {
    spec->band = r.Number(*band, "system.convergence_band");
    if (!(spec->band >= 0.0)) r.Fail("system.convergence_band", "must be >= 0, got " + NumberText(spec->band));
  }
  if (const json* d = r.Optional(system, "disturbance")) {
    const std::string field = "system.disturbance";
    r.Object(*d, field);
    r.Keys(*d, field, {"constant", "sinusoids"});
    if (const json* c = r.Optional(*d, "constant")) spec->constant = r.ValueOf(*c, field + ".constant", parameters);
    if (const json* list = r.Optional(*d, "sinusoids")) {
      if (!list->is_array()) r.Fail(field + ".sinusoids", "expected an array of {amplitude, omega, phase}");
      for (std::size_t j = 0; j < list->size(); ++j) {
        const std::string f = field + ".sinusoids[" + std::to_string(j) + "]";
        const json& term = (*list)[j];
        r.Object(term, f);
        r.Keys(term, f, {"amplitude", "omega", "phase"});
        SinusoidValue s;
        s.amplitude = r.ValueOf(r.Require(term, f, "amplitude"), f + ".amplitude", parameters);
        s.omega = r.ValueOf(r.Require(term, f, "omega"), f + ".omega", parameters);
        s.phase.field = f + ".phase";
        if (const json* phase = r.Optional(term, "phase")) s.phase = r.ValueOf(*phase, f + ".phase", parameters);
        spec->sinusoids.push_back(std::move(s));
      }
    }
  }

  const json& sim = r.Require(doc, "document", "simulation");
  r.Object(sim, "simulation");
  r.Keys(sim, "simulation", {"method", "algorithm", "h", "T", "x0", "solver"});
  SimulationSettings& d = spec->defaults;
  const std::string method = r.String(r.Require(sim, "simulation", "method"), "simulation.method");
  const auto parsed = MethodFromString(method);
  if (!parsed || !(*parsed == Method::kImplicit || *parsed == Method::kExplicit)) {
    r.Fail("simulation.method", "'" + method + "': a super-twisting scene runs implicit or explicit");
  }
  d.method = *parsed;
  d.algorithm = NonlinearAlgorithm::kClosedForm;
  if (const json* algorithm = r.Optional(sim, "algorithm")) {
    const std::string name = r.String(*algorithm, "simulation.algorithm");
    const auto a = NonlinearAlgorithmFromString(name);
    if (!a || *a == NonlinearAlgorithm::kNewtonMlcp) {
      r.Fail("simulation.algorithm", "'" + name + "': a super-twisting step is solved by closed-form or mcp");
    }
    d.algorithm = *a;
  }
  d.h = r.Number(r.Require(sim, "simulation", "h"), "simulation.h");
  d.T = r.Number(r.Require(sim, "simulation", "T"), "simulation.T");
  const json& x0 = r.Require(sim, "simulation", "x0");
  if (!x0.is_array() || x0.size() != 2) r.Fail("simulation.x0", "expected [sigma0, v0] (2 numbers)");
  d.x0 = (Vector(2) << r.Number(x0[0], "simulation.x0[0]"), r.Number(x0[1], "simulation.x0[1]")).finished();
  if (const json* solver = r.Optional(sim, "solver")) d.solver = r.String(*solver, "simulation.solver");
  d.theta = 1.0;
  d.gamma = 1.0;
  d.parameters = parameters;
  d.stepper.record = true;

  std::unique_ptr<SuperTwistingScene> scene(new SuperTwistingScene(std::move(spec)));
  try {
    scene->spec_->defaults.Validate(2);
    scene->System(parameters).Validate();
  } catch (const InvalidInputError& e) {
    throw InvalidInputError("scene file '" + source + "': " + e.what());
  }
  return scene;
}

SuperTwistingScene::SuperTwistingScene(std::unique_ptr<Spec> spec) : spec_(std::move(spec)) {}
SuperTwistingScene::~SuperTwistingScene() = default;

const SceneInfo& SuperTwistingScene::info() const { return spec_->info; }
const SimulationSettings& SuperTwistingScene::defaults() const { return spec_->defaults; }
std::optional<double> SuperTwistingScene::convergence_band() const { return spec_->band; }

SuperTwistingSystem SuperTwistingScene::System(const SceneParameters& overrides) const {
  SceneParameters values = spec_->defaults.parameters;
  for (const auto& [name, value] : overrides) {
    const auto it = values.find(name);
    if (it == values.end()) {
      throw InvalidInputError("scene '" + spec_->info.name + "' has no parameter '" + name + "'");
    }
    it->second = value;
  }
  SuperTwistingSystem system;
  system.k1 = spec_->k1.Evaluate(values);
  system.k2 = spec_->k2.Evaluate(values);
  system.disturbance.constant = spec_->constant.Evaluate(values);
  for (const SinusoidValue& s : spec_->sinusoids) {
    system.disturbance.sinusoids.push_back({s.amplitude.Evaluate(values), s.omega.Evaluate(values), s.phase.Evaluate(values)});
  }
  return system;
}

void SuperTwistingScene::Run(const SimulationSettings& settings, Solver* solver, Trajectory* out) const {
  settings.Validate(2);
  if (!Supports(settings.method)) {
    throw InvalidInputError("scene '" + spec_->info.name + "' " + WhyUnsupported(settings.method));
  }
  const bool implicit = settings.method == Method::kImplicit;
  if (implicit && settings.algorithm == NonlinearAlgorithm::kNewtonMlcp) {
    throw InvalidInputError("algorithm newton-mlcp: a super-twisting step is not a box-MLCP; use closed-form or mcp");
  }
  SuperTwistingOptions options;
  options.stepper = settings.stepper;
  options.solution = implicit && settings.algorithm == NonlinearAlgorithm::kMcp ? SuperTwistingSolution::kMcp
                                                                                : SuperTwistingSolution::kClosedForm;
  RunSuperTwisting(System(settings.parameters), implicit ? SignTreatment::kImplicit : SignTreatment::kExplicit,
                   settings.h, settings.x0, NumSteps(settings.T, settings.h), solver, options, out);
}

}  // namespace smcbench
