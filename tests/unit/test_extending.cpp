// docs/EXTENDING.md promises how many files an addition takes: a shadow filter three (its table
// row, its shader case, its test), a grid method with no data of its own at most four (its table
// row, its culling flag's case in the general kernel, its math, its test). This test holds those
// counts against the code as it is: every existing variant of those kinds is counted as if it had
// been added last, by the files that name it.
//
// A file names a variant when it holds its enum identifier (ShadowFilter::Tent7), its quoted
// command-line name ("tent7"), or a shader constant only it uses (a kernel define only its row
// uses, a culling flag only it sets). Counted: the code (src, shaders, tests, scripts, cmake,
// CMakeLists.txt). Not counted:
//  - a variant the program itself singles out, named in src/ outside its table file (a default,
//    the reference, a study's baseline): those names are the singling out, not the addition;
//  - the one-subgroup culling kernels (tile_culling.comp, cluster_culling.comp and their
//    subgroup_tiles.glsl): a flag's case there is a speed-up, and a method whose flag they lack
//    culls with the general kernel (Culling.AFlagTheSubgroupKernelsLackKeepsAMethodOnTheGeneralKernel);
//  - docs, bench records and the chart scripts' tests in bench/ (the charts take names from results);
//    the README's synopsis, which scripts/readme-synopsis.sh rewrites from `punctual render --help`.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "lights/shadow_filters.h"
#include "render/light_list_method.h"

namespace punctual {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = fs::path(PUNCTUAL_SHADER_DIR).parent_path();

std::string readText(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

// The code files, by their path from the repository root, with their text.
std::map<std::string, std::string> codeFiles() {
    static const std::set<std::string> kExtensions = {".h", ".cpp", ".glsl", ".comp", ".frag", ".vert", ".sh", ".cmake", ".txt"};
    static const std::set<std::string> kNotCounted = {"shaders/compute/tile_culling.comp",
                                                     "shaders/compute/cluster_culling.comp",
                                                     "shaders/shared/subgroup_tiles.glsl",
                                                     "tests/unit/test_extending.cpp"};  // its examples
    std::map<std::string, std::string> files;
    for (const char* folder : {"src", "shaders", "tests", "scripts", "cmake"}) {
        for (const fs::directory_entry& entry : fs::recursive_directory_iterator(kRoot / folder)) {
            const std::string relative = fs::relative(entry.path(), kRoot).generic_string();
            if (!entry.is_regular_file() || !kExtensions.contains(entry.path().extension().string())) continue;
            if (relative.starts_with("tests/fuzz/corpus") || relative.starts_with("tests/fuzz/regressions")) continue;
            if (kNotCounted.contains(relative)) continue;
            files[relative] = readText(entry.path());
        }
    }
    files["CMakeLists.txt"] = readText(kRoot / "CMakeLists.txt");
    return files;
}

// The enumerators of `enum class <name> : uint32_t { A, B, ... };` in `header`, in order: the
// table's entry i has enum value i (valuesAreIndices), so enumerator i names entry i.
std::vector<std::string> enumerators(const std::string& header, const std::string& name) {
    const std::string source = readText(kRoot / header);
    std::smatch match;
    EXPECT_TRUE(std::regex_search(source, match, std::regex("enum class " + name + " : uint32_t \\{([^}]*)\\}")))
        << header;
    std::vector<std::string> names;
    const std::string body = match[1].str();
    const std::regex word("\\w+");
    for (auto it = std::sregex_iterator(body.begin(), body.end(), word); it != std::sregex_iterator(); ++it) {
        names.push_back(name + "::" + it->str());
    }
    return names;
}

struct Variant {
    std::string name;                   // its command-line name
    std::vector<std::string> tokens;    // what names it in code
};

std::vector<std::string> filesNaming(const std::map<std::string, std::string>& files, const std::vector<std::string>& tokens) {
    // Whole identifiers only: ShadowFilter::Tent is not ShadowFilter::Tent5. Compiled once a call.
    std::vector<std::regex> wholeTokens;
    for (const std::string& token : tokens) {
        wholeTokens.emplace_back("(^|[^\\w])" + std::regex_replace(token, std::regex("[.]"), "\\.") + "($|[^\\w])");
    }
    std::vector<std::string> naming;
    for (const auto& [path, text] : files) {
        const bool names = std::any_of(wholeTokens.begin(), wholeTokens.end(),
                                       [&](const std::regex& whole) { return std::regex_search(text, whole); });
        if (names) naming.push_back(path);
    }
    return naming;
}

// The number EXTENDING.md gives in `section` (a "## " heading) before `phrase`: "Three files" -> 3.
size_t promisedFiles(const std::string& section, const std::string& phrase) {
    const std::string doc = readText(kRoot / "docs/EXTENDING.md");
    const size_t start = doc.find("\n## " + section + "\n");
    EXPECT_NE(start, std::string::npos) << section;
    const size_t end = doc.find("\n## ", start + 1);
    const std::string text = doc.substr(start, end - start);
    static const std::map<std::string, size_t> kNumbers = {{"two", 2}, {"three", 3}, {"four", 4}, {"five", 5}};
    std::smatch match;
    const std::regex promise("(\\w+) " + phrase, std::regex::icase);
    EXPECT_TRUE(std::regex_search(text, match, promise)) << section << ": no '<number> " << phrase << "'";
    std::string word = match[1].str();
    for (char& c : word) c = char(std::tolower(c));
    EXPECT_TRUE(kNumbers.contains(word)) << word;
    return kNumbers.contains(word) ? kNumbers.at(word) : 0;
}

// Checks each variant that is an addition of this kind (and not singled out) against `promised`
// files; returns how many were checked.
size_t expectEachAdditionWithin(const std::vector<Variant>& variants, const std::string& tableFile, size_t promised) {
    const std::map<std::string, std::string> files = codeFiles();
    size_t checked = 0;
    for (const Variant& variant : variants) {
        const std::vector<std::string> naming = filesNaming(files, variant.tokens);
        bool singledOut = false;
        for (const std::string& path : filesNaming(files, {variant.tokens[0], variant.tokens[1]})) {
            singledOut = singledOut || (path.starts_with("src/") && path != tableFile);
        }
        std::string list;
        for (const std::string& path : naming) list += "\n  " + path;
        if (singledOut) {
            std::printf("[ extending] %s: singled out by the program, not counted (%zu files)\n", variant.name.c_str(),
                        naming.size());
            continue;
        }
        ++checked;
        std::printf("[ extending] %s: %zu files (promised at most %zu)%s\n", variant.name.c_str(), naming.size(),
                    promised, list.c_str());
        EXPECT_LE(naming.size(), promised) << variant.name << " is named in:" << list;
        EXPECT_NE(std::find(naming.begin(), naming.end(), tableFile), naming.end()) << variant.name;
    }
    return checked;
}

TEST(Extending, AShadowFilterTakesTheFilesExtendingMdNames) {
    const size_t promised = promisedFiles("A shadow filter", "files");
    EXPECT_EQ(promised, 3u);  // the target: table row, shader case, test
    const std::vector<std::string> enums = enumerators("src/lights/shadow_filters.h", "ShadowFilter");
    ASSERT_EQ(enums.size(), kShadowFilters.size());
    std::map<std::string, size_t> kernelUses;
    for (const ShadowFilterInfo& filter : kShadowFilters) ++kernelUses[filter.kernel.name];
    std::vector<Variant> variants;
    for (const ShadowFilterInfo& filter : kShadowFilters) {
        Variant variant{filter.name, {enums[size_t(filter.value)], std::string("\"") + filter.name + "\""}};
        if (kernelUses[filter.kernel.name] == 1) variant.tokens.push_back(filter.kernel.name);
        variants.push_back(variant);
    }
    // Not vacuous: several filters, one of them with a kernel of its own, were counted.
    EXPECT_GE(expectEachAdditionWithin(variants, "src/lights/shadow_filters.h", promised), 3u);
}

TEST(Extending, AGridMethodWithNoDataOfItsOwnTakesTheFilesExtendingMdNames) {
    const size_t promised = promisedFiles("A light-list method (how the forward pass finds a pixel's lights)", "files at most");
    EXPECT_LE(promised, 4u);  // the target: table row, kernel case, its math, its test
    const std::vector<std::string> enums = enumerators("src/render/light_list_method.h", "LightListMethod");
    ASSERT_EQ(enums.size(), render::kLightListMethods.size());
    // Such a method has culling flags, and another row has its light source and slices: its grid
    // and lists are another method's, filled differently.
    std::vector<Variant> variants;
    for (const render::LightListMethodInfo& method : render::kLightListMethods) {
        if (method.cullFlags == 0) continue;
        bool sharesItsData = false;
        uint32_t othersFlags = 0;
        for (const render::LightListMethodInfo& other : render::kLightListMethods) {
            if (&other == &method) continue;
            othersFlags |= other.cullFlags;
            sharesItsData = sharesItsData ||
                            (other.source.value == method.source.value && other.depthSlices == method.depthSlices);
        }
        if (!sharesItsData) continue;
        Variant variant{method.name, {enums[size_t(method.value)], std::string("\"") + method.name + "\""}};
        // Its own flags, by their defines in culling.h.
        const std::string culling = readText(kRoot / "shaders/shared/culling.h");
        const std::regex flagDefine("#define (PUNCTUAL_CULL_\\w+) (\\d+)u");
        for (auto it = std::sregex_iterator(culling.begin(), culling.end(), flagDefine); it != std::sregex_iterator(); ++it) {
            const uint32_t bit = uint32_t(std::stoul((*it)[2].str()));
            if ((method.cullFlags & bit) != 0 && (othersFlags & bit) == 0) variant.tokens.push_back((*it)[1].str());
        }
        EXPECT_GT(variant.tokens.size(), 2u) << method.name << ": a flag of its own";
        variants.push_back(variant);
    }
    EXPECT_GE(expectEachAdditionWithin(variants, "src/render/light_list_method.h", promised), 2u);
}

}  // namespace
}  // namespace punctual
