// What every kind over a problem set shares (a set with a name, a description and problems that have an id), so
// each kind writes only what differs: the set kept, its name, its manifest line, one unit per problem; and SetOf,
// the set of a plan's suite of that kind.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "bench/kinds/problem_kind.h"
#include "solvers/core/problem.h"

namespace smcbench {

// checksum: the kind's content checksum of a set (the manifest's, which merges and resumes compare).
template <typename Set, std::string (*checksum)(const Set&)>
class SetKindSuite : public KindSuite {
 public:
  explicit SetKindSuite(Set set) : set_(std::move(set)) {}

  const Set& set() const { return set_; }
  std::string name() const override { return set_.name; }

  SuiteResults Describe() const override {
    SuiteResults suite;
    suite.suite = set_.name;
    suite.kind = kind();
    suite.description = set_.description;
    suite.problems = static_cast<int>(set_.problems.size());
    suite.checksum = checksum(set_);
    return suite;
  }

  std::vector<SuiteUnit> Units() const override {
    std::vector<SuiteUnit> units;
    for (std::size_t p = 0; p < set_.problems.size(); ++p) units.push_back({p, set_.problems[p].id, false, 0, ""});
    return units;
  }

 protected:
  Set set_;
};

// The set of suite when it is a KindSuiteOfSet (one of the SetKindSuite classes); InvalidInputError naming both
// kinds otherwise.
template <typename KindSuiteOfSet>
const auto& SetOf(const KindSuite& suite, const std::string& kind) {
  const auto* of_kind = dynamic_cast<const KindSuiteOfSet*>(&suite);
  if (!of_kind) throw InvalidInputError("suite " + suite.name() + " is of kind " + suite.kind() + ", not " + kind);
  return of_kind->set();
}

}  // namespace smcbench
