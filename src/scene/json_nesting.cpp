#include "scene/json_nesting.h"

namespace punctual {

std::string jsonNestingProblem(const unsigned char* text, size_t length, size_t maxDepth) {
    size_t depth = 0;
    bool inString = false;
    bool escaped = false;
    for (size_t i = 0; i < length; ++i) {
        const unsigned char c = text[i];
        if (inString) {
            // Inside a string only an unescaped quote ends it; '\\' escapes the next byte (\" and
            // \\ are the two that matter here, \uXXXX needs nothing special).
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') inString = false;
            continue;
        }
        if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > maxDepth)
                return "JSON nests more than " + std::to_string(maxDepth) + " levels deep (at byte " + std::to_string(i) +
                       "); punctual reads at most " + std::to_string(maxDepth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;  // unbalanced closers are a syntax error the parser reports
        }
    }
    return "";
}

}  // namespace punctual
