#pragma once
// Counts the GL calls that make up a pass's fixed costs (dispatches, draws, barriers, clears,
// synchronisations, program switches) by routing glad's function pointers through counting
// wrappers while a GlCallCounter lives: the core runs unchanged, only the benchmark pays.
#include <string>
#include <vector>

namespace subdfit::bench {

struct GlCallCounts {
    long dispatches = 0;
    long draws = 0;
    long barriers = 0;         // glMemoryBarrier, glTextureBarrier
    long bufferClears = 0;     // glClearNamedBufferData / SubData
    long targetClears = 0;     // one per cleared framebuffer attachment (glClearNamedFramebuffer*, glClear)
    long syncs = 0;            // the CPU waits for the GPU: glFinish, fence waits, buffer / image readbacks
    long programSwitches = 0;  // glUseProgram with another program than the one in use
    long uniformSets = 0;
    long bufferUploads = 0;  // glNamedBufferSubData, glCopyNamedBufferSubData

    static std::vector<std::string> names();
    std::vector<long> values() const;
};

class GlCallCounter {
public:
    // Needs a current context whose functions glad has loaded; one counter at a time.
    GlCallCounter();
    ~GlCallCounter();
    GlCallCounter(const GlCallCounter&) = delete;
    GlCallCounter& operator=(const GlCallCounter&) = delete;

    // The calls since construction or the last take().
    GlCallCounts take();
};

}  // namespace subdfit::bench
