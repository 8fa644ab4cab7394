#pragma once
// Applies a PatchSet's stencils on the GPU: control points (θ, or θ+ and θ−) -> every point the
// patches read. One dispatch, no readback.
#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "gl/texture.h"
#include "subdiv/patch_set.h"

namespace subdfit::render {

class StencilEvaluator {
public:
    explicit StencilEvaluator(const subdiv::PatchSet& patches);

    int pointCount() const { return pointCount_; }
    // A buffer sized for the evaluated points.
    gl::Buffer makePointBuffer() const { return gl::Buffer(GLsizeiptr(pointCount_) * 3 * sizeof(float)); }

    void evaluate(gl::ProgramCache& programs, const gl::Buffer& controlPoints, const gl::Buffer& points) const;
    // Two sets in the one dispatch (a step's θ+ and θ−), each stencil read once for both.
    void evaluate(gl::ProgramCache& programs, const gl::Buffer& controlPoints, const gl::Buffer& points,
                  const gl::Buffer& secondControlPoints, const gl::Buffer& secondPoints) const;

private:
    // The second set only where both of its buffers are given.
    void dispatch(gl::ProgramCache& programs, const gl::Buffer& controlPoints, const gl::Buffer& points,
                  const gl::Buffer* secondControlPoints, const gl::Buffer* secondPoints) const;

    int baseCount_, pointCount_;
    gl::Buffer offsets_, entries_;
    gl::BufferTexture entryTexture_;
};

}  // namespace subdfit::render
