#include "core/image.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

#include <stb_image.h>
#include <stb_image_write.h>

#include "core/error.h"

namespace punctual {
namespace {

std::string temporaryPathFor(const std::string& path) {
    return path + ".partial";
}

void publish(const std::string& temporary, const std::string& path) {
    std::error_code ec;
    std::filesystem::rename(temporary, path, ec);
    if (ec) {
        std::filesystem::remove(temporary, ec);
        throw Error(path, "cannot write file");
    }
}

}  // namespace

void writePng(const std::string& path, const ImageRgba8& image) {
    if (image.width == 0 || image.height == 0 || image.pixels.size() != size_t(image.width) * image.height * 4) {
        throw Error(path, "refusing to write an empty or inconsistent image");
    }
    const std::string temporary = temporaryPathFor(path);
    const int ok = stbi_write_png(temporary.c_str(), int(image.width), int(image.height), 4,
                                  image.pixels.data(), int(image.width * 4));
    if (!ok) {
        std::error_code ec;
        std::filesystem::remove(temporary, ec);
        throw Error(path, "cannot write PNG (is the folder there and writable?)");
    }
    publish(temporary, path);
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
    const std::string temporary = temporaryPathFor(path);
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) throw Error(path, "cannot write file (is the folder there and writable?)");
        out.write(contents.data(), std::streamsize(contents.size()));
        out.close();
        if (!out) {
            std::error_code ec;
            std::filesystem::remove(temporary, ec);
            throw Error(path, "cannot write file");
        }
    }
    publish(temporary, path);
}

}  // namespace punctual
