#pragma once
// Applies a PatchSet's stencils on the GPU: control points (θ, θ+ or θ−) -> every point the
// patches read. One dispatch, no readback.
#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "subdiv/patch_set.h"

namespace subdfit::render {

class StencilEvaluator {
public:
    explicit StencilEvaluator(const subdiv::PatchSet& patches);

    int pointCount() const { return pointCount_; }
    // A buffer sized for the evaluated points.
    gl::Buffer makePointBuffer() const { return gl::Buffer(GLsizeiptr(pointCount_) * 3 * sizeof(float)); }

    void evaluate(gl::ProgramCache& programs, const gl::Buffer& controlPoints, const gl::Buffer& points) const;

private:
    int baseCount_, pointCount_;
    gl::Buffer offsets_, indices_, weights_;
};

}  // namespace subdfit::render
