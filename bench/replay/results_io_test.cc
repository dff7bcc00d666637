// results.json read back: every status by its name, and an unknown name an error that says where it is.
#include "bench/replay/results_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "bench/replay/jobs.h"

namespace smcbench {
namespace {

namespace fs = std::filesystem;

constexpr int kLastStatus = static_cast<int>(SolveStatus::kDiverged);

// One suite whose records carry every status in turn (and a sweep record after them).
BenchResults EveryStatus() {
  BenchResults results;
  results.command = "results_io_test";
  SuiteResults suite;
  suite.suite = "statuses";
  suite.description = "one record per status";
  for (int s = 0; s <= kLastStatus; ++s) {
    ReplayRecord r;
    r.suite = suite.suite;
    r.problem = "p" + std::to_string(s);
    r.solver = "lemke";
    r.status = static_cast<SolveStatus>(s);
    r.mode = "cold";
    suite.replay.records.push_back(r);
  }
  ReplayRecord sweep = suite.replay.records.front();
  sweep.status = SolveStatus::kSolved;
  suite.replay.sweep.push_back(sweep);
  suite.problems = kLastStatus + 1;
  results.suites.push_back(suite);
  return results;
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

fs::path Written(const BenchResults& results, const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / name;
  fs::remove_all(dir);
  WriteBenchResults(results, dir.string(), nlohmann::json::object());
  return dir;
}

TEST(ResultsIo, EveryStatusReadsBackByItsName) {
  const fs::path dir = Written(EveryStatus(), "results-io-statuses");
  const std::string text = ReadText(dir / "results.json");
  const BenchResults back = ReadBenchResults(dir.string());
  ASSERT_EQ(back.suites.size(), 1u);
  ASSERT_EQ(back.suites[0].replay.records.size(), static_cast<std::size_t>(kLastStatus + 1));
  for (int s = 0; s <= kLastStatus; ++s) {
    const SolveStatus status = static_cast<SolveStatus>(s);
    EXPECT_EQ(back.suites[0].replay.records[s].status, status) << ToString(status);
    // Stored as the name, never as the number.
    EXPECT_NE(text.find("\"status\": \"" + std::string(ToString(status)) + "\""), std::string::npos)
        << ToString(status);
  }
}

// Replaces the first occurrence of `from` after `after` in the results.json of dir; returns the offset of `to`.
std::size_t Edit(const fs::path& dir, const std::string& after, const std::string& from, const std::string& to) {
  std::string text = ReadText(dir / "results.json");
  const std::size_t at = text.find(from, text.find(after));
  EXPECT_NE(at, std::string::npos);
  text.replace(at, from.size(), to);
  std::ofstream(dir / "results.json") << text;
  return at;
}

// "line:column" of an offset, counted here independently of the reader.
std::string Where(const std::string& text, std::size_t offset) {
  const std::string before = text.substr(0, offset);
  const std::size_t line_start = before.rfind('\n');
  const std::size_t column = line_start == std::string::npos ? offset + 1 : offset - line_start;
  return std::to_string(std::count(before.begin(), before.end(), '\n') + 1) + ":" + std::to_string(column);
}

TEST(ResultsIo, AnUnknownStatusNamesTheFileLineAndColumn) {
  for (const char* list : {"\"records\"", "\"sweep\""}) {
    SCOPED_TRACE(list);
    const fs::path dir = Written(EveryStatus(), "results-io-unknown");
    // The third record's status in the records list, or the sweep's only one.
    const std::string after = std::string(list) == "\"records\"" ? "\"p2\"" : "\"sweep\"";
    const std::size_t at = Edit(dir, after, "\"status\": \"", "\"status\": \"sovled_");
    const std::string text = ReadText(dir / "results.json");
    const std::size_t value = at + std::string("\"status\": ").size();
    ASSERT_EQ(text.substr(value, 8), "\"sovled_");
    try {
      ReadBenchResults(dir.string());
      FAIL() << "an unknown status was read";
    } catch (const InvalidInputError& e) {
      const std::string expected = (dir / "results.json").string() + ":" + Where(text, value) + ": field 'status'";
      EXPECT_EQ(std::string(e.what()).substr(0, expected.size()), expected) << e.what();
      EXPECT_NE(std::string(e.what()).find("unknown status 'sovled_"), std::string::npos) << e.what();
    }
  }
}

TEST(ResultsIo, OtherKeysNamedStatusAreNotRecordStatuses) {
  // A "status" outside a record (the environment here) is not a SolveStatus: a malformed record elsewhere is
  // reported as such, without a position taken from the wrong key.
  const fs::path dir = fs::path(testing::TempDir()) / "results-io-environment";
  fs::remove_all(dir);
  WriteBenchResults(EveryStatus(), dir.string(), nlohmann::json{{"status", "whatever"}});
  EXPECT_EQ(ReadBenchResults(dir.string()).suites[0].replay.records.size(), static_cast<std::size_t>(kLastStatus + 1));
  Edit(dir, "\"p1\"", "\"iterations\": 0", "\"iterations\": \"zero\"");
  try {
    ReadBenchResults(dir.string());
    FAIL() << "a malformed record was read";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("malformed"), std::string::npos) << e.what();
  }
}

TEST(ResultsIo, OneRecordWithAnUnknownStatusNamesTheField) {
  nlohmann::json record = ReplayRecordToJson(EveryStatus().suites[0].replay.records[1]);
  EXPECT_EQ(ReplayRecordFromJson(record).status, SolveStatus::kSolved);
  record["status"] = "1";  // the number is not a name
  try {
    ReplayRecordFromJson(record);
    FAIL() << "a status number was read";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("field 'status': unknown status '1'"), std::string::npos) << e.what();
  }
}

TEST(ResultsIo, EveryVerdictReadsBackByItsNameAndAnUnknownOneNamesTheField) {
  nlohmann::json record = ReplayRecordToJson(EveryStatus().suites[0].replay.records[1]);
  for (const Verdict v : {Verdict::kSolved, Verdict::kCorrectlyRefused, Verdict::kFailed, Verdict::kWronglyClaimed,
                          Verdict::kInaccurate, Verdict::kWronglyRefused}) {
    record["verdict"] = std::string(ToString(v));
    EXPECT_EQ(ReplayRecordFromJson(record).verdict, v) << ToString(v);
    EXPECT_EQ(VerdictFromString(ToString(v)), v);
  }
  for (const char* text : {"3", "wrongly claimed", "?", ""}) {  // numbers, other spellings, ToString's "?"
    EXPECT_FALSE(VerdictFromString(text).has_value()) << text;
    record["verdict"] = text;
    try {
      ReplayRecordFromJson(record);
      ADD_FAILURE() << "verdict '" << text << "' was read";
    } catch (const InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find("field 'verdict': unknown verdict '" + std::string(text) + "'"),
                std::string::npos)
          << e.what();
    }
  }
}

// The run's options (budgets, --problem globs, ...) read back as written; results written before them have none.
TEST(ResultsIo, TheRunsOptionsReadBack) {
  BenchResults results = EveryStatus();
  results.options = {{"sequence_budget", 1.0}, {"problems", {"families/spd-*"}}};
  const BenchResults back = ReadBenchResults(Written(results, "options").string());
  EXPECT_EQ(back.options, results.options);
  nlohmann::json older = ToJson(EveryStatus(), nlohmann::json::object());
  EXPECT_FALSE(older.contains("options"));
  EXPECT_TRUE(BenchResultsFromJson(older).options.is_null());
}

// A suite's kind goes into results.json and the manifest and back; results and manifests written before it have
// none (read as empty, which the report takes as "find the section as before").
TEST(ResultsIo, ASuitesKindReadsBack) {
  BenchResults results = EveryStatus();
  ASSERT_FALSE(results.suites.empty());
  results.suites[0].kind = "mcp";
  const BenchResults back = ReadBenchResults(Written(results, "kind").string());
  EXPECT_EQ(back.suites[0].kind, "mcp");
  nlohmann::json older = ToJson(EveryStatus(), nlohmann::json::object());
  EXPECT_FALSE(older["suites"][0].contains("kind"));
  EXPECT_EQ(BenchResultsFromJson(older).suites[0].kind, "");
  RunManifest manifest;
  manifest.suites = {results.suites[0]};
  nlohmann::json m = RunManifestToJson(manifest);
  EXPECT_EQ(m["suites"][0]["kind"], "mcp");
  EXPECT_EQ(RunManifestFromJson(m, "manifest").suites[0].kind, "mcp");
  m["suites"][0].erase("kind");
  EXPECT_EQ(RunManifestFromJson(m, "manifest").suites[0].kind, "");
}

}  // namespace
}  // namespace smcbench
