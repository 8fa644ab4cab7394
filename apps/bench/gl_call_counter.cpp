#include "gl_call_counter.h"

#include <glad/gl.h>

#include "util/error.h"

namespace subdfit::bench {
namespace {

GlCallCounts counts;
GLuint programInUse = 0;
bool installed = false;

// One wrapper per counted entry point: the slot is glad's pointer, the field what it adds to.
template <auto Slot, long GlCallCounts::*Field, long Weight = 1>
struct Counted;
template <class R, class... A, R (**Slot)(A...), long GlCallCounts::*Field, long Weight>
struct Counted<Slot, Field, Weight> {
    static inline R (*original)(A...) = nullptr;
    static R call(A... args) {
        counts.*Field += Weight;
        return original(args...);
    }
    static void install() {
        original = *Slot;
        *Slot = &call;
    }
    static void remove() { *Slot = original; }
};

using C = GlCallCounts;
template <class... W>
struct Wrappers {
    static void install() { (W::install(), ...); }
    static void remove() { (W::remove(), ...); }
};
using All = Wrappers<
    Counted<&glad_glDispatchCompute, &C::dispatches>, Counted<&glad_glDispatchComputeIndirect, &C::dispatches>,
    Counted<&glad_glDrawArrays, &C::draws>, Counted<&glad_glDrawElements, &C::draws>,
    Counted<&glad_glDrawArraysInstanced, &C::draws>, Counted<&glad_glDrawElementsInstanced, &C::draws>,
    Counted<&glad_glMemoryBarrier, &C::barriers>, Counted<&glad_glMemoryBarrierByRegion, &C::barriers>,
    Counted<&glad_glTextureBarrier, &C::barriers>, Counted<&glad_glClearNamedBufferData, &C::bufferClears>,
    Counted<&glad_glClearNamedBufferSubData, &C::bufferClears>, Counted<&glad_glClearBufferData, &C::bufferClears>,
    Counted<&glad_glClearNamedFramebufferfv, &C::targetClears>,
    Counted<&glad_glClearNamedFramebufferiv, &C::targetClears>,
    Counted<&glad_glClearNamedFramebufferuiv, &C::targetClears>,
    Counted<&glad_glClearNamedFramebufferfi, &C::targetClears>, Counted<&glad_glClear, &C::targetClears>,
    Counted<&glad_glClearTexImage, &C::targetClears>, Counted<&glad_glFinish, &C::syncs>,
    Counted<&glad_glClientWaitSync, &C::syncs>, Counted<&glad_glGetNamedBufferSubData, &C::syncs>,
    Counted<&glad_glGetBufferSubData, &C::syncs>, Counted<&glad_glGetTextureImage, &C::syncs>,
    Counted<&glad_glGetTextureSubImage, &C::syncs>, Counted<&glad_glReadPixels, &C::syncs>,
    Counted<&glad_glMapNamedBufferRange, &C::syncs>, Counted<&glad_glProgramUniform1i, &C::uniformSets>,
    Counted<&glad_glProgramUniform1ui, &C::uniformSets>, Counted<&glad_glProgramUniform1f, &C::uniformSets>,
    Counted<&glad_glProgramUniform2fv, &C::uniformSets>, Counted<&glad_glProgramUniform3fv, &C::uniformSets>,
    Counted<&glad_glProgramUniform4fv, &C::uniformSets>, Counted<&glad_glProgramUniformMatrix3fv, &C::uniformSets>,
    Counted<&glad_glProgramUniformMatrix4fv, &C::uniformSets>, Counted<&glad_glUniform1i, &C::uniformSets>,
    Counted<&glad_glUniform2i, &C::uniformSets>, Counted<&glad_glNamedBufferSubData, &C::bufferUploads>,
    Counted<&glad_glCopyNamedBufferSubData, &C::bufferUploads>>;

PFNGLUSEPROGRAMPROC originalUseProgram = nullptr;
void countedUseProgram(GLuint program) {
    if (program != programInUse) ++counts.programSwitches;
    programInUse = program;
    originalUseProgram(program);
}

}  // namespace

std::vector<std::string> GlCallCounts::names() {
    return {"dispatches",       "draws",        "barriers",      "buffer_clears", "target_clears", "syncs",
            "program_switches", "uniform_sets", "buffer_uploads"};
}

std::vector<long> GlCallCounts::values() const {
    return {dispatches, draws,           barriers,    bufferClears, targetClears,
            syncs,      programSwitches, uniformSets, bufferUploads};
}

GlCallCounter::GlCallCounter() {
    SUBDFIT_CHECK(!installed && glad_glDispatchCompute != nullptr);
    installed = true;
    GLint current = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &current);
    programInUse = GLuint(current);
    All::install();
    originalUseProgram = glad_glUseProgram;
    glad_glUseProgram = &countedUseProgram;
    counts = {};
}

GlCallCounter::~GlCallCounter() {
    glad_glUseProgram = originalUseProgram;
    All::remove();
    installed = false;
}

GlCallCounts GlCallCounter::take() {
    const GlCallCounts taken = counts;
    counts = {};
    return taken;
}

}  // namespace subdfit::bench
