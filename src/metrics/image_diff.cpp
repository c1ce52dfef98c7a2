#include "metrics/image_diff.h"

#include <algorithm>
#include <cstdlib>

#include "core/error.h"

namespace punctual {

ImageDifference compareImages(const ImageRgba8& a, const ImageRgba8& b) {
    if (a.width != b.width || a.height != b.height) throw Error("image comparison", "the images differ in size");
    const size_t pixels = size_t(a.width) * a.height;
    ImageDifference difference;
    if (pixels == 0) return difference;
    double sum = 0.0;
    size_t off = 0;
    for (size_t i = 0; i < pixels; ++i) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            const int d = std::abs(int(a.pixels[i * 4 + c]) - int(b.pixels[i * 4 + c]));
            sum += d;
            worst = std::max(worst, d);
        }
        off += worst > 2 ? 1 : 0;
    }
    difference.meanAbsolute = sum / (3.0 * 255.0 * double(pixels));
    difference.pixelsOff = double(off) / double(pixels);
    return difference;
}

}  // namespace punctual
