#pragma once
// Reading back the culling kernels' index lists (--light-lists indices; culling.h, "Index lists")
// as the masks the other form writes, so that every test, statistic and study that reads a light
// grid reads both forms the same way.
#include <cstdint>
#include <span>
#include <vector>

namespace punctual {

// The masks (`gridWords` words a cell, culling.h's lightGridWord) of the cells whose headers are
// `headers`, from `indexWords`, the index array after its words-used counter. A cell whose header
// says "no lights" gets zero masks. Throws InternalError naming the cell for a list that did not
// fit the array, runs past it, or holds a light at or past `lightCount` or out of ascending order:
// a kernel's bug, which no image test might notice.
std::vector<uint32_t> masksFromIndexLists(std::span<const uint32_t> headers, std::span<const uint32_t> indexWords,
                                          uint32_t gridWords, uint32_t lightCount);

}  // namespace punctual
