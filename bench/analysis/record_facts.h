// What every report table asks of a record: the instance it is timed on, whether it is correct, the backends in the
// order they appear, medians and maxima where NaN means "not defined", and the log-log slope of a growth fit.
#pragma once

#include <string>
#include <vector>

#include "bench/replay/results_io.h"

namespace smcbench {

// What a time is compared over: the problem, or for an MCP record the problem × start (each start is its own
// instance: the same backend may solve one start and fail another).
std::string InstanceOf(const ReplayRecord& record);

// Solved, or correctly refused.
bool IsCorrect(const ReplayRecord& record);

// The backends of records, in the order they first appear.
std::vector<std::string> SolversIn(const std::vector<ReplayRecord>& records);

// The median of sorted values (the upper middle one for an even count, as the report's other medians); NaN if empty.
double MedianOfSorted(const std::vector<double>& sorted);
// Median of the defined (non-NaN) values; NaN when there are none.
double MedianDefined(std::vector<double> values);
// The largest of a and b where NaN means "not defined" (so a defined value always wins).
double MaxDefined(double a, double b);

// Least-squares slope of log(y) against log(x); NaN for fewer than 2 points or equal x.
double LogLogSlope(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace smcbench
