#include "view_renderer.h"

namespace subdfit::view {

void ViewRenderer::draw(FitSession& session, const CageWireframe& wireframe, const render::Camera& camera,
                        const ViewSettings& settings, glm::ivec2 origin, glm::ivec2 size) {
    if (size.x < 1 || size.y < 1) return;  // minimised
    if (!fit_ || fit_->width() != size.x || fit_->height() != size.y) {
        fit_ = std::make_unique<render::RenderTarget>(size.x, size.y);
        target_ = std::make_unique<render::RenderTarget>(size.x, size.y);
    }
    if (!emptyVertexArray_) {
        GLuint id = 0;
        glCreateVertexArrays(1, &id);  // core profile draws need a vertex array, even an empty one
        emptyVertexArray_ = gl::GlHandle<gl::VertexArrayTraits>(id);
    }

    auto& fitter = session.fitter();
    // A mode that does not read a buffer leaves it cleared, so the composite sees background there.
    if (viewModeNeedsFit(settings.mode)) fitter.render(camera, *fit_);
    else fit_->bindAndClear();
    if (viewModeNeedsTarget(settings.mode)) session.scene().referenceRenderer.draw(session.programs(), camera, *target_);
    else target_->bindAndClear();

    const maps::MapParameters* maps = fitter.maps();
    const auto& program = programs_.get("view_composite",
                                        {{GL_VERTEX_SHADER, "view_fullscreen.vert"},
                                         {GL_FRAGMENT_SHADER, "view_composite.frag"}},
                                        maps ? maps->defines() : gl::Defines{});
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(origin.x, origin.y, size.x, size.y);
    glDisable(GL_DEPTH_TEST);
    program.use();
    program.set("uMode", int(settings.mode));
    glUniform2i(program.location("uOrigin"), origin.x, origin.y);
    program.set("uScale", settings.scale);
    if (maps) {
        program.set("uMapResolution", maps->layout().resolution);
        maps->forRaster(maps::ParameterVersion::Current).bind();
    }
    glBindTextureUnit(0, fit_->color().id());
    glBindTextureUnit(1, fit_->faceId().id());
    glBindTextureUnit(2, fit_->patchUv().id());
    glBindTextureUnit(3, target_->color().id());
    glBindVertexArray(emptyVertexArray_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);

    if (settings.cageWireframe) wireframe.draw(programs_, fitter.vertexGroup().theta, camera);
}

}  // namespace subdfit::view
