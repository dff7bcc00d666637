// The `avi` suite through the .smcps format (version 4, problems/library/problem_set_io.h): every AVI, its
// expected outcome and its certified reference come back bit for bit, the file is a fixed point of the writer, and
// the matrices the twisting captures share (M and the parallelogram H along a run) are stored once.
#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <sstream>
#include <string>

#include "problems/avi_library/avi_suite.h"
#include "problems/library/problem_set_io.h"

namespace smcbench {
namespace {

// Empty matrices and vectors compare equal by their sizes alone: their data() may be null, which memcmp must not see.
bool SameBits(const DenseMatrix& a, const DenseMatrix& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         (a.size() == 0 ||
          std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0);
}

bool SameBits(const Vector& a, const Vector& b) {
  return a.size() == b.size() &&
         (a.size() == 0 ||
          std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0);
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

std::string Serialize(const AviProblemSet& set) {
  std::ostringstream out;
  WriteAviProblemSet(set, out);
  return out.str();
}

TEST(AviSetIo, TheQuickSuiteRoundTripsBitForBit) {
  const AviProblemSet set = BuildAviSuite(true);
  ASSERT_GT(set.problems.size(), 10u);
  const std::string bytes = Serialize(set);
  const AviProblemSet back = ReadAviProblemSetBytes(bytes, "avi.smcps");
  EXPECT_EQ(back.name, set.name);
  EXPECT_EQ(back.description, set.description);
  ASSERT_EQ(back.problems.size(), set.problems.size());
  int verified = 0;
  for (std::size_t i = 0; i < set.problems.size(); ++i) {
    const AviLibraryProblem &a = set.problems[i], &b = back.problems[i];
    SCOPED_TRACE(a.id);
    EXPECT_EQ(b.id, a.id);
    EXPECT_EQ(b.source, a.source);
    EXPECT_EQ(b.tags, a.tags);
    EXPECT_EQ(b.expected, a.expected);
    EXPECT_EQ(b.metadata, a.metadata);
    EXPECT_EQ(b.problem->name(), a.problem->name());
    EXPECT_TRUE(SameBits(b.problem->M(), a.problem->M()));
    EXPECT_TRUE(SameBits(b.problem->q(), a.problem->q()));
    EXPECT_TRUE(SameBits(b.problem->H(), a.problem->H()));
    EXPECT_TRUE(SameBits(b.problem->K(), a.problem->K()));
    EXPECT_TRUE(SameBits(b.problem->E(), a.problem->E()));
    EXPECT_TRUE(SameBits(b.problem->f(), a.problem->f()));
    EXPECT_EQ(b.problem->boundedness(), a.problem->boundedness());
    const AviReference &r = a.reference, &s = b.reference;
    EXPECT_EQ(s.reduced.certificate, r.reduced.certificate);
    EXPECT_TRUE(SameBits(s.reduced.condition, r.reduced.condition));
    EXPECT_TRUE(SameBits(s.reduced.z, r.reduced.z));
    EXPECT_TRUE(SameBits(s.solution.lambda, r.solution.lambda));
    EXPECT_TRUE(SameBits(s.solution.mu, r.solution.mu));
    EXPECT_TRUE(SameBits(s.solution.nu, r.solution.nu));
    EXPECT_EQ(s.strictly_monotone, r.strictly_monotone);
    EXPECT_EQ(s.lambda_unique, r.lambda_unique);
    verified += r.verified();
  }
  EXPECT_GT(verified, 0);
  EXPECT_EQ(Serialize(back), bytes);  // a fixed point

  // Sharing: fewer matrix records than the distinct (M, H, E) of the AVIs counted one by one, since the captured
  // steps of a twisting run share M and H. Counted independently of the writer, by bits.
  std::set<std::string> distinct;
  std::size_t uses = 0;
  const auto add = [&](const DenseMatrix& A) {
    if (A.rows() == 0) return;
    ++uses;
    std::string key(reinterpret_cast<const char*>(A.data()), sizeof(double) * static_cast<std::size_t>(A.size()));
    key += "/" + std::to_string(A.rows()) + "x" + std::to_string(A.cols());
    distinct.insert(key);
  };
  for (const AviLibraryProblem& p : set.problems) {
    add(p.problem->M());
    add(p.problem->H());
    add(p.problem->E());
  }
  ASSERT_LT(distinct.size(), uses);
  std::size_t matrix_records = 0;
  for (std::size_t pos = 16; pos < bytes.size();) {
    std::uint64_t length = 0;  // the record's u64 body length, little-endian
    for (int i = 0; i < 8; ++i) {
      length |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[pos + 1 + i])) << (8 * i);
    }
    matrix_records += bytes[pos] == 2;
    pos += 9 + length;
  }
  EXPECT_EQ(matrix_records, distinct.size());
}

}  // namespace
}  // namespace smcbench
