#include "bench/perf/perf_record.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "solvers/core/duration_text.h"
#include "solvers/core/problem.h"

namespace smcbench {
namespace {

using json = nlohmann::json;
constexpr const char* kFormat = "smcbench-perf/1";
// The environment fields that change instruction counts: a baseline made with other values is not comparable.
constexpr const char* kComparableFields[] = {"compiler", "cxx_flags", "build_type", "assertions", "libraries"};

// JSON has no NaN: "not measured" is stored as null and read back as −1.
json Measured(double value) { return value >= 0.0 && std::isfinite(value) ? json(value) : json(nullptr); }
double MeasuredFrom(const json& j, const char* key) {
  const auto it = j.find(key);
  return it == j.end() || it->is_null() ? -1.0 : it->get<double>();
}

std::string Number(double value, const char* format) {
  if (value < 0.0) return "-";
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::string Nanoseconds(double value) { return DurationText(value * 1e-9); }

std::string EnvironmentText(const json& env, const char* key) {
  const auto it = env.find(key);
  return it == env.end() ? std::string("(absent)") : it->dump();
}

}  // namespace

// Instruction counts span 10² (a tiny solve) to 10⁸ (Ipopt).
std::string FormatInstructions(double value) {
  if (value < 0.0) return "-";
  if (value >= 1e6) return Number(value / 1e6, "%.2f M");
  if (value >= 1e4) return Number(value / 1e3, "%.1f k");
  return Number(value, "%.0f");
}

const PerfFigure* PerfRun::Find(const std::string& id) const {
  for (const PerfFigure& f : figures) {
    if (f.id == id) return &f;
  }
  return nullptr;
}

json ToJson(const PerfRun& run) {
  json j;
  j["format"] = kFormat;
  j["environment"] = run.environment;
  j["figures"] = json::array();
  for (const PerfFigure& f : run.figures) {
    j["figures"].push_back({{"id", f.id},
                            {"unit", f.unit},
                            {"units", f.units},
                            {"status", f.status},
                            {"instructions", Measured(f.instructions)},
                            {"ns", Measured(f.ns)},
                            {"ns_min", Measured(f.ns_min)},
                            {"ns_max", Measured(f.ns_max)}});
  }
  return j;
}

PerfRun PerfRunFromJson(const json& document) {
  try {
    if (document.at("format").get<std::string>() != kFormat) {
      throw InvalidInputError("perf record: format is " + document.at("format").dump() + ", expected \"" +
                              kFormat + "\"");
    }
    PerfRun run;
    run.environment = document.value("environment", json::object());
    for (const json& f : document.at("figures")) {
      PerfFigure figure;
      figure.id = f.at("id").get<std::string>();
      figure.unit = f.at("unit").get<std::string>();
      figure.units = f.at("units").get<std::int64_t>();
      figure.status = f.at("status").get<std::string>();
      figure.instructions = MeasuredFrom(f, "instructions");
      figure.ns = MeasuredFrom(f, "ns");
      figure.ns_min = MeasuredFrom(f, "ns_min");
      figure.ns_max = MeasuredFrom(f, "ns_max");
      if (figure.id.empty()) throw InvalidInputError("perf record: a figure has an empty id");
      if (run.Find(figure.id)) throw InvalidInputError("perf record: figure '" + figure.id + "' appears twice");
      run.figures.push_back(std::move(figure));
    }
    return run;
  } catch (const json::exception& e) {
    throw InvalidInputError(std::string("perf record: malformed (") + e.what() + ")");
  }
}

PerfRun ReadPerfRun(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InvalidInputError("cannot read perf record '" + path + "'");
  json document;
  try {
    in >> document;
  } catch (const json::exception& e) {
    throw InvalidInputError("perf record '" + path + "' is not JSON (" + e.what() + ")");
  }
  try {
    return PerfRunFromJson(document);
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(path + ": " + e.what());
  }
}

void WritePerfRun(const PerfRun& run, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  std::ofstream out(path);
  out << ToJson(run).dump(1) << "\n";
  if (!out) throw InvalidInputError("cannot write perf record '" + path + "'");
}

PerfRun MergePerfRuns(const PerfRun& instructions_run, const PerfRun& wallclock_run) {
  PerfRun merged = instructions_run;
  for (PerfFigure& f : merged.figures) {
    if (const PerfFigure* w = wallclock_run.Find(f.id)) {
      f.ns = w->ns;
      f.ns_min = w->ns_min;
      f.ns_max = w->ns_max;
    }
  }
  return merged;
}

const char* ToString(PerfVerdict verdict) {
  switch (verdict) {
    case PerfVerdict::kSame: return "same";
    case PerfVerdict::kRegressed: return "REGRESSED";
    case PerfVerdict::kImproved: return "improved";
    case PerfVerdict::kStatusChanged: return "STATUS CHANGED";
    case PerfVerdict::kMissing: return "MISSING";
    case PerfVerdict::kNew: return "new";
  }
  return "?";
}

bool PerfComparison::failed() const {
  return !incomparable.empty() || count(PerfVerdict::kRegressed) > 0 || count(PerfVerdict::kStatusChanged) > 0 ||
         count(PerfVerdict::kMissing) > 0;
}

int PerfComparison::count(PerfVerdict verdict) const {
  int n = 0;
  for (const PerfRow& r : rows) n += r.verdict == verdict;
  return n;
}

PerfComparison ComparePerfRuns(const PerfRun& baseline, const PerfRun& current, double threshold) {
  if (!(threshold > 0.0 && threshold < 1.0)) {
    throw InvalidInputError("perf threshold must lie in (0, 1), got " + std::to_string(threshold));
  }
  PerfComparison c;
  c.threshold = threshold;
  for (const char* key : kComparableFields) {
    const std::string was = EnvironmentText(baseline.environment, key), now = EnvironmentText(current.environment, key);
    if (was != now) c.incomparable.push_back(std::string(key) + ": baseline " + was + ", now " + now);
  }
  for (const PerfFigure& b : baseline.figures) {
    PerfRow row;
    row.id = b.id;
    row.baseline_instructions = b.instructions;
    row.baseline_ns = b.ns;
    const PerfFigure* now = current.Find(b.id);
    if (!now) {
      row.verdict = PerfVerdict::kMissing;
    } else {
      row.instructions = now->instructions;
      row.ns = now->ns;
      if (now->status != b.status) {
        row.verdict = PerfVerdict::kStatusChanged;
      } else if (b.instructions > 0.0 && now->instructions >= 0.0) {
        row.ratio = now->instructions / b.instructions;
        row.verdict = row.ratio > 1.0 + threshold   ? PerfVerdict::kRegressed
                      : row.ratio < 1.0 - threshold ? PerfVerdict::kImproved
                                                    : PerfVerdict::kSame;
      } else if (b.instructions > 0.0) {
        row.verdict = PerfVerdict::kMissing;  // the baseline tracks it; this run has no count for it
      }
    }
    c.rows.push_back(row);
  }
  for (const PerfFigure& f : current.figures) {
    if (baseline.Find(f.id)) continue;
    PerfRow row;
    row.id = f.id;
    row.instructions = f.instructions;
    row.ns = f.ns;
    row.verdict = PerfVerdict::kNew;
    c.rows.push_back(row);
  }
  return c;
}

std::string FormatComparison(const PerfComparison& c) {
  std::ostringstream s;
  const int regressed = c.count(PerfVerdict::kRegressed), improved = c.count(PerfVerdict::kImproved);
  const int changed = c.count(PerfVerdict::kStatusChanged), missing = c.count(PerfVerdict::kMissing);
  s << (c.failed() ? "**perf gate: FAIL**" : "**perf gate: pass**") << " — " << c.rows.size() << " figures, "
    << regressed << " regressed by more than " << Number(100.0 * c.threshold, "%g") << " %, " << changed
    << " changed status, " << missing << " missing, " << improved << " improved, " << c.count(PerfVerdict::kNew)
    << " new (instructions per unit, callgrind; wall-clock is information only)\n\n";
  for (const std::string& why : c.incomparable) s << "- not comparable: " << why << "\n";
  if (!c.incomparable.empty()) {
    s << "- the baseline was made by another build; if the change is intended, run tools/perf-update\n\n";
  }
  s << "| figure | baseline | now | ratio | verdict | wall-clock baseline | now |\n";
  s << "|---|---:|---:|---:|---|---:|---:|\n";
  for (const PerfRow& r : c.rows) {
    s << "| " << r.id << " | " << FormatInstructions(r.baseline_instructions) << " | "
      << FormatInstructions(r.instructions) << " | " << Number(r.ratio, "%.3f") << " | " << ToString(r.verdict)
      << " | " << Nanoseconds(r.baseline_ns) << " | " << Nanoseconds(r.ns) << " |\n";
  }
  if (improved > 0 && !c.failed()) {
    s << "\nSome figures improved beyond the threshold: run tools/perf-update (in its own commit) to lock them in.\n";
  }
  return s.str();
}

void AppendPerfHistory(const std::string& path, const PerfRun& current, const PerfComparison& comparison) {
  namespace fs = std::filesystem;
  const bool fresh = !fs::exists(path) || fs::file_size(path) == 0;
  if (fs::path(path).has_parent_path()) fs::create_directories(fs::path(path).parent_path());
  std::ofstream out(path, std::ios::app);
  if (!out) throw InvalidInputError("cannot append to perf history '" + path + "'");
  if (fresh) out << "date,git_sha,id,unit,instructions,baseline_instructions,ratio,ns\n";
  const std::string date = current.environment.value("date", std::string());
  const std::string sha = current.environment.value("git_sha", std::string());
  std::map<std::string, const PerfRow*> rows;
  for (const PerfRow& r : comparison.rows) rows[r.id] = &r;
  for (const PerfFigure& f : current.figures) {
    const auto it = rows.find(f.id);
    const double base = it == rows.end() ? -1.0 : it->second->baseline_instructions;
    const double ratio = it == rows.end() ? -1.0 : it->second->ratio;
    // Ids never hold commas (they are paths of names); numbers at full precision.
    out << date << "," << sha << "," << f.id << "," << f.unit << "," << Number(f.instructions, "%.17g") << ","
        << Number(base, "%.17g") << "," << Number(ratio, "%.17g") << "," << Number(f.ns, "%.17g") << "\n";
  }
  if (!out) throw InvalidInputError("cannot append to perf history '" + path + "'");
}

std::vector<PerfHistoryRow> ReadPerfHistory(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InvalidInputError("cannot read perf history '" + path + "'");
  std::vector<PerfHistoryRow> rows;
  std::string line;
  int number = 0;
  const auto value = [&](const std::string& field) {
    if (field == "-" || field.empty()) return -1.0;
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != field.size()) {
      throw InvalidInputError(path + ":" + std::to_string(number) + ": '" + field + "' is not a number");
    }
    return v;
  };
  while (std::getline(in, line)) {
    ++number;
    if (number == 1 && line.rfind("date,", 0) == 0) continue;
    if (line.empty()) continue;
    std::vector<std::string> fields;
    std::stringstream ss(line);
    for (std::string field; std::getline(ss, field, ',');) fields.push_back(field);
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    if (fields.size() != 8) {
      throw InvalidInputError(path + ":" + std::to_string(number) + ": expected 8 fields, got " +
                              std::to_string(fields.size()));
    }
    PerfHistoryRow r;
    r.date = fields[0];
    r.git_sha = fields[1];
    r.id = fields[2];
    r.unit = fields[3];
    r.instructions = value(fields[4]);
    r.baseline_instructions = value(fields[5]);
    r.ratio = value(fields[6]);
    r.ns = value(fields[7]);
    rows.push_back(std::move(r));
  }
  return rows;
}

}  // namespace smcbench
