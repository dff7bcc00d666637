#include "problems/library/problem_set.h"

#include <cstdio>
#include <set>

namespace smcbench {

std::string_view ToString(Tristate value) {
  switch (value) {
    case Tristate::kNo:
      return "no";
    case Tristate::kYes:
      return "yes";
    case Tristate::kUnknown:
      break;
  }
  return "unknown";
}

std::string QuoteForMessage(std::string_view text, std::size_t max_bytes) {
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < max_bytes; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
      out += escaped;
    }
  }
  if (text.size() > max_bytes) out += "...";
  return out;
}

void ProblemSet::Validate() const {
  std::set<std::string_view> ids;
  const std::string set_name = QuoteForMessage(name);
  for (const LibraryProblem& p : problems) {
    if (p.id.empty()) throw InvalidInputError("problem set '" + set_name + "': a problem has an empty id");
    if (!ids.insert(p.id).second) {
      throw InvalidInputError("problem set '" + set_name + "': duplicate id '" + QuoteForMessage(p.id) + "'");
    }
    if (p.solution.size() != 0 && p.solution.size() != p.size()) {
      throw InvalidInputError("problem set '" + set_name + "': problem '" + QuoteForMessage(p.id) +
                              "' has a solution of size " +
                              std::to_string(p.solution.size()) + " but n = " + std::to_string(p.size()));
    }
    const ReferenceSolution& r = p.reference;
    if (CertificateFromString(ToString(r.certificate)) != r.certificate) {  // ToString names only known values
      throw InvalidInputError("problem set '" + set_name + "': problem '" + QuoteForMessage(p.id) +
                              "' has a reference certificate with the invalid value " +
                              std::to_string(static_cast<int>(r.certificate)));
    }
    if (r.z.size() != (r.verified() ? p.size() : 0)) {
      throw InvalidInputError("problem set '" + set_name + "': problem '" + QuoteForMessage(p.id) +
                              "' has a reference (certificate '" + std::string(ToString(r.certificate)) +
                              "') with z* of size " + std::to_string(r.z.size()) + " but n = " +
                              std::to_string(p.size()) + (r.verified() ? "" : " and nothing verified"));
    }
  }
}

}  // namespace smcbench
