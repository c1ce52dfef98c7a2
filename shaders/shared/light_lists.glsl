// How the culling kernels write a light-grid cell: its mask words, or (--light-lists indices) a
// header word and a list of 16-bit indices in one compacted array (culling.h, "Index lists").
// GLSL only; include after gpu_types.h and culling.h. The kernel's specialization constant and
// the index array's binding are declared here, once for every kernel.

layout(constant_id = PUNCTUAL_SPEC_LIGHT_LIST_FORM) const uint LIGHT_LIST_FORM = PUNCTUAL_LIGHT_LIST_MASKS;
const bool INDEX_LISTS = LIGHT_LIST_FORM == PUNCTUAL_LIGHT_LIST_INDICES;

// The words the frame's lists have taken (cleared to 0 before the kernels run; the renderer reads it
// after a counting frame to size the array), then the lists.
layout(std430, set = 0, binding = PUNCTUAL_BINDING_LIGHT_INDICES) buffer LightIndexBlock {
    uint lightIndexWordsUsed;
    uint lightIndexWords[];
};

// The words of a list of `count` lights, taken with one atomic add: its start, PUNCTUAL_LIGHT_LIST_NONE
// for an empty list (none taken), or PUNCTUAL_LIGHT_LIST_OVERFLOW where it would pass the array's
// end (the words are counted all the same: the counter then says how many the frame needs).
uint claimLightList(uint count) {
    if (count == 0u) return PUNCTUAL_LIGHT_LIST_NONE;
    uint start = atomicAdd(lightIndexWordsUsed, lightListWords(count));
    return start + lightListWords(count) <= uint(lightIndexWords.length()) ? start : PUNCTUAL_LIGHT_LIST_OVERFLOW;
}

// Entry `entry` (1 .. count) of the list at `start` is `light`, and `before` is entry `entry` - 1
// (the count for the first light). Words are written whole, each once: an odd entry writes its
// word with the entry before it; an even one only when it is the list's last (its word's high half
// then stays 0).
void writeLightListEntry(uint start, uint entry, uint before, uint light, uint count) {
    if ((entry & 1u) != 0u) {
        lightIndexWords[start + entry / 2u] = lightListPair(before, light);
    } else if (entry == count) {
        lightIndexWords[start + entry / 2u] = light;
    }
}
