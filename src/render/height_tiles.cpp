#include "render/height_tiles.h"

#include <cmath>
#include <string>

#include "bindings.h"
#include "gl/dispatch.h"
#include "render/patch_renderer.h"
#include "util/error.h"

namespace subdfit::render {
namespace {

const gl::ProgramSpec kHeightTiles{"height_tiles", {{GL_COMPUTE_SHADER, "height_tiles.comp"}}};

int tilesPerRowFor(int faceCount) { return std::max(1, int(std::ceil(std::sqrt(double(faceCount))))); }

gl::Texture makeTexture(int faceCount, int resolution) {
    const int side = resolution + 3, perRow = tilesPerRowFor(faceCount);
    const int width = perRow * side, height = (faceCount + perRow - 1) / perRow * side;
    GLint most = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &most);
    if (std::max(width, height) > most)
        throw Error("the heights of " + std::to_string(faceCount) + " faces at " + std::to_string(resolution) +
                    " cells a side need " + std::to_string(width) + "x" + std::to_string(height) +
                    " texels, past this GL's largest texture (" + std::to_string(most) + ")");
    return gl::Texture(GL_R32F, width, std::max(height, 1));
}

}  // namespace

HeightTiles::HeightTiles(int faceCount, int resolution)
    : faceCount_(faceCount),
      resolution_(resolution),
      tilesPerRow_(tilesPerRowFor(faceCount)),
      texture_(makeTexture(faceCount, resolution)) {}

void HeightTiles::fill(gl::ProgramCache& programs, const PatchMaps& maps) const {
    SUBDFIT_CHECK(maps.kinds.has(kinds::MapKind::Displacement) && maps.resolution == resolution_);
    if (maps.bind) maps.bind();
    const auto& program = programs.get(kHeightTiles);
    program.use();
    program.set("uMapResolution", resolution_);
    program.set("uMapHaloTable", maps.haloTable);
    program.set("uTilesPerRow", tilesPerRow_);
    program.set("uFaceCount", faceCount_);
    glBindImageTexture(SUBDFIT_IMAGE_HEIGHT_TILES, texture_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glDispatchCompute(gl::groupsOf(texture_.width(), 8), gl::groupsOf(texture_.height(), 8), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindTextureUnit(SUBDFIT_UNIT_HEIGHT_TILES, texture_.id());
}

}  // namespace subdfit::render
