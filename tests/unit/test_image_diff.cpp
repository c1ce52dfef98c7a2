#include <gtest/gtest.h>

#include "core/error.h"
#include "metrics/image_diff.h"

namespace punctual {
namespace {

ImageRgba8 grey(uint8_t value) {
    ImageRgba8 image;
    image.width = 2;
    image.height = 2;
    image.pixels.assign(16, value);
    return image;
}

TEST(ImageDiff, KnownAnswers) {
    const ImageDifference same = compareImages(grey(10), grey(10));
    EXPECT_EQ(same.meanAbsolute, 0.0);
    EXPECT_EQ(same.pixelsOff, 0.0);
    ImageRgba8 other = grey(10);
    other.pixels[0] = 13;  // one channel of one pixel, 3/255 off
    const ImageDifference d = compareImages(grey(10), other);
    EXPECT_DOUBLE_EQ(d.meanAbsolute, 3.0 / (255.0 * 12.0));
    EXPECT_DOUBLE_EQ(d.pixelsOff, 0.25);
    other.pixels[0] = 12;  // 2/255 is within tolerance
    EXPECT_EQ(compareImages(grey(10), other).pixelsOff, 0.0);
}

TEST(ImageDiff, SizesMustMatch) {
    ImageRgba8 small = grey(0);
    small.width = 1;
    small.pixels.resize(8);
    EXPECT_THROW(compareImages(grey(0), small), Error);
}

}  // namespace
}  // namespace punctual
