#pragma once
// The bench's arithmetic on timings (docs/BENCH_RESULTS.md "How a configuration is measured"):
// the summary of one configuration's rounds, the run's noise figure, and the order in which a
// round visits its group's configurations.
#include <cstdint>
#include <vector>

namespace punctual {

struct RoundSummary {
    double median = 0.0;
    double iqr = 0.0;  // 75th minus 25th percentile
    double cv = 0.0;   // sample standard deviation / mean; 0 for fewer than two samples or a zero mean
};

// The q-quantile (0..1) of `samples` by linear interpolation between order statistics (the
// "type 7" rule of R and NumPy's default): position q (n - 1) in the sorted samples. 0 if empty.
double quantile(std::vector<double> samples, double q);

RoundSummary summarizeRounds(const std::vector<double>& samples);

// The median of `values` (the run's noise figure takes it over every configuration's CV).
double medianOf(const std::vector<double>& values);

// Whether a configuration's spread is too wide to plot as a point: its IQR over its median
// exceeds `limit`. A zero median with a zero IQR is not flagged.
bool exceedsSpreadLimit(const RoundSummary& summary, double limit);

// The order of `count` configurations in round `round` of group `group`: a permutation of
// 0 .. count - 1 drawn from `seed` (std::mt19937_64 and a Fisher-Yates shuffle written here, so
// the order is the same with every standard library).
std::vector<uint32_t> roundOrder(uint32_t count, uint64_t seed, uint32_t group, uint32_t round);

}  // namespace punctual
