// The fuzz build only (cmake/Fuzz.cmake): tinygltf, stb_image, stb_image_write and
// stb_image_resize (texture fitting, scene/texture_limit.cpp) compiled from
// the Debian packages' headers, so that they carry the fuzzer's coverage and ASan's checks,
// instead of linking the uninstrumented libtinygltf.so and libstb.so. Like Debian's
// libtinygltf.so, tinygltf uses the system's nlohmann JSON and stb_image.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <tiny_gltf.h>  // includes stb_image.h and stb_image_write.h, with the definitions above
#define STB_IMAGE_RESIZE_IMPLEMENTATION
#include <stb_image_resize.h>
