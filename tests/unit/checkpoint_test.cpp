// Checkpoints: what is written reads back exactly; anything damaged, truncated, of another
// version or written for other settings is refused with one line naming the file, and a count
// that claims more than the file holds allocates nothing.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "fit/checkpoint.h"
#include "error_message.h"
#include "test_paths.h"
#include "util/error.h"
#include "util/hash.h"

namespace subdfit::fit {
namespace {

namespace fs = std::filesystem;

FitState sampleState() {
    FitState state{.steps = 42, .samples = 7};
    for (int g = 0; g < 2; ++g) {
        GroupState group{.groupMoment2 = 0.5f + float(g), .adamSteps = 40 + g};
        for (int i = 0; i < 30; ++i) {
            group.theta.push_back(float(i) * 0.25f - float(g));
            group.moment1.push_back(float(i) * 1e-3f);
            group.moment2.push_back(float(i) * 1e-6f);
        }
        state.groups.push_back(group);
    }
    // Where a plateau schedule stands: resumed, it must continue with the same step and best.
    state.learningRateScale = 0.25f;
    state.mapsStartStep = 30;
    state.schedule = {.bestLoss = 0.125,
                      .bestStep = 36,
                      .window = {0.5, 0.25, 0.125},
                      .stageLosses = {1.0, 0.5},
                      .stageStart = 3,
                      .probationOver = true,
                      .halvings = 2,
                      .carriedHalvings = 3,
                      .bestTheta = {state.groups[0].theta, state.groups[1].moment1},
                      .startTheta = {state.groups[1].theta, state.groups[0].moment1}};
    state.monitored = {{.step = 0, .seconds = 0.0, .loss = 1.0}, {.step = 10, .seconds = 1.5, .loss = 0.5}};
    return state;
}

std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

std::string refusal(const fs::path& path, const std::string& fingerprint = "fp") {
    return test::errorMessage([&] { readCheckpoint(path, fingerprint); });
}

class Checkpoint : public ::testing::Test {
protected:
    void SetUp() override {
        path_ = test::scratchDir("checkpoint") / "checkpoint.bin";
        writeCheckpoint(path_, "fp", sampleState());
        bytes_ = readBytes(path_);
    }
    fs::path path_;
    std::string bytes_;
};

TEST_F(Checkpoint, ReadsBackExactly) {
    const auto read = readCheckpoint(path_, "fp");
    ASSERT_TRUE(read);
    const FitState expected = sampleState();
    EXPECT_EQ(read->steps, expected.steps);
    EXPECT_EQ(read->samples, expected.samples);
    ASSERT_EQ(read->groups.size(), expected.groups.size());
    for (size_t g = 0; g < expected.groups.size(); ++g) {
        EXPECT_EQ(read->groups[g].theta, expected.groups[g].theta);
        EXPECT_EQ(read->groups[g].moment1, expected.groups[g].moment1);
        EXPECT_EQ(read->groups[g].moment2, expected.groups[g].moment2);
        EXPECT_EQ(read->groups[g].groupMoment2, expected.groups[g].groupMoment2);
        EXPECT_EQ(read->groups[g].adamSteps, expected.groups[g].adamSteps);
    }
    EXPECT_EQ(read->learningRateScale, expected.learningRateScale);
    EXPECT_EQ(read->mapsStartStep, expected.mapsStartStep);
    EXPECT_EQ(read->schedule.bestLoss, expected.schedule.bestLoss);
    EXPECT_EQ(read->schedule.bestStep, expected.schedule.bestStep);
    EXPECT_EQ(read->schedule.window, expected.schedule.window);
    EXPECT_EQ(read->schedule.stageLosses, expected.schedule.stageLosses);
    EXPECT_EQ(read->schedule.stageStart, expected.schedule.stageStart);
    EXPECT_EQ(read->schedule.probationOver, expected.schedule.probationOver);
    EXPECT_EQ(read->schedule.halvings, expected.schedule.halvings);
    EXPECT_EQ(read->schedule.carriedHalvings, expected.schedule.carriedHalvings);
    EXPECT_EQ(read->schedule.bestTheta, expected.schedule.bestTheta);
    EXPECT_EQ(read->schedule.startTheta, expected.schedule.startTheta);
    EXPECT_EQ(read->monitored, expected.monitored);
    EXPECT_FALSE(readCheckpoint(path_.parent_path() / "none.bin", "fp"));
    // A probation that stops only a rise is resumed as one, and the later one that asks a gain
    // as that.
    for (const bool asksAGain : {false, true}) {
        FitState probation = sampleState();
        probation.schedule.probationOver = false;
        probation.schedule.probationStopsOnlyARise = !asksAGain;
        probation.schedule.probationAsksAGain = asksAGain;
        writeCheckpoint(path_, "fp", probation);
        const auto resumed = readCheckpoint(path_, "fp");
        ASSERT_TRUE(resumed);
        EXPECT_FALSE(resumed->schedule.probationOver);
        EXPECT_EQ(resumed->schedule.probationStopsOnlyARise, !asksAGain);
        EXPECT_EQ(resumed->schedule.probationAsksAGain, asksAGain);
    }
}

TEST_F(Checkpoint, EveryFlippedByteIsRefused) {
    for (size_t at = 0; at < bytes_.size(); at += 7) {
        std::string damaged = bytes_;
        damaged[at] ^= 0x20;
        writeBytes(path_, damaged);
        const std::string message = refusal(path_);
        EXPECT_NE(message.find("checkpoint.bin: "), std::string::npos) << "byte " << at << ": " << message;
    }
}

TEST_F(Checkpoint, TruncationOtherVersionsAndOtherSettingsAreRefused) {
    writeBytes(path_, bytes_.substr(0, bytes_.size() / 2));
    EXPECT_NE(refusal(path_).find("damaged checkpoint"), std::string::npos);
    writeBytes(path_, "SDFTCKP3" + bytes_.substr(8));
    EXPECT_NE(refusal(path_).find("another format version"), std::string::npos);
    writeBytes(path_, "not a checkpoint at all");
    EXPECT_NE(refusal(path_).find("not a subdfit checkpoint"), std::string::npos);
    writeBytes(path_, bytes_);
    EXPECT_NE(refusal(path_, "other").find("other inputs or settings"), std::string::npos);
}

// A count of 2^40 floats behind a valid checksum: the reader must see that the file cannot
// hold them instead of allocating 4 TB.
TEST_F(Checkpoint, ACountBeyondTheFileAllocatesNothing) {
    std::string payload = "SDFTCKP9";
    auto put = [&](auto value) { payload.append(reinterpret_cast<const char*>(&value), sizeof value); };
    put(std::uint64_t(2));
    payload += "fp";
    put(std::int32_t(1));
    put(std::uint32_t(1));
    put(std::uint32_t(1));        // one group
    put(std::int32_t(1));         // its Adam steps
    put(std::uint64_t(1) << 42);  // theta: 2^40 floats
    const std::uint64_t checksum = hash64(payload);
    writeBytes(path_, payload + std::string(reinterpret_cast<const char*>(&checksum), sizeof checksum));
    const std::string message = refusal(path_);
    EXPECT_NE(message.find("damaged checkpoint (it ends early)"), std::string::npos) << message;
}

}  // namespace
}  // namespace subdfit::fit
