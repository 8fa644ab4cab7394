// GL tests share one offscreen OSMesa context for the whole binary (Magnum's GL tester idea):
// creating one per test would spend seconds on context set-up and shader compiles.
#include <gtest/gtest.h>

#include "gl_test_context.h"
#include "gl/platform_defines.h"

namespace subdfit::test {
namespace {

std::unique_ptr<context::GlContext> sharedContext;
std::unique_ptr<gl::ProgramCache> sharedPrograms;

// A test that runs a whole job (simplify, batch) makes a context of its own current and leaves
// none current when it returns: every test starts on the shared one again.
class SharedContextListener : public ::testing::EmptyTestEventListener {
    void OnTestStart(const ::testing::TestInfo&) override { sharedContext->makeCurrent(); }
};

}  // namespace

void installSharedContextListener() {
    ::testing::UnitTest::GetInstance()->listeners().Append(new SharedContextListener);
}

const context::GlContext& glContext() { return *sharedContext; }
gl::ProgramCache& programs() { return *sharedPrograms; }

gl::Defines platformDefines() { return gl::platformDefines(); }

void expectNoGlError() {
    const GLenum error = glGetError();
    EXPECT_EQ(error, GLenum(GL_NO_ERROR)) << "GL error 0x" << std::hex << error;
}

}  // namespace subdfit::test

int main(int argc, char** argv) {
    ::testing::InitGoogleTest(&argc, argv);
    subdfit::test::sharedContext = subdfit::context::createHeadlessContext(subdfit::context::GlProvider::Osmesa);
    subdfit::test::sharedPrograms = std::make_unique<subdfit::gl::ProgramCache>(subdfit::test::platformDefines());
    subdfit::test::installSharedContextListener();
    const int result = RUN_ALL_TESTS();
    subdfit::test::sharedPrograms.reset();
    subdfit::test::sharedContext.reset();
    return result;
}
