// The report's note on an area light's oracle V names what the oracle gave: an estimate with a
// 95% interval where it sampled, V without sampling error where its exact pass applied.
#include <gtest/gtest.h>

#include "core/channels.h"
#include "raster_compare/compare/report.h"

namespace ch = so::channels;

namespace {

so::ChannelImage oracleWith(bool sampled, bool exact) {
    so::ChannelImage image(4, 1);
    float* stdErr = image.addChannel(ch::lightChannel("rect", ch::kStdErr));
    float* exactMask = image.addChannel(ch::lightChannel("rect", ch::kExact));
    if (sampled) stdErr[0] = 0.01f;
    if (exact) exactMask[1] = exactMask[2] = 1.0f;
    return image;
}

}  // namespace

TEST(ReportNote, SampledOnlyIsAnEstimate) {
    const std::string note = so::oracleCertaintyNote(oracleWith(true, false), "rect");
    EXPECT_NE(note.find("an estimate with a 95% interval"), std::string::npos) << note;
    EXPECT_EQ(note.find("exact pass"), std::string::npos) << note;
}

TEST(ReportNote, ExactEverywhereIsNotCalledAnEstimate) {
    const std::string note = so::oracleCertaintyNote(oracleWith(false, true), "rect");
    EXPECT_EQ(note.find("estimate"), std::string::npos) << note;
    EXPECT_NE(note.find("at all 2 pixels"), std::string::npos) << note;
}

TEST(ReportNote, MixedCountsBoth) {
    const std::string note = so::oracleCertaintyNote(oracleWith(true, true), "rect");
    EXPECT_NE(note.find("at 2 pixels"), std::string::npos) << note;
    EXPECT_NE(note.find("the other 1 penumbra pixels"), std::string::npos) << note;
}
