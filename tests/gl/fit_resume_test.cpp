// An interrupted fit resumes from its checkpoint and ends where an uninterrupted one does.
#include <gtest/gtest.h>

#include <atomic>
#include <glm/geometric.hpp>

#include "fit/fit_job.h"
#include "mesh/mesh_loader.h"
#include "mesh/obj_writer.h"
#include "mesh/procedural.h"
#include "scene_fixture.h"
#include "test_paths.h"
#include "util/error.h"

namespace subdfit::test {
namespace {

fit::FitOptions smallFit(const std::filesystem::path& dir, const std::string& name) {
    fit::FitOptions o;
    o.cage = dir / "cage.obj";
    o.reference = dir / "reference.obj";
    o.out = dir / name;
    o.steps = 40;
    o.views = 4;
    o.holdoutViews = 1;
    o.resolution = 48;
    o.checkpointEvery = 7;
    o.glProvider = context::GlProvider::Osmesa;
    return o;
}

TEST(FitResume, InterruptedRunContinuesToTheSameResult) {
    const auto dir = scratchDir("fit_resume");
    mesh::writeObj(dir / "cage.obj", mesh::makeQuadSphere(3));
    mesh::writeObj(dir / "reference.obj", mesh::makeLumpySphere(3, 0.2f, 5));

    const auto straight = fit::runFit(smallFit(dir, "straight"));
    EXPECT_EQ(straight.steps, 40);
    EXPECT_FALSE(straight.interrupted());

    // Stop after 20 steps, as Ctrl-C would: results of the steps taken are written.
    std::atomic<bool> cancel{false};
    auto interruptedOptions = smallFit(dir, "resumed");
    const auto interrupted =
        fit::runFit(interruptedOptions,
                    {.progress = [&](const fit::Progress& p) { cancel = cancel || p.step >= 20; }, .cancel = &cancel});
    EXPECT_TRUE(interrupted.interrupted());
    EXPECT_EQ(interrupted.steps, 20);
    EXPECT_TRUE(std::filesystem::exists(interruptedOptions.out / "cage.obj"));
    EXPECT_TRUE(std::filesystem::exists(interruptedOptions.out / "checkpoint.bin"));

    interruptedOptions.resume = true;
    const auto resumed = fit::runFit(interruptedOptions);
    EXPECT_EQ(resumed.resumedFromStep, 20);
    EXPECT_EQ(resumed.steps, 40);

    // G sums in fixed point, so a run repeats exactly: the resumed run must end on the very
    // same vertices (a restart from scratch or a skipped view order would differ by ~1e-3).
    const auto a = mesh::loadMesh(dir / "straight" / "cage.obj").positions;
    const auto b = mesh::loadMesh(dir / "resumed" / "cage.obj").positions;
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(a, b) << "largest vertex difference " << maxDistance(a, b);

    // The report's monitored losses run on through the resume: the same steps and losses, with
    // seconds that never go back.
    ASSERT_EQ(resumed.monitored.size(), straight.monitored.size());
    ASSERT_FALSE(straight.monitored.empty());
    for (size_t k = 0; k < straight.monitored.size(); ++k) {
        EXPECT_EQ(resumed.monitored[k].step, straight.monitored[k].step) << k;
        EXPECT_EQ(resumed.monitored[k].loss, straight.monitored[k].loss) << k;
        if (k > 0) {
            EXPECT_GE(resumed.monitored[k].seconds, resumed.monitored[k - 1].seconds) << k;
        }
    }
}

TEST(FitResume, RefusesACheckpointOfOtherSettings) {
    const auto dir = scratchDir("fit_resume_mismatch");
    mesh::writeObj(dir / "cage.obj", mesh::makeQuadSphere(2));
    mesh::writeObj(dir / "reference.obj", mesh::makeLumpySphere(2, 0.2f, 5));
    auto o = smallFit(dir, "out");
    o.steps = 3;
    fit::runFit(o);
    o.resume = true;
    o.seed = 99;
    try {
        fit::runFit(o);
        FAIL() << "resumed a checkpoint written with another seed";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("checkpoint.bin"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace subdfit::test
