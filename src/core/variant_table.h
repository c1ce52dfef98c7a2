#pragma once
// Tables of variants. Each kind of variant the renderer compares (light-list method, shadow
// filter, point-shadow layout, cascade blend) is one constexpr table with one entry per value;
// everything that lists the values (parsing, names, --help, error messages, the bench sweeps, the
// tests' loops) reads the table. What the shaders get of an entry is a GpuConstant (a value and
// the name of its define in shaders/shared): the entry's own value (point layouts, cascade
// blends), or the parameters it is made of (a method's light source and culling flags, a filter's
// kernel and size), so an entry that reuses parameters the shaders know needs no shader edit. A
// unit test checks that every GpuConstant a table uses has its explicit case in the shaders.
//
// An entry type has at least these members:
//   Enum value;               the C++ enum value, the entry's index in its table
//   const char* name;         the command-line name (also in stats, file names and results)
//   const char* description;  one line for --help
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace punctual {

// A value the shaders see (a specialization constant), with the name of its define in
// shaders/shared, which is what the shaders' cases compare against.
struct GpuConstant {
    uint32_t value;
    const char* name;
};

// PUNCTUAL_GPU_CONSTANT(PUNCTUAL_SHADOW_KERNEL_TENT) = {1u, "PUNCTUAL_SHADOW_KERNEL_TENT"}: the value
// and its name come from one token, so they cannot disagree.
#define PUNCTUAL_GPU_CONSTANT(constant) ::punctual::GpuConstant{constant, #constant}

// True when entry i has enum value i, so an enum value indexes its table.
template <typename Entry, size_t N>
constexpr bool valuesAreIndices(const std::array<Entry, N>& table) {
    for (size_t i = 0; i < N; ++i) {
        if (static_cast<uint32_t>(table[i].value) != i) return false;
    }
    return true;
}

// True when entry i has enum value i and GPU value i (the tables whose entries reach the shaders
// as themselves), so the shaders' values run 0 .. count - 1.
template <typename Entry, size_t N>
constexpr bool gpuValuesAreIndices(const std::array<Entry, N>& table) {
    for (size_t i = 0; i < N; ++i) {
        if (table[i].gpu.value != i) return false;
    }
    return valuesAreIndices(table);
}

// True when no two entries share a name (parsing takes the first match).
template <typename Entry, size_t N>
constexpr bool namesAreUnique(const std::array<Entry, N>& table) {
    for (size_t i = 0; i < N; ++i) {
        for (size_t j = i + 1; j < N; ++j) {
            if (std::string_view(table[i].name) == std::string_view(table[j].name)) return false;
        }
    }
    return true;
}

// Every enum value of the table, in table order.
template <typename Entry, size_t N>
constexpr auto variantValues(const std::array<Entry, N>& table) {
    std::array<decltype(Entry::value), N> values{};
    for (size_t i = 0; i < N; ++i) values[i] = table[i].value;
    return values;
}

// The entry of `value`, or nullptr for a value outside the table (a cast from a bad integer).
template <typename Entry, size_t N>
constexpr const Entry* findVariant(const std::array<Entry, N>& table, decltype(Entry::value) value) {
    for (const Entry& entry : table) {
        if (entry.value == value) return &entry;
    }
    return nullptr;
}

// The name of `value`'s entry; "unknown" for a value outside the table (a cast from a bad integer).
template <typename Entry, size_t N>
constexpr const char* variantName(const std::array<Entry, N>& table, decltype(Entry::value) value) {
    const Entry* entry = findVariant(table, value);
    return entry ? entry->name : "unknown";
}

// Every name, in table order.
template <typename Entry, size_t N>
std::vector<std::string> variantNames(const std::array<Entry, N>& table) {
    std::vector<std::string> names;
    for (const Entry& entry : table) names.emplace_back(entry.name);
    return names;
}

// "a, b, c or d" (`last` joins the last two).
inline std::string joinNames(const std::vector<std::string>& names, const std::string& last = " or ") {
    std::string text;
    for (size_t i = 0; i < names.size(); ++i) {
        if (i > 0) text += i + 1 == names.size() ? last : ", ";
        text += names[i];
    }
    return text;
}

// The entry named `name`. Throws Error(option, "expected a, b or c, got 'x'").
template <typename Entry, size_t N>
const Entry& parseVariant(const std::array<Entry, N>& table, const std::string& name, const std::string& option) {
    for (const Entry& entry : table) {
        if (name == entry.name) return entry;
    }
    throw Error(option, "expected " + joinNames(variantNames(table)) + ", got '" + name + "'");
}

// The --help lines listing every entry, one a line: `indent` spaces, the name padded to the
// longest, its description, and "(default)" after the default's.
template <typename Entry, size_t N>
std::string variantHelp(const std::array<Entry, N>& table, decltype(Entry::value) defaultValue, size_t indent) {
    size_t width = 0;
    for (const Entry& entry : table) width = std::max(width, std::string_view(entry.name).size());
    std::string text;
    for (const Entry& entry : table) {
        const std::string name = entry.name;
        text += std::string(indent, ' ') + name + std::string(width + 2 - name.size(), ' ') + entry.description;
        if (entry.value == defaultValue) text += " (default)";
        text += "\n";
    }
    return text;
}

}  // namespace punctual
