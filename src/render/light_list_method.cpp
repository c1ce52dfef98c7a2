#include "render/light_list_method.h"

#include "core/error.h"

namespace punctual::render {

const char* methodName(LightListMethod method) {
    switch (method) {
        case LightListMethod::Brute: return "brute";
        case LightListMethod::PerObject: return "per-object";
        case LightListMethod::Tiled: return "tiled";
        case LightListMethod::Clustered: return "clustered";
    }
    return "unknown";
}

LightListMethod parseMethod(const std::string& name) {
    for (LightListMethod m : {LightListMethod::Brute, LightListMethod::PerObject, LightListMethod::Tiled,
                              LightListMethod::Clustered}) {
        if (name == methodName(m)) return m;
    }
    throw Error("--culling", "expected brute, per-object, tiled or clustered, got '" + name + "'");
}

}  // namespace punctual::render
