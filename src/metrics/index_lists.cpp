#include "metrics/index_lists.h"

#include <string>

#include "core/check.h"
#include "culling.h"

namespace punctual {

std::vector<uint32_t> masksFromIndexLists(std::span<const uint32_t> headers, std::span<const uint32_t> indexWords,
                                          uint32_t gridWords, uint32_t lightCount) {
    std::vector<uint32_t> masks(headers.size() * gridWords, 0u);
    for (size_t cell = 0; cell < headers.size(); ++cell) {
        const uint32_t start = headers[cell];
        if (start == PUNCTUAL_LIGHT_LIST_NONE) continue;
        const std::string where = "light list of cell " + std::to_string(cell);
        PUNCTUAL_CHECK(start != PUNCTUAL_LIGHT_LIST_OVERFLOW, where + " did not fit the index array");
        PUNCTUAL_CHECK(start < indexWords.size(), where + " starts past the index array");
        const uint32_t count = gpu::lightListEntry(indexWords[start], 0u);
        PUNCTUAL_CHECK(count > 0 && start + gpu::lightListWords(count) <= indexWords.size(),
                       where + " is empty or runs past the index array");
        uint32_t previous = 0;
        for (uint32_t entry = 1; entry <= count; ++entry) {
            const uint32_t light = gpu::lightListEntry(indexWords[start + entry / 2], entry);
            PUNCTUAL_CHECK(light < lightCount && (entry == 1 || light > previous),
                           where + " holds a light out of range or out of order");
            masks[cell * gridWords + gpu::lightGridWord(light)] |= 1u << gpu::lightGridBit(light);
            previous = light;
        }
    }
    return masks;
}

}  // namespace punctual
