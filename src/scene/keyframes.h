#pragma once
// Keyframe tracks and their interpolation, as glTF 2.0 animation samplers define them (section
// 3.11, "Animations", and Appendix C, "Interpolation"): a track holds strictly increasing times
// and, per time, one value of `components` numbers (three for CUBICSPLINE: in-tangent, value,
// out-tangent). Sampling at time t finds the keyframes k, k + 1 with t_k <= t < t_k+1 and
// s = (t - t_k) / (t_k+1 - t_k), then
//   STEP         v_k;
//   LINEAR       (1 - s) v_k + s v_k+1, or for a rotation the spherical interpolation slerp(v_k,
//                v_k+1, s) along the shorter arc;
//   CUBICSPLINE  the cubic Hermite spline with tangents scaled by the interval,
//                  (2s^3 - 3s^2 + 1) v_k + td (s^3 - 2s^2 + s) b_k + (-2s^3 + 3s^2) v_k+1
//                  + td (s^3 - s^2) a_k+1,
//                td = t_k+1 - t_k, b_k the out-tangent of k and a_k+1 the in-tangent of k + 1;
//                a rotation is normalised afterwards.
// Before the first time a track holds its first value, after the last its last. The arithmetic
// is done in double and rounded to float once at the end, so a value interpolated here equals
// the same formula evaluated by hand in double and rounded (the still-frame test's oracle), on
// any platform whose libm is accurate to an ulp of double.
#include <cstdint>
#include <string>
#include <vector>

namespace punctual {

enum class Interpolation : uint8_t { Step, Linear, CubicSpline };

// "STEP", "LINEAR", "CUBICSPLINE" (glTF's names).
const char* interpolationName(Interpolation interpolation);

struct KeyframeTrack {
    Interpolation interpolation = Interpolation::Linear;
    uint32_t components = 1;    // numbers per value: 3 (translation, scale), 4 (rotation), morph targets (weights)
    bool rotation = false;      // unit quaternions x, y, z, w: slerp, and normalised after a spline
    std::vector<float> times;   // seconds, strictly increasing
    std::vector<float> values;  // times.size() x components, x 3 for CUBICSPLINE (a, v, b per keyframe)

    // The values' count a track of `times` keyframes must hold.
    size_t expectedValueCount() const {
        return times.size() * components * (interpolation == Interpolation::CubicSpline ? 3u : 1u);
    }
};

// What is wrong with `track` (times not strictly increasing, or negative, or not finite; values
// not finite or of the wrong count; a rotation keyframe of zero length), or "" where nothing is.
std::string trackProblem(const KeyframeTrack& track);

// The track's value at `time` seconds (components numbers). The track must be valid
// (trackProblem empty) and hold at least one keyframe.
std::vector<float> sampleTrack(const KeyframeTrack& track, double time);

}  // namespace punctual
