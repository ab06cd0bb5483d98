// Library code never ends the caller's process (issue 30): a broken invariant throws InternalError
// with one line naming the file, line and expression; a caller's misuse of an API is
// std::invalid_argument with one line.
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/image.h"
#include "core/image_codec.h"

namespace so {
namespace {

std::string whatOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

TEST(Errors, FailedCheckThrowsInternalErrorWithOneLine) {
    const int line = __LINE__ + 1;
    const auto fail = [] { SO_CHECK(1 + 1 == 3); };
    EXPECT_THROW(fail(), InternalError);
    EXPECT_THROW(fail(), std::logic_error);  // what a caller catching the standard kinds sees
    const std::string what = whatOf(fail);
    EXPECT_EQ(what, "internal error: " + std::string(__FILE__) + ":" + std::to_string(line) +
                        ": CHECK(1 + 1 == 3) failed");
}

TEST(Errors, FailedCheckOpNamesBothValues) {
    const auto fail = [] {
        const int a = 2, b = 3;
        SO_CHECK_EQ(a, b);
    };
    const std::string what = whatOf(fail);
    EXPECT_NE(what.find(": CHECK(a == b) failed with 2 vs 3"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
}

// A passing check does nothing but evaluate each operand once (a check of a call with side
// effects must not repeat it, in the message or elsewhere).
TEST(Errors, PassingChecksDoNothing) {
    int evaluated = 0;
    EXPECT_NO_THROW(SO_CHECK(++evaluated == 1));
    EXPECT_NO_THROW(SO_CHECK_LT(evaluated++, 2));
    EXPECT_NO_THROW(SO_CHECK_EQ(++evaluated, 3));
    EXPECT_EQ(evaluated, 3);
}

TEST(Errors, ImageMisuseIsInvalidArgument) {
    ChannelImage image(2, 2);
    image.addChannel("key.V");
    EXPECT_THROW(image.addChannel("key.V"), std::invalid_argument);
    EXPECT_THROW(image.channel("fill.V"), std::invalid_argument);
    const std::string what = whatOf([&] { image.channel("bad\nname"); });
    EXPECT_EQ(what, "image: no channel \"bad\\x0aname\"");
    EXPECT_THROW(encodePngRgb(2, 2, std::vector<float>(5)), std::invalid_argument);
    EXPECT_THROW(writeExr("/nonexistent/x.exr", image, {}, 1, nullptr, {1, 2}),
                 std::invalid_argument)
        << "rows 1..3 do not fit 2 rows";
}

}  // namespace
}  // namespace so
