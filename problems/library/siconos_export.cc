#include "problems/library/siconos_export.h"

#include <cmath>
#include <ostream>

#include "problems/io/siconos_format.h"
#include "solvers/core/number_text.h"

namespace smcbench {
namespace {

}  // namespace

bool CanExportSiconosRelay(const LibraryProblem& problem, std::string* why) {
  if (problem.size() > kMaxSiconosRelayExportSize) {
    if (why) {
      *why = "n = " + std::to_string(problem.size()) + " is above " + std::to_string(kMaxSiconosRelayExportSize) +
             " (the relay format stores M densely: n^2 numbers as text)";
    }
    return false;
  }
  const Vector& l = problem.problem.l();
  const Vector& u = problem.problem.u();
  for (Eigen::Index i = 0; i < l.size(); ++i) {
    if (std::isfinite(l[i]) && std::isfinite(u[i])) continue;
    if (why) {
      const char* kind = "an upper-bounded row";
      if (!std::isfinite(l[i]) && !std::isfinite(u[i])) {
        kind = "a free row";
      } else if (!std::isfinite(u[i])) {
        kind = l[i] == 0.0 ? "an LCP row" : "a lower-bounded row";
      }
      *why = "row " + std::to_string(i) + " has l = " + NumberText(l[i]) + ", u = " + NumberText(u[i]) + " (" + kind + ")";
    }
    return false;
  }
  return true;
}

void ExportSiconosRelay(const LibraryProblem& problem, std::ostream& out) {
  std::string why;
  if (!CanExportSiconosRelay(problem, &why)) {
    throw InvalidInputError("problem '" + problem.id + "': cannot be written in Siconos relay format: " + why);
  }
  WriteSiconosRelay(problem.problem, out);
}

void ExportSiconosRelayFile(const LibraryProblem& problem, const std::string& path) {
  std::string why;
  if (!CanExportSiconosRelay(problem, &why)) {
    throw InvalidInputError("problem '" + problem.id + "': cannot be written in Siconos relay format: " + why);
  }
  WriteSiconosRelayFile(problem.problem, path);
}

std::string SiconosRelayFileName(const std::string& id) {
  constexpr std::size_t kMaxStem = 150;
  std::string stem;
  stem.reserve(id.size());
  for (char c : id) {
    const bool keep = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' ||
                      c == '_' || c == '+' || c == '-';
    stem += keep ? c : '_';
  }
  if (stem.empty()) stem = "_";
  if (stem[0] == '.') stem[0] = '_';
  if (stem.size() > kMaxStem) {
    std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a 64 of the full id
    for (unsigned char c : id) h = (h ^ c) * 0x100000001b3ULL;
    static const char kHex[] = "0123456789abcdef";
    std::string suffix = "-";
    for (int shift = 60; shift >= 0; shift -= 4) suffix += kHex[(h >> shift) & 15];
    stem = stem.substr(0, kMaxStem) + suffix;
  }
  return stem + ".dat";
}

}  // namespace smcbench
