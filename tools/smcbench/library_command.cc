#include "tools/smcbench/library_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "problems/avi_library/avi_references.h"
#include "problems/avi_library/avi_suite.h"
#include "problems/library/references.h"
#include "problems/library/siconos_export.h"
#include "problems/suites/catalogue.h"
#include "tools/smcbench/avi_export.h"
#include "tools/smcbench/output_paths.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

// "relay/box" (every bound finite), "lcp" (l = 0, u = +∞ everywhere), "free" (no bound anywhere), else "mixed".
std::string BoundKind(const BoxMLCP& p) {
  bool finite = true, lcp = true, free = true;
  for (int i = 0; i < p.size(); ++i) {
    const double l = p.l()[i], u = p.u()[i];
    finite = finite && std::isfinite(l) && std::isfinite(u);
    lcp = lcp && l == 0.0 && u == kInf;
    free = free && l == -kInf && u == kInf;
  }
  if (finite) return "relay/box";
  if (lcp) return "lcp";
  if (free) return "free";
  return "mixed";
}

// "a 3, b 1" from counts, largest first (ties by name).
std::string Counts(const std::map<std::string, std::size_t>& counts) {
  std::vector<std::pair<std::string, std::size_t>> v(counts.begin(), counts.end());
  std::stable_sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  std::string s;
  for (const auto& [name, count] : v) s += (s.empty() ? "" : ", ") + name + " " + std::to_string(count);
  return s.empty() ? "none" : s;
}

std::string CsvQuote(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string s = "\"";
  for (char c : text) s += c == '"' ? std::string("\"\"") : std::string(1, c);
  return s + "\"";
}

std::string TagLetter(Tristate t) { return t == Tristate::kYes ? "y" : t == Tristate::kNo ? "n" : "?"; }

// "unique 3, none 1": the certificates of the set's references.
std::string CertificateCounts(const ProblemSet& set) {
  std::map<std::string, std::size_t> counts;
  for (const LibraryProblem& p : set.problems) ++counts[std::string(ToString(p.reference.certificate))];
  return Counts(counts);
}

// The condition μ of a reference, 3 digits ("-" when no reference was computed or none verified).
std::string ConditionText(const ReferenceSolution& r) {
  if (!r.verified()) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", r.condition);
  return text;
}

// Whether path names a problem-set file by its extension (".smcps", any case).
bool HasProblemSetExtension(const std::string& path) {
  const std::string extension = kProblemSetExtension;
  if (path.size() <= extension.size()) return false;
  std::string tail = path.substr(path.size() - extension.size());
  for (char& c : tail) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return tail == extension;
}

// What `library FILE` prints for a set of AVIs: the counts of the box summary that apply to an AVI (sizes n, m, p,
// expected outcomes, the references' certificates, sources, labels).
std::string AviSetSummary(const AviProblemSet& set, const ProblemSetFileInfo& info) {
  std::ostringstream o;
  o << "set " << (set.name.empty() ? "(unnamed)" : set.name);
  if (!set.description.empty()) o << ": " << set.description;
  o << "\nfile: " << info.bytes << " bytes, format version " << info.version << " (a set of AVIs), " << info.matrices
    << " distinct matri" << (info.matrices == 1 ? "x" : "ces") << " (M, H, E) for " << info.problems << " AVI"
    << (info.problems == 1 ? "" : "s") << "\n";
  std::map<std::string, std::size_t> sizes, expected, certificates, sources, labels;
  std::size_t lambda_unique = 0;
  for (const AviLibraryProblem& p : set.problems) {
    ++sizes["n=" + std::to_string(p.size())];
    ++expected[std::string(ToString(p.expected))];
    ++certificates[std::string(ToString(p.reference.reduced.certificate))];
    ++sources[p.source.substr(0, p.source.find(':'))];
    for (const std::string& t : p.tags) ++labels[t];
    lambda_unique += p.reference.lambda_unique;
  }
  o << "AVIs: " << set.problems.size() << "\nsizes: " << Counts(sizes) << "\nexpected: " << Counts(expected)
    << "\nreferences: " << Counts(certificates) << " (lambda* unique: " << lambda_unique << ")\nsources: "
    << Counts(sources) << "\nlabels: " << Counts(labels) << "\n";
  return o.str();
}

// "unique 3, none 1": the certificates of the references of a set of AVIs.
std::string AviCertificateCounts(const AviProblemSet& set) {
  std::map<std::string, std::size_t> counts;
  for (const AviLibraryProblem& p : set.problems) ++counts[std::string(ToString(p.reference.reduced.certificate))];
  return Counts(counts);
}

}  // namespace

std::string ProblemSetSummary(const ProblemSet& set, const ProblemSetFileInfo* info) {
  std::ostringstream o;
  o << "set " << (set.name.empty() ? "(unnamed)" : set.name);
  if (!set.description.empty()) o << ": " << set.description;
  o << "\n";
  if (info) {
    o << "file: " << info->bytes << " bytes, format version " << info->version << ", " << info->matrices
      << " distinct matri" << (info->matrices == 1 ? "x" : "ces") << " for " << info->problems << " problem"
      << (info->problems == 1 ? "" : "s") << "\n";
  }
  const std::size_t total = set.problems.size();
  o << "problems: " << total;
  if (total == 0) {
    o << "\n";
    return o.str();
  }
  std::size_t sparse = 0, seeded = 0, with_solution = 0;
  std::map<int, std::size_t> sizes;
  std::map<std::string, std::size_t> bounds, expected, sources, labels;
  std::size_t tag_counts[3][3] = {};  // [symmetric, pd, p][unknown, no, yes]
  for (const LibraryProblem& p : set.problems) {
    sparse += p.sparse();
    seeded += p.seed.has_value();
    with_solution += p.solution.size() != 0;
    ++sizes[p.size()];
    ++bounds[BoundKind(p.problem)];
    ++expected[std::string(ToString(p.expected))];
    ++sources[p.source.substr(0, p.source.find(':'))];
    for (const std::string& t : p.tags) ++labels[t];
    const Tristate t3[3] = {p.matrix.symmetric, p.matrix.positive_definite, p.matrix.p_matrix};
    for (int k = 0; k < 3; ++k) ++tag_counts[k][static_cast<int>(t3[k])];
  }
  o << " (dense " << total - sparse << ", sparse " << sparse << ")\n";
  o << "sizes: ";
  if (sizes.size() <= 8) {
    std::string s;
    for (const auto& [n, count] : sizes) {
      s += (s.empty() ? "" : ", ") + ("n=" + std::to_string(n)) + " x" + std::to_string(count);
    }
    o << s << "\n";
  } else {
    o << sizes.size() << " distinct, n = " << sizes.begin()->first << " ... " << sizes.rbegin()->first << "\n";
  }
  o << "bounds: " << Counts(bounds) << "\n";
  o << "expected: " << Counts(expected) << "\n";
  o << "references: " << CertificateCounts(set) << "\n";
  o << "matrix tags (yes / no / unknown):\n";
  const char* names[3] = {"symmetric", "positive definite", "P-matrix"};
  for (int k = 0; k < 3; ++k) {
    o << "  " << names[k] << std::string(19 - std::string(names[k]).size(), ' ') << tag_counts[k][2] << " / "
      << tag_counts[k][1] << " / " << tag_counts[k][0] << "\n";
  }
  o << "sources: " << Counts(sources) << "\n";
  o << "labels: " << Counts(labels) << "\n";
  o << "seeded: " << seeded << ", with a known solution: " << with_solution << "\n";
  return o.str();
}

std::size_t ExportProblemSetRelay(const ProblemSet& set, const std::string& dir, std::string* skipped) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    throw InvalidInputError("--export-relay: cannot create the folder '" + dir + "'" +
                            (ec ? ": " + ec.message() : std::string()));
  }
  std::set<std::string> used;
  std::string index = "file,id,n,expected\n";
  std::size_t written = 0;
  for (const LibraryProblem& p : set.problems) {
    std::string why;
    if (!CanExportSiconosRelay(p, &why)) {
      if (skipped) *skipped += p.id + ": " + why + "\n";
      continue;
    }
    std::string name = SiconosRelayFileName(p.id);
    const std::string stem = name.substr(0, name.size() - 4);
    for (int k = 2; used.count(name) || name == "index.csv"; ++k) name = stem + "-" + std::to_string(k) + ".dat";
    used.insert(name);
    ExportSiconosRelayFile(p, (fs::path(dir) / name).string());
    index += CsvQuote(name) + "," + CsvQuote(p.id) + "," + std::to_string(p.size()) + "," +
             std::string(ToString(p.expected)) + "\n";
    ++written;
  }
  const std::string index_path = (fs::path(dir) / "index.csv").string();
  std::ofstream out(index_path, std::ios::binary | std::ios::trunc);
  out << index;
  out.close();
  if (!out) throw InvalidInputError("--export-relay: cannot write '" + index_path + "'");
  return written;
}

struct LibraryCommand::Flags {
  std::string file, export_dir, certify_out;
  // --write-suite NAME FILE: a built-in suite frozen to a file (what shards of a sharded run can all read).
  std::vector<std::string> write_suite;
  std::string siconos_dir = SuiteRequest{}.siconos_dir;
  bool quick = false;
  bool list = false;
  int certify_max_size = ReferenceOptions{}.max_size;
};

LibraryCommand::LibraryCommand(CLI::App* app) : flags_(std::make_unique<Flags>()) {
  command_ = app->add_subcommand("library", "summarize a problem-set file (.smcps, see problems/library/README.md), "
                                            "attach certified reference solutions, export it to Siconos relay files");
  command_->add_option("FILE", flags_->file, "problem-set file (written by simulate --record, bench, ...)");
  command_->add_option("--write-suite", flags_->write_suite,
                       "write the built-in suite NAME (as `bench --suite NAME` builds it, certified references "
                       "attached) to FILE.smcps and print its checksum; `bench --suite FILE.smcps` then runs the "
                       "same problems with the same checksum in results.json; NAME avi: FILE.smcps receives a set "
                       "of AVIs (format version " + std::to_string(kAviProblemSetFormatVersion) + "), any other "
                       "FILE is a folder that receives one .avi.json file per AVI (docs/formats.md)")
      ->expected(2)
      ->type_name("NAME FILE");
  command_->add_option("--siconos-dir", flags_->siconos_dir, "with --write-suite: the Siconos collection (default " +
                                                                 SuiteRequest{}.siconos_dir + ")");
  command_->add_flag("--quick", flags_->quick, "with --write-suite: the suite as `bench --quick` builds it");
  command_->add_flag("--list", flags_->list,
                     "also print one line per problem: id, n, storage, expected, matrix tags, the reference's "
                     "certificate and its condition mu (after --certify when both are given)");
  command_->add_option("--certify", flags_->certify_out,
                       "compute a certified reference solution (extended-precision active-set certification, "
                       "candidates: the known solution and the answers of lemke, enum and newton) for every "
                       "problem that has none and at most --certify-max-size rows, and write the set with them "
                       "to OUT.smcps (format version " + std::to_string(kProblemSetFormatVersion) +
                       "; OUT may be FILE itself); existing references are kept; on a set of AVIs the reduction "
                       "to a box-MLCP is certified (CertifyAvi), its n + m + p rows counted against "
                       "--certify-max-size, and OUT is written in format version " +
                       std::to_string(kAviProblemSetFormatVersion))
      ->type_name("OUT");
  command_->add_option("--certify-max-size", flags_->certify_max_size,
                       "larger problems keep certificate 'none' (default " +
                           std::to_string(ReferenceOptions{}.max_size) +
                           "; each quad-precision active-set solve costs ~n^3, a few ms at n = 64)")
      ->check(CLI::Range(1, 256));
  command_->add_option("--export-relay", flags_->export_dir,
                       "write every problem with finite bounds to DIR/<id>.dat in Siconos relay format, plus "
                       "DIR/index.csv; problems with infinite bounds are listed and make the exit status 1 (a set "
                       "of box-MLCPs only)");
}

LibraryCommand::~LibraryCommand() = default;

// `library FILE` on a set of AVIs: its summary, --certify (AttachAviReferences; the limit counts the reduction's
// rows n + m + p, what the certifier solves) and --list. --export-relay is refused: relay files hold box problems.
int LibraryCommand::RunAviSet(std::ostream& out) const {
  const Flags& f = *flags_;
  if (!f.export_dir.empty()) {
    throw InvalidInputError("library: --export-relay takes a set of box-MLCPs (Siconos relay files hold a box "
                            "problem); '" + f.file + "' is a set of AVIs");
  }
  ProblemSetFileInfo info;
  AviProblemSet set = ReadAviProblemSetFile(f.file, &info);
  out << AviSetSummary(set, info);
  if (!f.certify_out.empty()) {
    ReferenceOptions options;
    options.max_size = f.certify_max_size;
    std::size_t todo = 0, kept = 0, too_large = 0;
    for (const AviLibraryProblem& p : set.problems) {
      if (p.reference.reduced.certificate != Certificate::kNone) {
        ++kept;
      } else if (AviReductionRows(*p.problem) > options.max_size) {
        ++too_large;
      } else {
        ++todo;
      }
    }
    const auto start = std::chrono::steady_clock::now();
    try {
      AttachAviReferences(&set, options);
    } catch (const std::logic_error& e) {
      // A solution verified on an AVI the file says is infeasible: the file's data is wrong, not smcbench.
      throw InvalidInputError("--certify: " + std::string(e.what()) + "; nothing was written");
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    WriteAviProblemSetFile(set, f.certify_out);
    char time_text[32];
    std::snprintf(time_text, sizeof time_text, "%.2f", seconds);
    out << "\ncertified " << todo << " AVI(s) in " << time_text << " s (kept " << kept
        << " existing reference(s); " << too_large << " with more than " << options.max_size
        << " rows n + m + p left without)\n"
        << "references: " << AviCertificateCounts(set) << "\n"
        << "wrote " << f.certify_out << " (format version " << kAviProblemSetFormatVersion << ")\n";
  }
  if (f.list) {
    out << "\nid | n | m | p | expected | certificate | mu\n";
    for (const AviLibraryProblem& p : set.problems) {
      out << p.id << " | " << p.size() << " | " << p.problem->inequality_count() << " | "
          << p.problem->equality_count() << " | " << ToString(p.expected) << " | "
          << ToString(p.reference.reduced.certificate) << " | " << ConditionText(p.reference.reduced) << "\n";
    }
  }
  return 0;
}

bool LibraryCommand::parsed() const { return command_->parsed(); }

int LibraryCommand::Run(std::ostream& out, std::ostream& err) const {
  const Flags& f = *flags_;
  // Every output path before any work (building and certifying a suite takes seconds).
  if (!f.certify_out.empty()) CheckOutputFile("--certify", f.certify_out);
  if (!f.export_dir.empty()) CheckOutputFolder("--export-relay", f.export_dir);
  if (!f.write_suite.empty()) {
    if (!f.file.empty()) throw InvalidInputError("library: --write-suite NAME FILE takes no other FILE");
    const std::string& target = f.write_suite.at(1);
    if (f.write_suite.at(0) == kAviSuiteName && !HasProblemSetExtension(target)) {
      CheckOutputFolder("--write-suite", target);
    } else {
      CheckOutputFile("--write-suite", target);
    }
    if (f.write_suite.at(0) == kAviSuiteName) {  // one set of AVIs (.smcps), or a folder of AVI files
      const AviProblemSet set = BuildAviSuite(f.quick);
      if (HasProblemSetExtension(target)) {
        WriteAviProblemSetFile(set, target);
        out << "wrote suite " << kAviSuiteName << " (" << set.problems.size() << " AVIs, format version "
            << kAviProblemSetFormatVersion << ") to " << target << "\n";
        return 0;
      }
      const std::size_t written = ExportAviSet(set, target);
      out << "wrote suite " << kAviSuiteName << " (" << written << " AVI files .avi.json and index.csv) to " << target
          << "/\n";
      return 0;
    }
    SuiteRequest request;
    request.siconos_dir = f.siconos_dir;
    request.quick = f.quick;
    ProblemSet set = BuildSuite(f.write_suite.at(0), request);
    set.Validate();
    WriteProblemSetFile(set, f.write_suite.at(1));
    out << "wrote suite " << set.name << " (" << set.problems.size() << " problems, checksum "
        << ProblemSetContentChecksum(set) << ") to " << f.write_suite.at(1) << "\n";
    return 0;
  }
  if (f.file.empty()) {  // a usage error, like CLI11's own: exit status 2
    err << "smcbench: library: FILE is required (a problem-set file), or --write-suite NAME FILE (see 'smcbench "
           "library --help')\n";
    return 2;
  }
  if (ReadProblemSetKind(f.file) == ProblemSetKind::kAvi) return RunAviSet(out);
  ProblemSetFileInfo info;
  ProblemSet set = ReadProblemSetFile(f.file, &info);
  out << ProblemSetSummary(set, &info);
  if (!f.certify_out.empty()) {
    ReferenceOptions options;
    options.max_size = f.certify_max_size;
    std::size_t todo = 0, kept = 0, too_large = 0;
    for (const LibraryProblem& p : set.problems) {
      if (p.reference.certificate != Certificate::kNone) {
        ++kept;
      } else if (p.size() > options.max_size) {
        ++too_large;
      } else {
        ++todo;
      }
    }
    const auto start = std::chrono::steady_clock::now();
    try {
      AttachReferences(&set, options);
    } catch (const std::logic_error& e) {
      // A solution verified on a problem the file says is infeasible: the file's data is wrong, not smcbench.
      throw InvalidInputError("--certify: " + std::string(e.what()) + "; nothing was written");
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    WriteProblemSetFile(set, f.certify_out);
    char time_text[32];
    std::snprintf(time_text, sizeof time_text, "%.2f", seconds);
    out << "\ncertified " << todo << " problem(s) in " << time_text << " s (kept " << kept
        << " existing reference(s); " << too_large << " above " << options.max_size << " rows left without)\n"
        << "references: " << CertificateCounts(set) << "\n"
        << "wrote " << f.certify_out << " (format version " << kProblemSetFormatVersion << ")\n";
  }
  if (f.list) {
    out << "\nid | n | storage | expected | symmetric/pd/P | certificate | mu\n";
    for (const LibraryProblem& p : set.problems) {
      out << p.id << " | " << p.size() << " | " << (p.sparse() ? "sparse" : "dense") << " | "
          << ToString(p.expected) << " | " << TagLetter(p.matrix.symmetric) << TagLetter(p.matrix.positive_definite)
          << TagLetter(p.matrix.p_matrix) << " | " << ToString(p.reference.certificate) << " | "
          << ConditionText(p.reference) << "\n";
    }
  }
  if (f.export_dir.empty()) return 0;
  std::string skipped;
  const std::size_t written = ExportProblemSetRelay(set, f.export_dir, &skipped);
  out << "exported " << written << " of " << set.problems.size() << " problem(s) to " << f.export_dir
      << " (Siconos relay format, index.csv)\n";
  if (skipped.empty()) return 0;
  const std::size_t count = static_cast<std::size_t>(std::count(skipped.begin(), skipped.end(), '\n'));
  err << skipped << "smcbench: --export-relay: " << count << " problem(s) cannot be written in Siconos relay format "
      << "(it needs finite bounds on every row); the other " << written << " were written\n";
  return 1;
}

}  // namespace smcbench
