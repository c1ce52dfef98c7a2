#include "scene/keyframes.h"

#include <algorithm>
#include <cmath>

namespace punctual {
namespace {

using Value = std::vector<double>;

// Keyframe k's value (for CUBICSPLINE: its middle element of a, v, b); `part` 0, 1, 2 picks the
// in-tangent, the value or the out-tangent of a spline.
Value keyframe(const KeyframeTrack& track, size_t k, size_t part = 1) {
    const bool spline = track.interpolation == Interpolation::CubicSpline;
    const size_t first = (spline ? 3 * k + part : k) * track.components;
    return Value(track.values.begin() + std::ptrdiff_t(first), track.values.begin() + std::ptrdiff_t(first + track.components));
}

double dot(const Value& a, const Value& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) sum += a[i] * b[i];
    return sum;
}

Value normalised(Value v) {
    const double length = std::sqrt(dot(v, v));
    for (double& x : v) x /= length;
    return v;
}

// Spherical linear interpolation of unit quaternions along the shorter arc (glTF Appendix C):
// with cos(theta) = a.b (b negated first where that is negative, q and -q being one rotation),
// slerp = sin((1 - s) theta) / sin(theta) a + sin(s theta) / sin(theta) b. Where the two are
// nearly one rotation, sin(theta) -> 0 and the ratio loses its digits; the chord's normalised
// lerp agrees with the arc there to far below float precision (the arc and chord differ by
// O(theta^2) relative).
Value slerp(const Value& a, Value b, double s) {
    double cosine = dot(a, b);
    if (cosine < 0.0) {
        for (double& x : b) x = -x;
        cosine = -cosine;
    }
    Value result(a.size());
    if (cosine > 1.0 - 1e-10) {
        for (size_t i = 0; i < a.size(); ++i) result[i] = (1.0 - s) * a[i] + s * b[i];
        return normalised(result);
    }
    const double theta = std::acos(cosine);
    const double wa = std::sin((1.0 - s) * theta) / std::sin(theta);
    const double wb = std::sin(s * theta) / std::sin(theta);
    for (size_t i = 0; i < a.size(); ++i) result[i] = wa * a[i] + wb * b[i];
    return result;
}

Value hermite(const KeyframeTrack& track, size_t k, double s, double interval) {
    const Value v0 = keyframe(track, k, 1);
    const Value b0 = keyframe(track, k, 2);
    const Value v1 = keyframe(track, k + 1, 1);
    const Value a1 = keyframe(track, k + 1, 0);
    const double s2 = s * s;
    const double s3 = s2 * s;
    Value result(v0.size());
    for (size_t i = 0; i < v0.size(); ++i) {
        result[i] = (2.0 * s3 - 3.0 * s2 + 1.0) * v0[i] + interval * (s3 - 2.0 * s2 + s) * b0[i] +
                    (-2.0 * s3 + 3.0 * s2) * v1[i] + interval * (s3 - s2) * a1[i];
    }
    return track.rotation ? normalised(result) : result;
}

std::vector<float> rounded(const Value& v) {
    std::vector<float> result(v.size());
    for (size_t i = 0; i < v.size(); ++i) result[i] = float(v[i]);
    return result;
}

bool finite(const std::vector<float>& values) {
    return std::all_of(values.begin(), values.end(), [](float x) { return std::isfinite(x); });
}

}  // namespace

const char* interpolationName(Interpolation interpolation) {
    switch (interpolation) {
        case Interpolation::Step: return "STEP";
        case Interpolation::Linear: return "LINEAR";
        case Interpolation::CubicSpline: return "CUBICSPLINE";
    }
    return "?";
}

std::string trackProblem(const KeyframeTrack& track) {
    if (track.times.empty()) return "has no keyframes";
    if (!finite(track.times)) return "has a keyframe time that is not finite";
    if (track.times.front() < 0.0f) return "has a negative keyframe time";
    for (size_t k = 1; k < track.times.size(); ++k) {
        if (!(track.times[k] > track.times[k - 1])) return "has keyframe times that are not strictly increasing";
    }
    if (track.values.size() != track.expectedValueCount()) {
        return "has " + std::to_string(track.values.size()) + " output numbers where " + std::to_string(track.times.size()) +
               " " + interpolationName(track.interpolation) + " keyframes need " + std::to_string(track.expectedValueCount());
    }
    if (!finite(track.values)) return "has an output value that is not finite";
    if (track.rotation) {
        for (size_t k = 0; k < track.times.size(); ++k) {
            const Value q = keyframe(track, k);
            if (!(dot(q, q) > 1e-12)) return "has a zero rotation quaternion at keyframe " + std::to_string(k);
        }
    }
    return "";
}

std::vector<float> sampleTrack(const KeyframeTrack& track, double time) {
    const std::vector<float>& times = track.times;
    const auto fixed = [&](size_t k) {
        const Value v = keyframe(track, k);
        return rounded(track.rotation ? normalised(v) : v);
    };
    if (!(time > double(times.front()))) return fixed(0);
    if (time >= double(times.back())) return fixed(times.size() - 1);
    // The last keyframe at or before `time`: times[k] <= time < times[k + 1].
    const size_t k = size_t(std::upper_bound(times.begin(), times.end(), time,
                                             [](double t, float key) { return t < double(key); }) -
                            times.begin()) - 1;
    const double interval = double(times[k + 1]) - double(times[k]);
    const double s = (time - double(times[k])) / interval;
    switch (track.interpolation) {
        case Interpolation::Step: return fixed(k);
        case Interpolation::Linear: {
            const Value a = keyframe(track, k);
            const Value b = keyframe(track, k + 1);
            if (track.rotation) return rounded(slerp(normalised(a), normalised(b), s));
            Value result(a.size());
            for (size_t i = 0; i < a.size(); ++i) result[i] = (1.0 - s) * a[i] + s * b[i];
            return rounded(result);
        }
        case Interpolation::CubicSpline: return rounded(hermite(track, k, s, interval));
    }
    return fixed(k);
}

}  // namespace punctual
