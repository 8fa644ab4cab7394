#include "view_renderer.h"

#include "gl/raster_state.h"

namespace subdfit::view {
namespace {

const gl::ProgramSpec kComposite{
    "view_composite",
    {{GL_VERTEX_SHADER, "view_fullscreen.vert"}, {GL_FRAGMENT_SHADER, "view_composite.frag"}},
    {"SUBDFIT_DISPLACEMENT", "SUBDFIT_NORMAL_MAP", "SUBDFIT_BASE_COLOR_MAP", "SUBDFIT_METALLIC_ROUGHNESS_MAP",
     "SUBDFIT_APPEARANCE_ATLAS"}};
constexpr gl::VariantBits kCompositeDisplacement = 1u << 0, kCompositeNormalMap = 1u << 1,
                          kCompositeBaseColor = 1u << 2, kCompositeMetallicRoughness = 1u << 3,
                          kCompositeAppearanceAtlas = 1u << 4;

}  // namespace

void ViewRenderer::draw(const ViewSource& source, const render::Camera& camera, const ViewSettings& settings,
                        glm::ivec2 origin, glm::ivec2 size) {
    if (size.x < 1 || size.y < 1) return;  // minimised
    if (!fit_ || fit_->width() != size.x || fit_->height() != size.y) {
        fit_ = std::make_unique<render::RenderTarget>(size.x, size.y);
        target_ = std::make_unique<render::RenderTarget>(size.x, size.y);
    }
    if (!emptyVertexArray_) emptyVertexArray_.emplace();

    // A mode that does not read a buffer leaves it cleared, so the composite sees background there.
    if (viewModeNeedsFit(settings.mode)) source.draw(camera, *fit_);
    else fit_->bindAndClear();
    if (viewModeNeedsTarget(settings.mode) && source.drawReference) source.drawReference(camera, *target_);
    else target_->bindAndClear();

    const maps::MapParameters* maps = source.maps;
    const maps::MapEffects effects = maps ? maps->effects() : maps::MapEffects{};
    const bool atlas = maps && maps->appearanceAtlas().present();
    const auto& program = programs_.get(
        kComposite, (effects.has(maps::MapKind::Displacement) ? kCompositeDisplacement : 0) |
                        (effects.has(maps::MapKind::NormalMap) ? kCompositeNormalMap : 0) |
                        (effects.has(maps::MapKind::BaseColor) ? kCompositeBaseColor : 0) |
                        (effects.has(maps::MapKind::MetallicRoughness) ? kCompositeMetallicRoughness : 0) |
                        (atlas && effects.appearance() ? kCompositeAppearanceAtlas : 0));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(origin.x, origin.y, size.x, size.y);
    gl::RasterState{.depthTest = false}.apply();
    program.use();
    program.set("uMode", int(settings.mode));
    glUniform2i(program.location("uOrigin"), origin.x, origin.y);
    program.set("uScale", settings.scale);
    if (maps) {
        const render::PatchMaps current = maps->forRaster(maps::ParameterVersion::Current);
        program.set("uMapResolution", maps->layout().resolution);
        if (effects.appearance()) {
            program.set("uAppearanceResolution", current.appearanceResolution);
            program.set("uAppearanceTable", current.appearanceTable);
        }
        current.bind();
    }
    glBindTextureUnit(0, fit_->color().id());
    glBindTextureUnit(1, fit_->faceId().id());
    glBindTextureUnit(2, fit_->patchUv().id());
    glBindTextureUnit(3, target_->color().id());
    emptyVertexArray_->bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);

    if (settings.cageWireframe && source.wireframe && source.cageVertices)
        source.wireframe->draw(programs_, *source.cageVertices, camera);
}

}  // namespace subdfit::view
