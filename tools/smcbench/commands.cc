#include "tools/smcbench/commands.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <sstream>

#include "problems/io/data_dirs.h"
#include "problems/io/siconos_format.h"
#include "problems/library/problem_set_io.h"
#include "solvers/core/edit_distance.h"
#include "solvers/auto/auto_solver.h"
#include "solvers/reference/certify.h"
#include "smcbench/version.h"
#include "solvers/registry/backend_settings.h"
#include "solvers/registry/registry.h"
#include "tools/smcbench/avi_solve.h"
#include "tools/smcbench/bench_command.h"
#include "tools/smcbench/compare_command.h"
#include "tools/smcbench/library_command.h"
#include "tools/smcbench/merge_command.h"
#include "tools/smcbench/number_flags.h"
#include "tools/smcbench/output_paths.h"
#include "tools/smcbench/paper.h"
#include "tools/smcbench/problem_files.h"
#include "tools/smcbench/simulate.h"
#include "tools/smcbench/smc_sweep.h"
#include "tools/smcbench/solve_report.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

// Common solve settings shared by `solve` and `collection`.
struct SolveSettings {
  // `solve` uses the default backend (auto: solvers/auto/auto_solver.h); `collection` tables every backend.
  std::vector<std::string> solvers{"auto"};
  double tolerance = 1e-10;
  int max_iterations = 0;
  double time_limit = 30.0;
  int repeat = 1;
  std::vector<std::string> sets;  // "backend.option=value"
  bool no_polish = false;         // SolverOptions::polish = false
  bool warm = false;              // repeats through a session, each from the previous answer (docs/session.md)
  std::optional<ProblemFormat> format;  // --format; unset: guessed from the file (tools/smcbench/problem_files.h)
};

// --format lcp|relay|mlcp|smcps|mtx|avi into settings->format (only the Siconos kinds where allowed says so).
void AddFormatFlag(CLI::App* app, std::optional<ProblemFormat>* format, const std::vector<std::string>& allowed,
                   const std::string& help) {
  std::string choices;
  for (const std::string& name : allowed) choices += (choices.empty() ? "" : "|") + name;
  app->add_option_function<std::string>(
         "--format",
         [format](const std::string& text) {
           format->emplace(*ParseProblemFormat(text));  // the check below admits known names only
         },
         help + " (" + choices + "; default: guessed from the extension, the folder, the name, then the content)")
      ->check(CLI::IsMember(allowed))
      ->type_name("KIND");
}

void AddSolveFlags(CLI::App* app, SolveSettings* s) {
  app->add_option("--solver", s->solvers,
                  "backend name(s) from `smcbench list`, or all (default: " + s->solvers.front() + ")")
      ->expected(1, -1);
  app->add_option("--tol", s->tolerance, "tolerance on the relative and the row-equilibrated natural residual")
      ->check(PositiveNumber());
  app->add_option("--max-iter", s->max_iterations, "iteration/pivot budget (0: backend default)")
      ->check(NonNegativeInteger());
  app->add_option("--time-limit", s->time_limit, "seconds per solve")->check(PositiveNumber());
  app->add_option("--repeat", s->repeat, "cold solves per backend; the median time is reported")
      ->check(CLI::Range(1, 1000000));
  app->add_option("--set", s->sets, "typed backend option, e.g. --set psor.omega=1.2 (see `smcbench list`); it also "
                                    "applies to auto's own instance of that backend");
  app->add_flag("--no-polish", s->no_polish, "no exact polish of the backends' answers (SolverOptions::polish = "
                                             "false): time a raw algorithm");
}

std::vector<std::string> ResolveSolverNames(const std::vector<std::string>& requested) {
  std::vector<std::string> names;
  for (const std::string& name : requested) {
    if (name == "all") {  // every backend that solves box-MLCPs (the files `solve` and `collection` read)
      for (auto known : SolverNames()) {
        if (CreateSolver(known)->info().box) names.emplace_back(known);
      }
    } else {
      CreateSolver(name);  // throws InvalidInputError listing the known names
      names.push_back(name);
    }
  }
  return names;
}

// Creates the backends and applies --set options (solvers/registry/backend_settings.h: a setting must reach a
// selected backend or auto's instance of it); throws InvalidInputError on any bad name or value.
std::vector<std::unique_ptr<Solver>> MakeSolvers(const SolveSettings& s) {
  std::vector<std::unique_ptr<Solver>> solvers;
  for (const std::string& name : ResolveSolverNames(s.solvers)) solvers.push_back(CreateSolver(name));
  ApplyBackendSettings(s.sets, solvers);
  return solvers;
}

SolverOptions MakeOptions(const SolveSettings& s) {
  SolverOptions options;
  options.tolerance = s.tolerance;
  options.max_iterations = s.max_iterations;
  options.time_limit_seconds = s.time_limit;
  options.polish = !s.no_polish;
  return options;
}

int RunList(std::ostream& out) {
  for (auto name : SolverNames()) {
    auto solver = CreateSolver(name);
    const SolverInfo& info = solver->info();
    out << info.name << "\n  algorithm:  " << info.algorithm << "\n  reference:  " << info.reference
        << "\n  accepts:    " << (info.dense ? "dense" : "") << (info.dense && info.sparse ? " + " : "")
        << (info.sparse ? "sparse" : "") << " M" << (info.symmetric_only ? ", symmetric only" : "")
        << (info.mcp ? "; nonlinear MCP" : "") << "\n  kind:       "
        << (info.exact ? "exact (finite termination)" : "iterative") << "\n  size limit: "
        << (info.default_size_limit > 0 ? std::to_string(info.default_size_limit) + " (default)" : "none")
        << "\n  options:\n"
        << solver->OptionsHelp();
  }
  return 0;
}

// `solve FILE`: every chosen backend on each problem of the file (one, or a .smcps set's selected ones); with
// reference, each problem is also certified (solvers/reference/certify.h) from every backend's answer and the cold
// point Π(0) — or judged against the reference a .smcps problem carries — and each answer judged against z*
// (forward error, verdict against the problem's expected outcome, unknown outside a .smcps set).
struct SolvedProblem {
  std::vector<SolveRecord> records;
  ReferenceSolution certified;
};

SolvedProblem SolveOne(const LibraryProblem& library_problem, std::vector<std::unique_ptr<Solver>>& solvers,
                       const SolverOptions& options, const SolveSettings& s, bool reference) {
  const BoxMLCP& problem = library_problem.problem;
  SolvedProblem solved;
  for (auto& solver : solvers) solved.records.push_back(TimedSolve(*solver, problem, options, s.repeat, s.warm));
  if (!reference) return solved;
  if (library_problem.reference.verified()) {
    solved.certified = library_problem.reference;
  } else {
    std::vector<Vector> candidates;
    for (const SolveRecord& r : solved.records) {
      if (r.result.z.size() == problem.size()) candidates.push_back(r.result.z);
    }
    Vector cold;
    ProjectZeroOntoBox(problem.l(), problem.u(), &cold);
    candidates.push_back(cold);
    solved.certified = Certify(problem, candidates);
  }
  for (SolveRecord& r : solved.records) {
    r.has_judgement = true;
    r.judgement = Judge(problem, library_problem.expected, &solved.certified, r.result.status, r.result.z,
                        options.tolerance);
  }
  return solved;
}

void PrintSolved(const LibraryProblem& p, const SolvedProblem& solved, bool reference, std::ostream& out) {
  out << (p.id.empty() ? p.problem.name() : p.id) << " (n = " << p.problem.size() << ")\n";
  if (reference) {
    const ReferenceSolution& certified = solved.certified;
    char line[160];
    std::snprintf(line, sizeof line, "reference: certificate %s, condition %.3g, |z*|inf %.3g",
                  std::string(ToString(certified.certificate)).c_str(), certified.condition,
                  certified.z.size() ? certified.z.cwiseAbs().maxCoeff() : 0.0);
    out << line << (certified.unique() ? "" : " (forward error not defined: z* not proven unique)");
    if (!std::isnan(certified.proved_radius)) {
      std::snprintf(line, sizeof line, "; proved: an exact solution within %.2g of z* (interval enclosure)%s",
                    certified.proved_radius, certified.proved_unique ? ", the only one (M + M^T > 0)" : "");
      out << line;
    }
    out << "\n";
  }
  for (const SolveRecord& r : solved.records) out << "  " << FormatRecordLine(r) << "\n";
}

int RunSolve(const std::string& path, const std::vector<std::string>& ids, const SolveSettings& s, bool json,
             bool reference, std::ostream& out) {
  const FormatChoice choice = ChooseProblemFormat(path, s.format);
  if (choice.format == ProblemFormat::kAvi) {  // an AVI is not a box problem: its own path (avi_solve.h)
    if (!ids.empty()) {
      throw InvalidInputError("--id selects problems of a .smcps set; '" + path + "' is an AVI file (one problem; " +
                              choice.reason + ")");
    }
    if (s.warm) {
      throw InvalidInputError("--warm is not supported for AVI files ('" + path + "'): their repeats are cold "
                              "SolveAvi calls; a warm AVI session is not there yet");
    }
    auto solvers = MakeSolvers(s);
    return RunSolveAvi(path, s.format, solvers, MakeOptions(s), s.repeat, json, reference, out);
  }
  const bool problem_set = choice.format == ProblemFormat::kSmcps;
  if (problem_set && IsAviProblemSetFile(path)) {  // a set of AVIs: each AVI as an AVI file is solved
    if (s.warm) {
      throw InvalidInputError("--warm is not supported for a set of AVIs ('" + path + "'): their repeats are cold "
                              "SolveAvi calls; a warm AVI session is not there yet");
    }
    auto solvers = MakeSolvers(s);
    return RunSolveAviSet(path, ids, solvers, MakeOptions(s), s.repeat, json, reference, out);
  }
  const std::vector<LibraryProblem> problems = ReadProblemFile(path, s.format, ids);
  auto solvers = MakeSolvers(s);
  const SolverOptions options = MakeOptions(s);
  nlohmann::json all = nlohmann::json::array();
  for (const LibraryProblem& p : problems) {
    SolvedProblem solved = SolveOne(p, solvers, options, s, reference);
    if (!json) {
      PrintSolved(p, solved, reference, out);
      continue;
    }
    nlohmann::json array = nlohmann::json::array();
    for (SolveRecord& r : solved.records) {
      if (problem_set) r.problem = p.id;
      array.push_back(RecordToJson(r));
    }
    // One problem file: as before (an array, or {reference, results}); a .smcps set: one object per problem.
    if (!problem_set) {
      if (!reference) {
        all = std::move(array);
      } else {
        all = nlohmann::json{{"reference", ReferenceToJson(solved.certified)}, {"results", std::move(array)}};
      }
      continue;
    }
    nlohmann::json entry{{"problem", p.id}, {"n", p.problem.size()}, {"results", std::move(array)}};
    if (reference) entry["reference"] = ReferenceToJson(solved.certified);
    all.push_back(std::move(entry));
  }
  if (json) out << all.dump(2) << "\n";
  return 0;
}

std::string Cell(const SolveRecord& r) {
  if (!r.error.empty()) return "error";
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "%s / %.1e / %s", std::string(ToString(r.result.status)).c_str(),
                r.result.residual_rel, FormatDuration(r.time_ns_median).c_str());
  return buffer;
}

int RunCollection(const std::string& dir, const SolveSettings& s, const std::string& markdown_path,
                  const std::string& json_path, const std::string& command_line, std::ostream& out,
                  std::ostream& err) {
  if (!markdown_path.empty()) CheckOutputFile("--markdown", markdown_path);
  if (!json_path.empty()) CheckOutputFile("--json", json_path);
  const auto files = SiconosCollectionFiles(dir);
  auto solvers = MakeSolvers(s);
  const SolverOptions options = MakeOptions(s);
  std::ostringstream table;
  table << "| file | n |";
  for (auto& solver : solvers) table << " " << solver->info().name << " |";
  table << "\n|---|---:|";
  for (size_t i = 0; i < solvers.size(); ++i) table << "---|";
  table << "\n";
  nlohmann::json all = nlohmann::json::array();
  std::map<std::string, std::map<std::string, int>> tally;  // solver → status → count
  int unreadable = 0;
  for (const fs::path& file : files) {
    const std::string label = file.parent_path().filename().string() + "/" + file.filename().string();
    std::optional<BoxMLCP> problem;
    try {
      problem.emplace(std::move(ReadProblemFile(file.string(), s.format).front().problem));
    } catch (const InvalidInputError& e) {
      ++unreadable;
      table << "| " << label << " | – | rejected by the reader: " << e.what() << " |\n";
      err << "  " << label << ": " << e.what() << "\n";
      continue;
    }
    table << "| " << label << " | " << problem->size() << " |";
    for (auto& solver : solvers) {
      SolveRecord record = TimedSolve(*solver, *problem, options, s.repeat);
      record.problem = label;
      ++tally[record.solver][std::string(ToString(record.result.status))];
      table << " " << Cell(record) << " |";
      all.push_back(RecordToJson(record));
    }
    table << "\n";
    err << "  done " << label << "\n";
  }
  std::ostringstream summary;
  summary << "\n| backend | solved | other statuses |\n|---|---:|---|\n";
  for (auto& solver : solvers) {
    const auto& counts = tally[std::string(solver->info().name)];
    std::string others;
    for (const auto& [status, count] : counts) {
      if (status != "solved") others += (others.empty() ? "" : ", ") + status + " " + std::to_string(count);
    }
    const auto it = counts.find("solved");
    summary << "| " << solver->info().name << " | " << (it == counts.end() ? 0 : it->second) << " / "
            << files.size() - unreadable << " | " << (others.empty() ? "–" : others) << " |\n";
  }
  std::ostringstream doc;
  doc << "Cells: status / relative natural residual / median wall time per cold solve (" << s.repeat
      << " repetition" << (s.repeat > 1 ? "s" : "") << "), tolerance " << s.tolerance
      << ". \"solved\" always means the merit function confirmed it.\n\n"
      << table.str() << summary.str();
  out << doc.str();
  if (!markdown_path.empty()) {
    std::ofstream md(markdown_path);
    if (!md) throw InvalidInputError("cannot write " + markdown_path);
    md << "# Siconos collection: every backend on every file\n\nGenerated by `" << command_line << "`.\n\n"
       << doc.str();
  }
  if (!json_path.empty()) {
    std::ofstream js(json_path);
    if (!js) throw InvalidInputError("cannot write " + json_path);
    js << all.dump(1) << "\n";
  }
  return 0;
}

// The per-size goals of docs/benchmarks.md, 'Performance against the goals' (ns per cold solve at tolerance
// 1e-10); 0 = no goal stated for that size.
double GoalNs(int m) {
  if (m <= 2) return 50;
  if (m == 4) return 150;
  if (m == 16) return 1000;
  if (m == 256) return 1e6;
  if (m == 1024) return 1e7;
  return 0;
}

// Google Benchmark JSON (names "solve/<backend>/<family-bounds>/<m>/", run with repetitions and
// --benchmark_report_aggregates_only) → markdown: one row per problem class and size, one column per backend,
// cell = median time (± coefficient of variation), the best backend in bold, and the goal.
int RunBenchTable(const std::string& path, std::ostream& out) {
  std::ifstream in(path);
  if (!in) throw InvalidInputError("bench-table: cannot read '" + path + "'");
  // Google Benchmark writes non-finite counters (e.g. the CV of a constant) as bare NaN/inf, which is not JSON.
  const std::string raw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string text = std::regex_replace(raw, std::regex(R"(:\s*-?(NaN|nan|inf|Infinity)\b)"), ": null");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInputError("bench-table: '" + path + "' is not JSON: " + e.what());
  }
  if (!doc.contains("benchmarks")) throw InvalidInputError("bench-table: '" + path + "' has no \"benchmarks\"");
  struct Cell {
    double median = -1, cv = -1;
    std::string error;
  };
  std::map<std::pair<std::string, int>, std::map<std::string, Cell>> rows;  // (class, m) → backend → cell
  std::vector<std::string> backends;
  for (const auto& b : doc["benchmarks"]) {
    const std::string name = b.value("run_name", b.value("name", ""));
    std::vector<std::string> parts;
    std::stringstream ss(name);
    for (std::string part; std::getline(ss, part, '/');) parts.push_back(part);
    if (parts.size() < 4 || parts[0] != "solve") continue;
    const std::string backend = parts[1], klass = parts[2];
    const int m = std::atoi(parts[3].c_str());
    if (m <= 0) continue;
    if (std::find(backends.begin(), backends.end(), backend) == backends.end()) backends.push_back(backend);
    Cell& cell = rows[{klass, m}][backend];
    if (b.value("error_occurred", false)) {
      cell.error = b.value("error_message", "error");
      continue;
    }
    const std::string aggregate = b.value("aggregate_name", "");
    const double t = b["real_time"].is_number() ? b["real_time"].get<double>() : -1.0;
    if (aggregate == "median" || (aggregate.empty() && cell.median < 0)) cell.median = t;
    if (aggregate == "cv") cell.cv = t;
  }
  out << "| problem | m |";
  for (const auto& name : backends) out << " " << name << " |";
  out << " goal |\n|---|---:|";
  for (size_t i = 0; i < backends.size(); ++i) out << "---:|";
  out << "---:|\n";
  for (const auto& [key, cells] : rows) {
    double best = -1;
    for (const auto& [name, c] : cells) {
      if (c.error.empty() && c.median >= 0 && (best < 0 || c.median < best)) best = c.median;
    }
    out << "| " << key.first << " | " << key.second << " |";
    for (const auto& name : backends) {
      const auto it = cells.find(name);
      if (it == cells.end()) {
        out << " – |";
      } else if (!it->second.error.empty()) {
        out << " fails: " << it->second.error.substr(0, it->second.error.find(':')) << " |";
      } else {
        const bool is_best = it->second.median == best;
        out << " " << (is_best ? "**" : "") << FormatDuration(it->second.median) << (is_best ? "**" : "");
        if (it->second.cv >= 0) out << " ±" << static_cast<int>(std::lround(100 * it->second.cv)) << "%";
        out << " |";
      }
    }
    const double goal = GoalNs(key.second);
    out << " " << (goal > 0 ? "≤ " + FormatDuration(goal) : "–") << " |\n";
  }
  return 0;
}

// `convert INPUT OUTPUT`: one problem from any readable kind to the kind OUTPUT's extension names (.mtx, .smcps,
// else Siconos relay).
int RunConvert(const std::string& input, std::optional<ProblemFormat> format, const std::string& id,
               const std::string& output, std::ostream& out) {
  CheckOutputFile("OUTPUT", output);
  std::vector<LibraryProblem> problems = ReadProblemFile(input, format, id.empty() ? std::vector<std::string>{}
                                                                                   : std::vector<std::string>{id});
  if (problems.size() != 1) {
    throw InvalidInputError("convert writes one problem; '" + input + "' gives " + std::to_string(problems.size()) +
                            ": choose one with --id");
  }
  WriteProblemFile(problems.front(), output);
  out << "convert: wrote '" << problems.front().id << "' (m = " << problems.front().size() << ", "
      << (problems.front().sparse() ? "sparse" : "dense") << ") to " << output << "\n";
  return 0;
}

// `convert A B C … --out SET.smcps`: every problem of every input, in the order given, into one set named after
// SET's stem. InvalidInputError naming the file for one that cannot be read, and naming both files when two problems
// share an id (a set's ids are unique: rename one with `convert IN OUT --id`, or give the files distinct names).
int RunGather(const std::vector<std::string>& inputs, std::optional<ProblemFormat> format, const std::string& output,
              std::ostream& out) {
  if (fs::path(output).extension() != kProblemSetExtension) {
    throw InvalidInputError("convert --out: '" + output + "' must name a problem set file ending in " +
                            kProblemSetExtension);
  }
  if (inputs.empty()) throw InvalidInputError("convert --out: give at least one INPUT file");
  ProblemSet set;
  set.name = fs::path(output).stem().string();
  set.description = "gathered by smcbench convert from " + std::to_string(inputs.size()) + " file(s)";
  std::map<std::string, std::string> file_of;  // id → the file it came from
  for (const std::string& input : inputs) {
    for (LibraryProblem& p : ReadProblemFile(input, format, {})) {
      const auto [it, inserted] = file_of.emplace(p.id, input);
      if (!inserted) {
        throw InvalidInputError("convert --out: problem id '" + p.id + "' of '" + input + "' is also in '" +
                                it->second + "': a set's ids must be unique");
      }
      set.problems.push_back(std::move(p));
    }
  }
  WriteProblemSetFile(set, output);
  out << "convert: wrote " << set.problems.size() << " problems from " << inputs.size() << " file(s) to " << output
      << "\n";
  return 0;
}

// "unknown flag '--solvr' (did you mean '--solver'?)" for the first word of argv that looks like a long flag and is
// not one of command's flags (its own or its parents'); empty when there is none (then CLI11's message is kept).
// Only words after the command's name are looked at, so a flag of another command is not suggested.
std::string UnknownFlagMessage(const CLI::App& command, int argc, const char* const* argv) {
  std::vector<std::string> known;
  for (const CLI::App* app = &command; app != nullptr; app = app->get_parent()) {
    for (const CLI::Option* option : app->get_options()) {
      for (const std::string& name : option->get_lnames()) known.push_back("--" + name);
    }
  }
  for (int i = 1; i < argc; ++i) {
    std::string word = argv[i];
    if (word == "--") break;
    if (word.rfind("--", 0) != 0 || word.size() < 3) continue;
    word = word.substr(0, word.find('='));
    if (std::find(known.begin(), known.end(), word) != known.end()) continue;
    std::string nearest;
    std::size_t best = std::string::npos;
    for (const std::string& name : known) {
      const std::size_t d = EditDistance(word, name);
      if (d < best) {
        best = d;
        nearest = name;
      }
    }
    std::string message = "unknown flag '" + word + "'";
    // Suggest only a plausible typo: at most a third of the word changed.
    if (!nearest.empty() && best <= std::max<std::size_t>(2, word.size() / 3)) {
      message += " (did you mean '" + nearest + "'?)";
    }
    return message;
  }
  return {};
}

}  // namespace

int RunCli(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  CLI::App app{"smcbench: complementarity solvers benchmarked on implicit-Euler sliding-mode problems"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all");
  const std::string version = "smcbench " + std::string(Version()) + " (git " + std::string(GitRevision()) + ")";
  app.set_version_flag("--version", version, "print the version and the git revision it was built from, then exit");

  auto* list = app.add_subcommand("list", "list the backends with their capabilities, references and options");

  auto* solve = app.add_subcommand("solve", "solve a problem file (Siconos LCP/Relay/MLCP, Matrix Market, the "
                                             "problems of a .smcps set of box-MLCPs or of AVIs, or an AVI file "
                                             ".avi.json) with the default backend (auto), or the ones named by "
                                             "--solver (all: every backend)");
  std::string solve_file;
  std::vector<std::string> solve_ids;
  bool solve_json = false, solve_reference = false;
  SolveSettings solve_settings;
  solve->add_option("FILE", solve_file, "problem file (docs/formats.md)")->required();
  AddFormatFlag(solve, &solve_settings.format, {"lcp", "relay", "mlcp", "smcps", "mtx", "avi"}, "the kind of FILE");
  solve->add_option("--id", solve_ids, "problems of a .smcps set to solve, by id ('PREFIX*': every id with that "
                                       "prefix; default: all)")
      ->expected(1, -1);
  AddSolveFlags(solve, &solve_settings);
  solve->add_flag("--warm", solve_settings.warm, "time the repeats through a prepared session, each starting from "
                                                "the previous answer with the warm active-set path on "
                                                "(docs/session.md): what one time step costs");
  solve->add_flag("--json", solve_json, "print one JSON array, one object per backend (with --reference: one "
                                        "object {reference, results})");
  solve->add_flag("--reference", solve_reference, "certify the problem in extended precision (dense, n <= 64) "
                                                  "and judge every answer by its forward error |z - z*|inf "
                                                  "(keys forward_error, forward_error_rel, verdict)");

  auto* collection = app.add_subcommand("collection", "solve every file of a Siconos collection with every backend");
  std::string collection_dir = DataDirectory(DataFolder::kSiconosCollection), markdown_path, json_path;
  SolveSettings collection_settings;
  collection_settings.solvers = {"all"};
  collection_settings.repeat = 3;
  collection->add_option("DIR", collection_dir, "folder holding lcp/, relay/, mlcp/ (default: $SMCBENCH_SICONOS_DIR, "
                                                "else share/smcbench/siconos of this installation, else the "
                                                "checkout's tests/data/siconos)");
  AddSolveFlags(collection, &collection_settings);
  AddFormatFlag(collection, &collection_settings.format, {"lcp", "relay", "mlcp"},
                "read every file as this Siconos kind");
  collection->add_option("--markdown", markdown_path, "also write the table to this markdown file");
  collection->add_option("--json", json_path, "also write every record as JSON to this file");

  auto* convert = app.add_subcommand("convert", "write one problem in the kind OUTPUT's extension names: NAME.mtx "
                                                 "(Matrix Market: NAME.mtx + NAME_q/_l/_u.mtx), NAME.smcps, else "
                                                 "Siconos relay; or, with --out SET.smcps, gather every problem of "
                                                 "the files INPUT... into one problem set");
  std::string convert_out, convert_id, convert_set;
  std::vector<std::string> convert_args;
  std::optional<ProblemFormat> convert_format;
  convert->add_option("FILES", convert_args, "INPUT OUTPUT, or with --out the INPUT files (docs/formats.md)")
      ->required();
  convert->add_option("--out", convert_set, "gather the problems of every INPUT into this problem set (.smcps)");
  AddFormatFlag(convert, &convert_format, {"lcp", "relay", "mlcp", "smcps", "mtx"}, "the kind of INPUT");
  convert->add_option("--id", convert_id, "the problem of a .smcps INPUT to write (needed if it holds several)");

  auto* bench_table = app.add_subcommand(
      "bench-table", "turn backend_benchmark JSON output into the markdown table of docs/benchmarks.md (median ± CV vs goal)");
  std::string bench_json;
  bench_table->add_option("FILE", bench_json, "Google Benchmark JSON (--benchmark_out)")->required();

  SimulateCommand simulate(&app);
  ScenesCommand scenes(&app);
  PaperCommand paper(&app);
  SmcSweepCommand smc_sweep(&app);
  BenchCommand bench(&app);
  LibraryCommand library(&app);
  MergeCommand merge(&app);
  CompareCommand compare(&app);

  // An unknown first word gets a message naming it and the commands (CLI11 would only say one is required).
  if (argc >= 2 && argv[1][0] != '-') {
    const std::string word = argv[1];
    std::string known;
    bool found = false;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
      found = found || sub->get_name() == word;
      known += (known.empty() ? "" : ", ") + sub->get_name();
    }
    if (!found) {
      err << "smcbench: unknown command '" << word << "' (known: " << known << ")\n";
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {  // --help, --help-all, --version: CLI11 prints them
      std::ostringstream o, e2;
      app.exit(e, o, e2);
      out << o.str();
      err << e2.str();
      return 0;
    }
    // CLI11's own usage errors as ours: one line with the program's prefix, where to look, exit status 2. An
    // unknown flag is named first, with the nearest flag of the command that was being parsed.
    std::string where = "smcbench";
    const CLI::App* innermost = &app;
    for (const CLI::App* sub : app.get_subcommands()) {
      where += " " + sub->get_name();
      innermost = sub;
    }
    std::string what = UnknownFlagMessage(*innermost, argc, argv);
    if (what.empty()) what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    err << "smcbench: " << what << " (see '" << where << " --help')\n";
    return 2;
  }
  std::string command_line = "smcbench";
  for (int i = 1; i < argc; ++i) command_line += std::string(" ") + argv[i];
  try {
    if (list->parsed()) return RunList(out);
    if (solve->parsed()) return RunSolve(solve_file, solve_ids, solve_settings, solve_json, solve_reference, out);
    if (collection->parsed()) {
      return RunCollection(collection_dir, collection_settings, markdown_path, json_path, command_line, out, err);
    }
    if (convert->parsed()) {
      if (!convert_set.empty()) return RunGather(convert_args, convert_format, convert_set, out);
      if (convert_args.size() != 2) {
        throw InvalidInputError("convert: give INPUT OUTPUT, or INPUT... --out SET.smcps to gather files into one set "
                                "(got " + std::to_string(convert_args.size()) + " file names)");
      }
      return RunConvert(convert_args[0], convert_format, convert_id, convert_args[1], out);
    }
    if (bench_table->parsed()) return RunBenchTable(bench_json, out);
    if (simulate.parsed()) return simulate.Run(out, err);
    if (scenes.parsed()) return scenes.Run(out, err);
    if (paper.parsed()) return paper.Run(out, err);
    if (smc_sweep.parsed()) return smc_sweep.Run(out, err);
    if (bench.bench_parsed()) return bench.RunBench(command_line, out, err);
    if (bench.report_parsed()) return bench.RunReport(out, err);
    if (library.parsed()) return library.Run(out, err);
    if (merge.parsed()) return merge.Run(out, err);
    if (compare.parsed()) return compare.Run(out, err);
  } catch (const InvalidInputError& e) {
    err << "smcbench: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    err << "smcbench: internal error: " << e.what() << "\n";
    return 1;
  }
  return 2;
}

}  // namespace smcbench
