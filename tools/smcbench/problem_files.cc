// Problem files by choice and by guess: one place that maps a path (and --format) to a reader, so `solve`,
// `collection` and `convert` agree and a failed guess is explained the same way everywhere.
#include "tools/smcbench/problem_files.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "problems/io/matrix_market.h"
#include "problems/io/siconos_format.h"
#include "problems/library/problem_set_io.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

constexpr ProblemFormat kSiconosFormats[] = {ProblemFormat::kLCP, ProblemFormat::kRelay, ProblemFormat::kMLCP};

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// "a Siconos LCP", "a .smcps problem set", ... for messages.
std::string Describe(ProblemFormat format) {
  switch (format) {
    case ProblemFormat::kLCP:
      return "a Siconos LCP";
    case ProblemFormat::kRelay:
      return "a Siconos relay problem";
    case ProblemFormat::kMLCP:
      return "a Siconos MLCP";
    case ProblemFormat::kSmcps:
      return "a .smcps problem set";
    case ProblemFormat::kMatrixMarket:
      return "a Matrix Market problem";
    case ProblemFormat::kAvi:
      return "an AVI file";
  }
  return "an unknown kind";
}

SiconosKind ToSiconosKind(ProblemFormat format) {
  switch (format) {
    case ProblemFormat::kRelay:
      return SiconosKind::kRelay;
    case ProblemFormat::kMLCP:
      return SiconosKind::kMLCP;
    default:
      return SiconosKind::kLCP;
  }
}

bool HasSmcpsMagic(const std::string& path) {
  static constexpr char kMagic[] = "\x89SMCPS\r\n";
  char head[8] = {};
  std::ifstream in(path, std::ios::binary);
  return in.read(head, sizeof head) && std::memcmp(head, kMagic, sizeof head) == 0;
}

// A JSON object that says "format": "smcbench-avi" (only the first bytes are looked at, and only when the file
// starts with '{', so a Siconos file is never parsed as JSON).
bool DeclaresAviFormat(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
  const std::size_t first = head.find_first_not_of(" \t\r\n");
  if (first == std::string::npos || head[first] != '{') return false;
  return head.find(std::string("\"") + kAviFileFormat + "\"") != std::string::npos;
}

bool ReadsAs(const std::string& path, ProblemFormat format) {
  try {
    ReadSiconosFile(path, ToSiconosKind(format));
    return true;
  } catch (const InvalidInputError&) {
    return false;
  }
}

// Every problem of path read as format (a Siconos or Matrix Market file holds one).
std::vector<LibraryProblem> ReadUnder(const std::string& path, ProblemFormat format) {
  if (format == ProblemFormat::kSmcps) return ReadProblemSetFile(path).problems;
  if (format == ProblemFormat::kAvi) {
    throw InvalidInputError("'" + path + "' is an AVI file, not a box problem: only `smcbench solve` reads it "
                            "(docs/formats.md, \"AVI files\")");
  }
  BoxMLCP problem = format == ProblemFormat::kMatrixMarket ? ReadMatrixMarketProblem(path)
                                                           : ReadSiconosFile(path, ToSiconosKind(format));
  std::string id = problem.name();
  std::vector<LibraryProblem> one;
  one.push_back(MakeLibraryProblem(std::move(id), "file:" + path, std::move(problem)));
  return one;
}

// The problems of a set named by ids, in that order ('PREFIX*': every id with the prefix); Problem is a
// LibraryProblem or an AviLibraryProblem (both have an id).
template <typename Problem>
std::vector<Problem> SelectById(std::vector<Problem> problems, const std::vector<std::string>& ids,
                                const std::string& path) {
  if (ids.empty()) return problems;
  std::vector<Problem> selected;
  for (const std::string& id : ids) {
    const bool prefix = !id.empty() && id.back() == '*';
    const std::string stem = prefix ? id.substr(0, id.size() - 1) : id;
    bool found = false;
    for (const Problem& p : problems) {
      if (prefix ? p.id.compare(0, stem.size(), stem) == 0 : p.id == id) {
        selected.push_back(p);
        found = true;
      }
    }
    if (!found) {
      std::string examples;
      for (std::size_t i = 0; i < problems.size() && i < 3; ++i) {
        examples += (i ? ", " : "") + QuoteForMessage(problems[i].id, 80);
      }
      throw InvalidInputError("--id " + QuoteForMessage(id, 80) + ": no such problem in '" + path + "' (" +
                              std::to_string(problems.size()) + " problems, e.g. " + examples + "; `smcbench library " +
                              path + "` lists them; 'PREFIX*' selects by prefix)");
    }
  }
  return selected;
}

}  // namespace

std::string_view ToString(ProblemFormat format) {
  switch (format) {
    case ProblemFormat::kLCP:
      return "lcp";
    case ProblemFormat::kRelay:
      return "relay";
    case ProblemFormat::kMLCP:
      return "mlcp";
    case ProblemFormat::kSmcps:
      return "smcps";
    case ProblemFormat::kMatrixMarket:
      return "mtx";
    case ProblemFormat::kAvi:
      return "avi";
  }
  return "unknown";
}

std::optional<ProblemFormat> ParseProblemFormat(std::string_view text) {
  for (ProblemFormat f : {ProblemFormat::kLCP, ProblemFormat::kRelay, ProblemFormat::kMLCP, ProblemFormat::kSmcps,
                          ProblemFormat::kMatrixMarket, ProblemFormat::kAvi}) {
    if (text == ToString(f)) return f;
  }
  return std::nullopt;
}

FormatChoice ChooseProblemFormat(const std::string& path, std::optional<ProblemFormat> requested) {
  if (requested) return {*requested, true, "chosen with --format " + std::string(ToString(*requested))};
  const fs::path p(path);
  const std::string extension = Lower(p.extension().string());
  const std::string folder = Lower(p.parent_path().filename().string());
  const std::string file = Lower(p.filename().string());
  if (extension == ".smcps") return {ProblemFormat::kSmcps, false, "guessed from the extension '.smcps'"};
  if (extension == ".mtx") return {ProblemFormat::kMatrixMarket, false, "guessed from the extension '.mtx'"};
  if (HasAviFileExtension(path)) return {ProblemFormat::kAvi, false, "guessed from the extension '.avi.json'"};
  for (ProblemFormat f : kSiconosFormats) {
    if (folder == ToString(f)) return {f, false, "guessed from the folder name '" + folder + "/'"};
  }
  // "relay2_mlcp.dat" is an MLCP: "mlcp" is looked for first.
  if (file.find("mlcp") != std::string::npos) return {ProblemFormat::kMLCP, false, "guessed from 'mlcp' in the file name"};
  if (file.find("relay") != std::string::npos) {
    return {ProblemFormat::kRelay, false, "guessed from 'relay' in the file name"};
  }
  if (HasSmcpsMagic(path)) return {ProblemFormat::kSmcps, false, "guessed from the content (the .smcps magic bytes)"};
  if (DeclaresAviFormat(path)) {
    return {ProblemFormat::kAvi, false,
            "guessed from the content (\"format\": \"" + std::string(kAviFileFormat) + "\")"};
  }
  // Nothing in the name: the content decides when exactly one Siconos reading fits.
  std::vector<ProblemFormat> fitting;
  for (ProblemFormat f : kSiconosFormats) {
    if (ReadsAs(path, f)) fitting.push_back(f);
  }
  if (fitting.size() == 1) {
    return {fitting[0], false, "guessed from the content (no folder or name tells the kind; it reads only as " +
                                   std::string(ToString(fitting[0])) + ")"};
  }
  if (fitting.empty()) {
    return {ProblemFormat::kLCP, false,
            "the default: no folder or name tells the kind and it reads as none of lcp, relay, mlcp"};
  }
  std::string kinds;
  for (ProblemFormat f : fitting) kinds += (kinds.empty() ? "" : ", ") + std::string(ToString(f));
  return {fitting[0], false, "guessed from the content (it reads as " + kinds + "; the first taken)"};
}

std::vector<LibraryProblem> ReadProblemFile(const std::string& path, std::optional<ProblemFormat> requested,
                                            const std::vector<std::string>& ids) {
  const FormatChoice choice = ChooseProblemFormat(path, requested);
  if (!ids.empty() && choice.format != ProblemFormat::kSmcps) {
    throw InvalidInputError("--id selects problems of a .smcps set; '" + path + "' is read as " +
                            Describe(choice.format) + " (one problem; " + choice.reason + ")");
  }
  if (choice.format == ProblemFormat::kAvi) ReadUnder(path, choice.format);  // refused whatever the guess
  if (choice.format == ProblemFormat::kSmcps && IsAviProblemSetFile(path)) {  // not a kind --format could change
    throw InvalidInputError("'" + path + "' is a set of AVIs (.smcps format version " +
                            std::to_string(kAviProblemSetFormatVersion) + "), not of box problems: `smcbench solve`, "
                            "`smcbench library` and `smcbench bench --suite` read it (docs/formats.md, \"Sets of "
                            "AVIs\")");
  }
  std::vector<LibraryProblem> problems;
  try {
    problems = ReadUnder(path, choice.format);
  } catch (const InvalidInputError& e) {
    std::error_code ec;
    if (choice.chosen || !fs::is_regular_file(path, ec)) throw;  // the user's choice, or no file: nothing to add
    std::string hint;
    for (ProblemFormat f : kSiconosFormats) {
      if (f != choice.format && choice.format != ProblemFormat::kSmcps && ReadsAs(path, f)) {
        hint = "it reads as " + Describe(f) + ": choose that with --format " + std::string(ToString(f));
        break;
      }
    }
    if (hint.empty()) hint = std::string("choose another kind with --format ") + kProblemFormatChoices;
    throw InvalidInputError(std::string(e.what()) + " (read as " + Describe(choice.format) + ", " + choice.reason +
                            "; " + hint + ")");
  }
  return SelectById(std::move(problems), ids, path);
}

bool IsAviProblemSetFile(const std::string& path) {
  try {
    return ReadProblemSetKind(path) == ProblemSetKind::kAvi;
  } catch (const InvalidInputError&) {
    return false;
  }
}

std::vector<AviLibraryProblem> ReadAviProblemSetById(const std::string& path, const std::vector<std::string>& ids) {
  return SelectById(ReadAviProblemSetFile(path).problems, ids, path);
}

AviFile ReadAviProblemFile(const std::string& path, std::optional<ProblemFormat> requested) {
  const FormatChoice choice = ChooseProblemFormat(path, requested);
  if (choice.format != ProblemFormat::kAvi) {
    throw InvalidInputError("'" + path + "' is read as " + Describe(choice.format) + " (" + choice.reason +
                            "), not as an AVI file");
  }
  try {
    return ReadAviFile(path);
  } catch (const InvalidInputError& e) {
    std::error_code ec;
    if (choice.chosen || !fs::is_regular_file(path, ec)) throw;
    throw InvalidInputError(std::string(e.what()) + " (read as an AVI file, " + choice.reason +
                            "; choose another kind with --format " + kProblemFormatChoices + ")");
  }
}

void WriteProblemFile(const LibraryProblem& problem, const std::string& path) {
  const std::string extension = Lower(fs::path(path).extension().string());
  if (extension == ".mtx") {
    WriteMatrixMarketProblem(problem.problem, path);
  } else if (extension == ".smcps") {
    ProblemSet set{fs::path(path).stem().string(), "converted by smcbench convert", {problem}};
    WriteProblemSetFile(set, path);
  } else {
    WriteSiconosRelayFile(problem.problem, path);
  }
}

}  // namespace smcbench
