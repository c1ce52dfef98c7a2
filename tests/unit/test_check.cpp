// PUNCTUAL_CHECK: misuse by calling code is an internal error, never confused with a user error.
#include <gtest/gtest.h>

#include <string>

#include "core/check.h"
#include "core/error.h"

namespace punctual {
namespace {

int checkedHalf(int even) {
    PUNCTUAL_CHECK(even % 2 == 0, "checkedHalf needs an even number");
    return even / 2;
}

TEST(InternalCheck, PassesThroughWhenTheConditionHolds) { EXPECT_EQ(checkedHalf(8), 4); }

TEST(InternalCheck, ThrowsAnInternalErrorNotAUserError) {
    bool caught = false;
    try {
        checkedHalf(7);
    } catch (const Error&) {
        FAIL() << "a broken promise between parts of punctual must not read as the user's mistake";
    } catch (const InternalError& error) {
        caught = true;
        const std::string what = error.what();
        // Names the source file, the message and the condition.
        EXPECT_NE(what.find("test_check.cpp:"), std::string::npos) << what;
        EXPECT_NE(what.find("checkedHalf needs an even number"), std::string::npos) << what;
        EXPECT_NE(what.find("(even % 2 == 0)"), std::string::npos) << what;
    }
    EXPECT_TRUE(caught);
}

TEST(InternalCheck, ReportsSourcePathsFromSrcOn) {
    try {
        failCheck("/home/someone/punctual/src/render/renderer.cpp", 12, "x", "broken");
        FAIL() << "failCheck returned";
    } catch (const InternalError& error) {
        EXPECT_EQ(std::string(error.what()), "src/render/renderer.cpp:12: broken (x)");
    }
}

}  // namespace
}  // namespace punctual
