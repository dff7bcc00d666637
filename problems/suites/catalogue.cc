#include "problems/suites/catalogue.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "problems/io/siconos_format.h"
#include "problems/library/capture.h"
#include "problems/library/problem_set_io.h"
#include "problems/library/references.h"
#include "problems/suites/families.h"
#include "problems/suites/hard_cases.h"
#include "solvers/generators/random_problems.h"

namespace smcbench {

namespace fs = std::filesystem;

std::vector<fs::path> SiconosCollectionFiles(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw InvalidInputError("collection: '" + dir.string() + "' is not a directory");
  std::vector<fs::path> files;
  for (const char* sub : {"lcp", "relay", "mlcp"}) {
    if (!fs::is_directory(dir / sub)) continue;
    std::vector<fs::path> found;
    for (const auto& entry : fs::directory_iterator(dir / sub)) {
      const fs::path& p = entry.path();
      // The `_block` LCP files duplicate their dense twins in another storage: solving both adds nothing.
      if (p.extension() == ".dat" && p.stem().string().find("_block") == std::string::npos) found.push_back(p);
    }
    std::sort(found.begin(), found.end());
    files.insert(files.end(), found.begin(), found.end());
  }
  if (files.empty()) throw InvalidInputError("collection: no .dat files under " + dir.string() + "/{lcp,relay,mlcp}");
  return files;
}

ProblemSet SiconosSuite(const std::string& dir, std::vector<std::string>* rejected) {
  ProblemSet set;
  set.name = "siconos";
  set.description = "the Siconos Numerics test collection (LCP, relay, MLCP files of " + dir + ")";
  for (const fs::path& file : SiconosCollectionFiles(dir)) {
    const std::string kind = file.parent_path().filename().string();
    try {
      BoxMLCP problem = ReadSiconosFile(file.string());
      LibraryProblem p = MakeLibraryProblem("siconos/" + kind + "/" + file.stem().string(),
                                     "siconos:" + kind + "/" + file.filename().string(), std::move(problem));
      p.tags = {kind};
      set.problems.push_back(std::move(p));
    } catch (const InvalidInputError& e) {
      if (rejected) rejected->push_back(file.string() + ": " + e.what());
    }
  }
  return set;
}

ProblemSet TinySuite() {
  ProblemSet set;
  set.name = "tiny";
  set.description = "five small generated problems (CI's end-to-end run of bench and report)";
  const auto add = [&](MatrixFamily family, BoundKind bounds, int m, std::uint64_t seed) {
    GeneratorOptions g;
    g.family = family;
    g.bounds = bounds;
    g.size = m;
    g.seed = seed;
    GeneratedProblem gen = GenerateProblem(g);
    std::string id = "tiny/" + gen.problem.name();
    LibraryProblem p = MakeLibraryProblem(std::move(id), "generated:random_problems", std::move(gen.problem));
    p.seed = seed;
    p.expected = ExpectedOutcome::kSolvable;
    p.solution = gen.z_star;
    p.matrix.p_matrix = Tristate::kYes;
    p.matrix.symmetric = family == MatrixFamily::kSymmetricPositiveDefinite ? Tristate::kYes : Tristate::kNo;
    set.problems.push_back(std::move(p));
  };
  add(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 2, 1);
  add(MatrixFamily::kSymmetricPositiveDefinite, BoundKind::kRelay, 8, 2);
  add(MatrixFamily::kNonsymmetricPMatrix, BoundKind::kLCP, 4, 3);
  add(MatrixFamily::kDiagonallyDominant, BoundKind::kMixed, 6, 4);
  // Infeasible LCP: w_1 = −x_1 − x_2 − 1 < 0 for every z ≥ 0, so no z ≥ 0 has w ≥ 0.
  DenseMatrix M(2, 2);
  M << -1.0, -1.0, 0.0, 1.0;
  Vector q(2);
  q << -1.0, 1.0;
  LibraryProblem infeasible =
      MakeLibraryProblem("tiny/infeasible-lcp", "handmade", BoxMLCP::LCP(M, q, "infeasible-lcp"));
  infeasible.expected = ExpectedOutcome::kInfeasible;
  infeasible.tags = {"infeasible"};
  set.problems.push_back(std::move(infeasible));
  return set;
}

namespace {

ProblemSet BuildSuiteProblems(const std::string& name, const SuiteRequest& request) {
  if (name == "tiny") return TinySuite();
  if (name == "siconos") return SiconosSuite(request.siconos_dir);
  if (name == "paper") {
    PaperSuiteOptions o;
    if (request.quick) o.max_steps_per_scene = 8;
    return CapturePaperSuite(o);
  }
  if (name == "families") {
    FamiliesOptions o;
    if (request.quick) o.seeds = 1, o.max_size = 16;
    return FamiliesSuite(o);
  }
  if (name == "hard") return HardSuite(request.siconos_dir);
  if (name == "scale") {
    ScaleOptions o;
    if (request.quick) o.max_size = 1000;
    return ScaleSuite(o);
  }
  std::error_code ec;
  if (fs::is_regular_file(name, ec)) return ReadProblemSetFile(name);
  throw InvalidInputError("unknown suite '" + name +
                          "' (known: paper, families, hard, siconos, scale, tiny, all, or a problem-set file)");
}

}  // namespace

ProblemSet BuildSuite(const std::string& name, const SuiteRequest& request) {
  ProblemSet set = BuildSuiteProblems(name, request);
  if (request.references) AttachReferences(&set);
  return set;
}

std::string ProblemSetContentChecksum(const ProblemSet& set) {
  std::ostringstream image;
  WriteProblemSet(set, image);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(ProblemSetChecksum(image.str())));
  return hex;
}

}  // namespace smcbench
