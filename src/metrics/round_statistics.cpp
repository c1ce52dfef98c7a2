#include "metrics/round_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace punctual {

double quantile(std::vector<double> samples, double q) {
    if (samples.empty()) return 0.0;
    std::sort(samples.begin(), samples.end());
    const double position = std::clamp(q, 0.0, 1.0) * double(samples.size() - 1);
    const size_t below = size_t(std::floor(position));
    const size_t above = std::min(below + 1, samples.size() - 1);
    const double fraction = position - double(below);
    return samples[below] + (samples[above] - samples[below]) * fraction;
}

RoundSummary summarizeRounds(const std::vector<double>& samples) {
    RoundSummary summary;
    if (samples.empty()) return summary;
    summary.median = quantile(samples, 0.5);
    summary.iqr = quantile(samples, 0.75) - quantile(samples, 0.25);
    if (samples.size() >= 2) {
        double mean = 0.0;
        for (double s : samples) mean += s;
        mean /= double(samples.size());
        double squares = 0.0;
        for (double s : samples) squares += (s - mean) * (s - mean);
        const double deviation = std::sqrt(squares / double(samples.size() - 1));
        summary.cv = mean > 0.0 ? deviation / mean : 0.0;
    }
    return summary;
}

double medianOf(const std::vector<double>& values) { return quantile(values, 0.5); }

bool exceedsSpreadLimit(const RoundSummary& summary, double limit) {
    if (summary.iqr <= 0.0) return false;
    return !(summary.iqr <= limit * summary.median);
}

std::vector<uint32_t> roundOrder(uint32_t count, uint64_t seed, uint32_t group, uint32_t round) {
    std::vector<uint32_t> order(count);
    for (uint32_t i = 0; i < count; ++i) order[i] = i;
    // One stream per (seed, group, round): a round's order does not depend on how many rounds or
    // groups came before it.
    std::seed_seq seq{uint32_t(seed), uint32_t(seed >> 32), group, round};
    std::mt19937_64 engine(seq);
    for (uint32_t i = count; i > 1; --i) {
        // Unbiased draw in [0, i): rejection of the top partial block of 2^64.
        const uint64_t limit = std::numeric_limits<uint64_t>::max() - std::numeric_limits<uint64_t>::max() % i;
        uint64_t draw = engine();
        while (draw >= limit) draw = engine();
        std::swap(order[i - 1], order[size_t(draw % i)]);
    }
    return order;
}

}  // namespace punctual
