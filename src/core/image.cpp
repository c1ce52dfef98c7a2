#include "core/image.h"

#include <cstdio>

#include <stb_image.h>
#include <stb_image_write.h>

#include "core/error.h"
#include "core/output_files.h"

namespace punctual {

void writePng(const std::string& path, const ImageRgba8& image) {
    if (image.width == 0 || image.height == 0 || image.pixels.size() != size_t(image.width) * image.height * 4) {
        throw Error(path, "refusing to write an empty or inconsistent image");
    }
    writeFileAtomically(path, encodePng(image));
}

std::string encodePng(const ImageRgba8& image) {
    if (image.width == 0 || image.height == 0 || image.pixels.size() != size_t(image.width) * image.height * 4) {
        throw Error("png", "refusing to encode an empty or inconsistent image");
    }
    std::string bytes;
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    if (!stbi_write_png_to_func(append, &bytes, int(image.width), int(image.height), 4, image.pixels.data(),
                                int(image.width * 4))) {
        throw Error("png", "encoding failed");
    }
    return bytes;
}

ImageRgba8 readPng(const std::string& path) {
    int w = 0, h = 0, channels = 0;
    stbi_uc* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
    if (!data) {
        throw Error(path, std::string("cannot read image: ") + stbi_failure_reason());
    }
    ImageRgba8 image;
    image.width = uint32_t(w);
    image.height = uint32_t(h);
    image.pixels.assign(data, data + size_t(w) * size_t(h) * 4);
    stbi_image_free(data);
    return image;
}

void writeFileAtomically(const std::string& path, const std::string& contents) {
    OutputFiles output;
    output.add(path, contents);
    output.commit();
}

}  // namespace punctual
