// Capture: turns the one-step box-MLCPs of a time-stepping run into library problems (`smcbench simulate
// --record`), and builds the "paper" suite (the one-step problems of the report's scenes) for `smcbench bench`.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "problems/library/matrix_tags.h"
#include "problems/library/problem_set.h"
#include "problems/library/problem_set_io.h"
#include "problems/scenes/scene.h"
#include "problems/stepper/linear_stepper.h"

namespace smcbench {

// Captured problems up to this many rows get a certified reference as they are recorded (ComputeReference,
// problems/library/references.h, with the run's z as the only candidate besides Certify's own): at most
// 3⁴ = 81 active sets of at most 4 rows in quad precision, cheap next to a record path that already copies every
// problem. Larger ones would need the backends and up to 3⁸ sets a step (81 times as many, each larger):
// they keep Certificate::kNone, and `smcbench library FILE --certify OUT` attaches them afterwards.
inline constexpr int kCaptureReferenceMaxSize = 4;

// What a captured problem records about the run it came from.
struct CaptureContext {
  std::string set = "capture";  // first part of every id
  std::string scene;
  std::string method;             // "implicit", "zoh", ...
  double h = 0.0;
  std::optional<double> theta;    // θ of the θ-method (none for ZOH)
  std::string backend;            // metadata "backend" (omitted if empty)
  std::map<std::string, std::string> metadata;  // extra entries for every problem (gamma, algorithm, ...)
  std::vector<std::string> tags{"capture"};     // free labels for every problem
  // Attach a certified reference to problems of at most kCaptureReferenceMaxSize rows as they are recorded.
  bool attach_references = true;
};

// The context of a scene run: scene name, method, h, θ (not for ZOH), and for nonlinear scenes gamma and the
// algorithm in metadata.
CaptureContext MakeCaptureContext(const std::string& set, const Scene& scene, const SimulationSettings& settings,
                                  std::string_view backend);

// "<set>/<scene>/<method>/h<h>/k<step>", plus "/it<α>" for the inner problem of Newton iteration α ≥ 1; h in its
// shortest round-trip form ("paper/sign/implicit/h0.01/k12", "paper/arctan/implicit/h0.05/k3/it2").
std::string CaptureId(const CaptureContext& context, std::int64_t step, int newton_iteration);

// A StepObserver that turns each one-step problem into a LibraryProblem:
//   id CaptureId(...), source "capture:<scene>", the problem itself (named by its id), tags ClassifyMatrix(M)
//   (computed once per distinct M), labels context.tags (+ "newton-mlcp" for Algorithm 2's inner problems),
//   metadata scene, method, h, theta, step (and iteration), backend, status (the backend's), plus
//   context.metadata; solution = the z the run used (if finite and of the right size); expected = solvable when
//   the backend solved it, else unknown (a failure of one backend proves nothing); with
//   context.attach_references and m ≤ kCaptureReferenceMaxSize, the certified reference (the run's z as candidate).
// With a writer each problem is streamed to it at once (nothing is kept); without, they are collected.
// The ids of one recorder are distinct by construction: OnStep throws std::logic_error unless (step, Newton
// iteration) strictly increases from call to call (as every stepper calls it), so a writer may be told
// IdCheck::kGuaranteedByCaller and a capture of any length is written in constant memory.
class ProblemRecorder final : public StepObserver {
 public:
  explicit ProblemRecorder(CaptureContext context, ProblemSetWriter* writer = nullptr,
                           ClassifyOptions classify = {});

  void OnStep(std::int64_t step, int newton_iteration, const BoxMLCP& problem, const SolveResult& result) override;

  std::uint64_t count() const { return count_; }
  const std::vector<LibraryProblem>& problems() const { return problems_; }  // empty when streaming
  std::vector<LibraryProblem> TakeProblems();
  const CaptureContext& context() const { return context_; }

 private:
  CaptureContext context_;
  ProblemSetWriter* writer_;
  ClassifyOptions classify_;
  std::vector<LibraryProblem> problems_;
  std::uint64_t count_ = 0;
  std::int64_t last_step_ = -1;
  int last_iteration_ = -1;
  // ClassifyMatrix of the last matrix seen (a linear run's M is constant: classified once).
  std::optional<BoxMLCP> classified_;
  MatrixTags classified_tags_;
};

// Runs scene with settings on solver with a recorder attached (settings.stepper.observer is replaced and
// settings.stepper.record forced on) and returns the captured problems; *trajectory receives the run.
std::vector<LibraryProblem> CaptureSceneRun(const Scene& scene, SimulationSettings settings, Solver* solver,
                                            const CaptureContext& context, Trajectory* trajectory);

// Steps kept from a run of num_steps steps (1-based, ascending): all of them if num_steps ≤ max_steps; else
// steps 1..first_steps, the steps within reaching_window of reaching_step (if ≥ 1), and evenly spaced steps
// (the last one included) up to max_steps in all.
std::vector<std::int64_t> SubsampleSteps(std::int64_t num_steps, std::int64_t reaching_step, int max_steps,
                                         int first_steps, int reaching_window);

struct PaperSuiteOptions {
  std::string backend = "lemke";  // solves every step (and every Newton iteration's MLCP)
  double tolerance = 1e-10;       // of each step's solve
  int max_steps_per_scene = 50;
  int first_steps = 5;
  int reaching_window = 2;        // steps kept on either side of the reaching step
};

// The "paper" suite: every linear scene of docs/scenes.md (S1–S8, S11: LinearScene in the registry) run with its own
// settings (h, T, θ, x0, method; implicit or ZOH) and every step's box-MLCP captured, then SubsampleSteps with the
// reaching step of the run (|y| ≤ 10·tolerance); plus the inner MLCPs of Algorithm 2 for the nonlinear scenes S9
// (hypomonotone) and S10 (arctan), every Newton iteration of the kept steps. Deterministic: same binary, same ids
// and bits. Problems are tagged "paper" and "capture", and carry the metadata of ProblemRecorder and a certified
// reference (AttachReferences without backends, on the kept steps only: every problem has m ≤ 2).
ProblemSet CapturePaperSuite(const PaperSuiteOptions& options = {});

}  // namespace smcbench
