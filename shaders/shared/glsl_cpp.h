// One dialect for code shared by GLSL and C++.
//
// Files in shaders/shared are included by the shaders (glslang, GL_GOOGLE_include_directive) and
// by the C++ code, so that struct layouts, limits and the shading math exist exactly once. This
// prelude maps the few differences: in C++ the GLSL vector types are GLM's, `uint` is uint32_t,
// and functions need `inline`. Shared code must stay inside the common subset: no `inout`, no
// swizzle assignment, float literals with an `f` suffix (valid GLSL 4.x, and float in C++, so GLM
// never mixes float and double).
#ifndef PUNCTUAL_GLSL_CPP_H
#define PUNCTUAL_GLSL_CPP_H

#ifdef __cplusplus
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#define PUNCTUAL_NAMESPACE_BEGIN namespace punctual::gpu { using namespace glm; using uint = std::uint32_t;
#define PUNCTUAL_NAMESPACE_END }
#define PUNCTUAL_FN inline
// Integer-only helpers the C++ tables evaluate at compile time (a filter's taps from its size).
#define PUNCTUAL_CONSTEXPR_FN constexpr
#else
#define PUNCTUAL_NAMESPACE_BEGIN
#define PUNCTUAL_NAMESPACE_END
#define PUNCTUAL_FN
#define PUNCTUAL_CONSTEXPR_FN
#endif

#endif
