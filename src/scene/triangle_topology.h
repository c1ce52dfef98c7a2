#pragma once
// glTF's other triangle topologies as the triangle lists the renderer draws. Each triangle keeps
// the winding the glTF 2.0 spec gives it ("Topology types" in 3.7.2.1), so front faces stay front
// faces and the vertex that starts a triangle is the one the spec names first:
//   strip: triangle i is (v[i], v[i+1], v[i+2]) for even i, (v[i], v[i+2], v[i+1]) for odd i;
//   fan:   triangle i is (v[i+1], v[i+2], v[0]).
// A triangle that repeats an index covers no pixel. Strips use such triangles to join runs (and
// to fix the parity of the next run), so there they are routine, and both conversions drop them
// rather than hand the rasterizer and the shadow passes triangles that draw nothing.
#include <cstdint>
#include <span>
#include <vector>

namespace punctual {

// Fewer than three indices give no triangle.
std::vector<uint32_t> triangleListFromStrip(std::span<const uint32_t> strip);
std::vector<uint32_t> triangleListFromFan(std::span<const uint32_t> fan);

}  // namespace punctual
