// The AVI suite as AVI files (avi_export.h).
#include "tools/smcbench/avi_export.h"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>

#include "problems/io/avi_file.h"
#include "solvers/core/problem.h"

namespace smcbench {

std::string AviExportFileName(const std::string& id) {
  std::string stem = id.rfind("avi/", 0) == 0 ? id.substr(4) : id;
  for (char& c : stem) {
    const auto u = static_cast<unsigned char>(c);
    if (!std::isalnum(u) && c != '.' && c != '_' && c != '-') c = '-';
  }
  return stem + kAviFileExtension;
}

std::size_t ExportAviSet(const AviProblemSet& set, const std::string& dir) {
  namespace fs = std::filesystem;
  set.Validate();
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InvalidInputError("cannot create '" + dir + "': " + ec.message());
  std::set<std::string> names;
  std::string index = "file,id,n,m,p,expected,source\n";
  for (const AviLibraryProblem& p : set.problems) {
    const std::string name = AviExportFileName(p.id);
    if (!names.insert(name).second) {
      throw InvalidInputError("AVI ids '" + p.id + "' and another give the same file name '" + name + "'");
    }
    const Vector solution = p.reference.verified() ? p.reference.solution.lambda : Vector();
    WriteAviFile(*p.problem, (fs::path(dir) / name).string(), solution, p.expected);
    // Ids and sources are plain ASCII without commas (avi_library.h), so the CSV needs no quoting.
    index += name + "," + p.id + "," + std::to_string(p.problem->size()) + "," +
             std::to_string(p.problem->inequality_count()) + "," + std::to_string(p.problem->equality_count()) +
             "," + std::string(ToString(p.expected)) + "," + p.source + "\n";
  }
  const std::string index_path = (fs::path(dir) / "index.csv").string();
  std::ofstream out(index_path);
  out << index;
  out.close();
  if (!out) throw InvalidInputError("cannot write '" + index_path + "'");
  return set.problems.size();
}

}  // namespace smcbench
