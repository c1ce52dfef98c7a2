// Prints the option fuzzer's dictionary words that the tables hold: every render option's name and
// every variant name its help lists (the first word of each variant line), one quoted word a line
// in libFuzzer's dictionary syntax. scripts/fuzz.sh appends them to tests/fuzz/options.dict, which
// keeps only the hand-picked values no table holds (edge-case numbers, separators), so a new
// option or variant reaches the fuzzer with no edit here.
#include <iostream>
#include <set>
#include <sstream>
#include <string>

#include "cli/options.h"
#include "cli/render_option_table.h"

int main() {
    using namespace punctual::cli;
    const RenderOptions defaults;
    std::set<std::string> words;
    for (const RenderOptionSpec& spec : renderOptionTable()) {
        words.insert(spec.name);
        if (!spec.variants) continue;
        std::istringstream lines(spec.variants(defaults, 0));
        std::string line;
        while (std::getline(lines, line)) {
            std::istringstream first(line);
            std::string name;
            if (first >> name) words.insert(name);
        }
    }
    for (const std::string& word : words) std::cout << '"' << word << "\"\n";
    return 0;
}
