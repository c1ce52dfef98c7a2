#pragma once
// Messages joined through a stream: GCC 12 warns falsely (-Wrestrict, bug 105329) about some
// chains of std::string operator+. Pass std::filesystem::path as .string(): a stream quotes paths.
#include <sstream>
#include <string>

namespace punctual {

template <typename... Parts>
std::string concat(const Parts&... parts) {
    std::ostringstream s;
    (s << ... << parts);
    return s.str();
}

}  // namespace punctual
