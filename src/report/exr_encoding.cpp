#include "report/exr_encoding.h"

#include <cstdio>
#include <cstdlib>

#include <tinyexr.h>

#include "core/check.h"
#include "core/concat.h"
#include "core/error.h"

namespace punctual::report {

std::string encodeExr(const std::vector<float>& data, uint32_t width, uint32_t height, int components,
                      const std::string& name) {
    PUNCTUAL_CHECK(components == 1 || components == 3, "EXR images have 1 or 3 channels here");
    const size_t pixels = size_t(width) * height;
    const size_t count = static_cast<size_t>(components);
    PUNCTUAL_CHECK(data.size() == pixels * count, "EXR data does not match its size");
    // The channels one plane each, in the order viewers expect (B, G, R; a single one named A),
    // as SaveEXR does: the bytes match what it would write to a file.
    std::vector<std::vector<float>> planes(count, std::vector<float>(pixels));
    for (size_t i = 0; i < pixels; ++i) {
        for (size_t c = 0; c < count; ++c) planes[count - 1 - c][i] = data[i * count + c];
    }
    std::vector<float*> planePointers;
    for (std::vector<float>& plane : planes) planePointers.push_back(plane.data());
    std::vector<EXRChannelInfo> channels;
    for (const char* channelName : components == 1 ? std::vector<const char*>{"A"} : std::vector<const char*>{"B", "G", "R"}) {
        EXRChannelInfo channel{};
        std::snprintf(channel.name, sizeof(channel.name), "%s", channelName);
        channels.push_back(channel);
    }
    std::vector<int> pixelTypes(count, TINYEXR_PIXELTYPE_FLOAT);

    EXRHeader header;
    InitEXRHeader(&header);
    header.compression_type = width < 16 && height < 16 ? TINYEXR_COMPRESSIONTYPE_NONE : TINYEXR_COMPRESSIONTYPE_ZIP;
    header.num_channels = components;
    header.channels = channels.data();
    header.pixel_types = pixelTypes.data();
    header.requested_pixel_types = pixelTypes.data();
    EXRImage image;
    InitEXRImage(&image);
    image.num_channels = components;
    image.images = reinterpret_cast<unsigned char**>(planePointers.data());
    image.width = int(width);
    image.height = int(height);

    unsigned char* memory = nullptr;
    const char* error = nullptr;
    const size_t size = SaveEXRImageToMemory(&image, &header, &memory, &error);
    if (size == 0 || memory == nullptr) {
        const std::string message = error ? error : "unknown error";
        if (error) FreeEXRErrorMessage(error);
        std::free(memory);
        throw Error(name, concat("cannot encode OpenEXR: ", message));
    }
    std::string bytes(reinterpret_cast<const char*>(memory), size);
    std::free(memory);
    return bytes;
}

}  // namespace punctual::report
