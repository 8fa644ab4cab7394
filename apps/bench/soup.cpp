// `subdfit-bench soup`: the paper's Figure 2. A soup of N flat-coloured triangles (12 parameters
// each: three clip-space corners and an RGB colour) is fitted to a procedural 2D image with the
// per-pixel SGE estimator (Eq. 5: a pixel's Δ only reaches the triangles that covered it in the
// ± renders) and with the full-image one (Eq. 1: the image's ΣΔ reaches every parameter). Same
// perturbations, renders, Adam and step count; only G differs. With 10⁶ parameters the
// full-image estimate is almost pure noise, so it does not converge: that is the point.
#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "bench_commands.h"
#include "gl/platform_defines.h"
#include "bench_common.h"
#include "context/gl_context.h"
#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "gl/raster_state.h"
#include "gl/vertex_array.h"
#include "io/image_io.h"
#include "plot.h"
#include "bindings.h"
#include "render/render_target.h"
#include "optim/parameter_group.h"
#include "optim/updates.h"
#include "soup_bindings.h"
#include "util/error.h"

namespace subdfit::bench {
namespace {

constexpr std::uint32_t kPerturbationSeed = 0x50u;
constexpr std::uint32_t kSoupSeed = 2024u;

GLuint groupsOf(int count, int size) { return GLuint((count + size - 1) / size); }

// The soup renders into the project's RenderTarget: its face-id attachment holds triangle ids
// (soup_raster.frag writes them at the same locations; the (u,v) attachment stays unused).
using SoupTarget = render::RenderTarget;
static_assert(SUBDFIT_SOUP_ATTACHMENT_COLOR == SUBDFIT_ATTACHMENT_COLOR);
static_assert(SUBDFIT_SOUP_ATTACHMENT_TRIANGLE == SUBDFIT_ATTACHMENT_FACE_ID);

// Deterministic target, rows bottom-up: a smooth two-axis colour ramp, three discs and a patch of
// diagonal stripes, so it has both flat regions and edges at several scales.
std::vector<glm::vec4> makeTargetImage(int resolution) {
    std::vector<glm::vec4> pixels(size_t(resolution) * resolution);
    struct Disc {
        float x, y, r;
        glm::vec4 color;
    };
    const Disc discs[] = {{0.30f, 0.68f, 0.17f, {0.95f, 0.25f, 0.15f, 1}},
                          {0.72f, 0.30f, 0.14f, {0.98f, 0.85f, 0.20f, 1}},
                          {0.62f, 0.74f, 0.08f, {0.15f, 0.75f, 0.35f, 1}}};
    for (int y = 0; y < resolution; ++y)
        for (int x = 0; x < resolution; ++x) {
            const float u = (x + 0.5f) / resolution, v = (y + 0.5f) / resolution;
            glm::vec4 c{0.15f + 0.55f * u, 0.25f + 0.45f * v, 0.75f - 0.45f * u * v, 1.0f};
            if (u > 0.12f && u < 0.45f && v > 0.12f && v < 0.38f && std::sin(60.0f * (u + v)) > 0.0f)
                c = {0.1f, 0.12f, 0.35f, 1.0f};
            for (const auto& d : discs)
                if ((u - d.x) * (u - d.x) + (v - d.y) * (v - d.y) < d.r * d.r) c = d.color;
            pixels[size_t(y) * resolution + x] = c;
        }
    return pixels;
}

struct Soup {
    std::vector<float> positions;  // 9 per triangle
    std::vector<float> colors;     // 3 per triangle
};

// Small random triangles over the frame, sized so that together they cover it about 2.5 times
// (random placement leaves ~8% uncovered). Uniforms come from the raw mt19937 stream, so the
// soup is the same with every standard library.
Soup makeInitialSoup(int triangles) {
    std::mt19937 rng(kSoupSeed);
    auto uniform = [&rng](float lo, float hi) { return lo + (hi - lo) * float(rng() >> 8) * (1.0f / 16777216.0f); };
    // Circumradius r of a roughly equilateral triangle: area ≈ 1.3 r²; the frame is 4 clip units².
    const float radius = std::sqrt(2.5f * 4.0f / (1.3f * float(triangles)));
    Soup soup;
    soup.positions.reserve(size_t(triangles) * 9);
    soup.colors.reserve(size_t(triangles) * 3);
    for (int t = 0; t < triangles; ++t) {
        const float cx = uniform(-1.0f, 1.0f), cy = uniform(-1.0f, 1.0f), z = uniform(-0.9f, 0.9f);
        const float angle = uniform(0.0f, 6.2831853f);
        for (int k = 0; k < 3; ++k) {
            const float a = angle + 2.0943951f * k + uniform(-0.3f, 0.3f);
            const float r = radius * uniform(0.7f, 1.2f);
            soup.positions.insert(soup.positions.end(), {cx + r * std::cos(a), cy + r * std::sin(a), z});
        }
        for (int c = 0; c < 3; ++c) soup.colors.push_back(uniform(0.0f, 1.0f));
    }
    return soup;
}

const gl::ProgramSpec kSoupRaster{"soup_raster",
                                  {{GL_VERTEX_SHADER, "soup_raster.vert"}, {GL_FRAGMENT_SHADER, "soup_raster.frag"}}};
const gl::ProgramSpec kSoupGradient{
    "soup_gradient", {{GL_COMPUTE_SHADER, "soup_gradient.comp"}}, {"SUBDFIT_SOUP_FULL_IMAGE"}};
const gl::ProgramSpec kSoupScatter{
    "soup_scatter", {{GL_COMPUTE_SHADER, "soup_scatter.comp"}}, {"SUBDFIT_SOUP_FULL_IMAGE"}};
constexpr gl::VariantBits kSoupFullImage = 1u << 0;

class SoupFitter {
public:
    SoupFitter(gl::ProgramCache& programs, const Soup& soup, int resolution, bool fullImage)
        : programs_(programs),
          triangles_(int(soup.colors.size() / 3)),
          fullImage_(fullImage),
          positions_(optim::GroupKind::Other, "soup_positions", soup.positions, positionSettings(resolution),
                     SUBDFIT_SOUP_SEED_POSITIONS),
          colors_(optim::GroupKind::Other, "soup_colors", soup.colors, colorSettings(), SUBDFIT_SOUP_SEED_COLORS),
          triangleDelta_(GLsizeiptr(std::max(triangles_, 256)) * GLsizeiptr(sizeof(float))),
          plus_(resolution, resolution),
          minus_(resolution, resolution),
          image_(resolution, resolution) {}

    // Positions in clip units: ε = half a pixel, step a quarter pixel. Colours: ε = 0.05.
    static optim::GroupSettings positionSettings(int resolution) {
        optim::GroupSettings s;
        s.epsilon = 1.0f / float(resolution);
        s.learningRate = 0.5f / float(resolution);
        return s;
    }
    static optim::GroupSettings colorSettings() {
        optim::GroupSettings s;
        s.epsilon = 0.05f;
        s.learningRate = 0.01f;
        return s;
    }

    int triangles() const { return triangles_; }
    int parameters() const { return positions_.count() + colors_.count(); }

    void render(const gl::Buffer& positions, const gl::Buffer& colors, const SoupTarget& target) const {
        const auto& program = programs_.get(kSoupRaster);
        program.use();
        target.bindAndClear();
        // Random windings (never culled); depth clamp keeps triangles whose z drifts past ±1 visible.
        gl::RasterState{.depthClamp = true}.apply();
        positions.bindStorage(SUBDFIT_SOUP_SSBO_POSITIONS);
        colors.bindStorage(SUBDFIT_SOUP_SSBO_COLORS);
        vertexArray_.bind();
        glDrawArrays(GL_TRIANGLES, 0, 3 * triangles_);
        glBindVertexArray(0);
    }

    // The unperturbed soup θ, into the fitter's own image target.
    const SoupTarget& renderCurrent() {
        render(positions_.theta, colors_.theta, image_);
        return image_;
    }

    // One SGE step: P, R+, R−, G (two passes), Adam.
    void step(std::uint32_t counter, GLuint targetTexture) {
        optim::perturb(programs_, positions_, counter, kPerturbationSeed);
        optim::perturb(programs_, colors_, counter, kPerturbationSeed);
        render(positions_.thetaPlus, colors_.thetaPlus, plus_);
        render(positions_.thetaMinus, colors_.thetaMinus, minus_);

        const gl::VariantBits estimator = fullImage_ ? kSoupFullImage : 0;
        triangleDelta_.clearToZero();
        const auto& gradient = programs_.get(kSoupGradient, estimator);
        gradient.use();
        glBindTextureUnit(SUBDFIT_SOUP_UNIT_COLOR_PLUS, plus_.color().id());
        glBindTextureUnit(SUBDFIT_SOUP_UNIT_COLOR_MINUS, minus_.color().id());
        glBindTextureUnit(SUBDFIT_SOUP_UNIT_TRIANGLE_PLUS, plus_.faceId().id());
        glBindTextureUnit(SUBDFIT_SOUP_UNIT_TRIANGLE_MINUS, minus_.faceId().id());
        glBindTextureUnit(SUBDFIT_SOUP_UNIT_TARGET, targetTexture);
        triangleDelta_.bindStorage(SUBDFIT_SOUP_SSBO_TRIANGLE_DELTA);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        glDispatchCompute(groupsOf(plus_.width(), 16), groupsOf(plus_.height(), 16), 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

        const auto& scatter = programs_.get(kSoupScatter, estimator);
        scatter.use();
        scatter.set("uTriangleCount", unsigned(triangles_));
        scatter.set("uCounter", counter);
        scatter.set("uSeed", kPerturbationSeed);
        scatter.set("uEpsilonPositions", positions_.settings().epsilon);
        scatter.set("uEpsilonColors", colors_.settings().epsilon);
        triangleDelta_.bindStorage(SUBDFIT_SOUP_SSBO_TRIANGLE_DELTA);
        positions_.gradient.bindStorage(SUBDFIT_SOUP_SSBO_GRADIENT_POSITIONS);
        colors_.gradient.bindStorage(SUBDFIT_SOUP_SSBO_GRADIENT_COLORS);
        glDispatchCompute(groupsOf(triangles_, 256), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

        optim::adamStep(programs_, positions_, positions_.gradient, positions_.settings().learningRate);
        optim::adamStep(programs_, colors_, colors_.gradient, colors_.settings().learningRate);
    }

    // Checks on the CPU that the id buffer names the triangle that drew each pixel (llvmpipe has
    // had gl_PrimitiveID bugs): its colour must be that triangle's colour, bit for bit.
    void verifyTriangleIds(const Soup& soup) {
        const auto& image = renderCurrent();
        const auto color = image.readColor();
        const auto ids = image.readFaceId();
        size_t covered = 0, wrong = 0;
        for (size_t p = 0; p < ids.size(); ++p) {
            const int t = ids[p];
            if (t < 0) {
                wrong += color[p].a != 0.0f;
                continue;
            }
            ++covered;
            if (t >= triangles_) {
                ++wrong;
                continue;
            }
            for (int c = 0; c < 3; ++c) wrong += color[p][c] != soup.colors[size_t(t) * 3 + size_t(c)];
        }
        if (wrong > 0)
            throw Error("soup: the triangle-id buffer disagrees with the colour buffer on " + std::to_string(wrong) +
                        " values (gl_PrimitiveID is unreliable on this GL implementation)");
        std::printf("triangle ids verified: %zu of %zu pixels covered, all ids match their triangle's colour\n",
                    covered, ids.size());
    }

private:
    gl::ProgramCache& programs_;
    int triangles_;
    bool fullImage_;
    optim::ParameterGroup positions_, colors_;
    gl::Buffer triangleDelta_;
    SoupTarget plus_, minus_, image_;
    gl::VertexArray vertexArray_;
};

// Mean over pixels of ‖I_p − T_p‖² (RGB).
double meanLoss(const std::vector<glm::vec4>& image, const std::vector<glm::vec4>& target) {
    double sum = 0.0;
    for (size_t p = 0; p < image.size(); ++p)
        for (int c = 0; c < 3; ++c) {
            const double d = double(image[p][c]) - double(target[p][c]);
            sum += d * d;
        }
    return sum / double(image.size());
}

struct Curve {
    std::string name;
    std::vector<int> steps;
    std::vector<double> seconds, losses;
    double stepMs = 0.0;
    int stepsRun = 0;
};

Curve fit(gl::ProgramCache& programs, const Soup& soup, const SoupOptions& o, bool fullImage,
          const gl::Texture& targetTexture, const std::vector<glm::vec4>& target, const std::filesystem::path& png) {
    Curve curve{fullImage ? "full_image" : "per_pixel", {}, {}, {}, 0.0, 0};
    SoupFitter fitter(programs, soup, o.resolution, fullImage);
    if (!fullImage) fitter.verifyTriangleIds(soup);
    const int maxSteps = o.steps > 0 ? o.steps : 1 << 30;
    const int every = o.steps > 0 ? std::max(1, o.steps / 60) : 10;
    double elapsed = 0.0;  // step time only: loss measurements are not the optimiser's cost
    std::vector<double> stepSeconds;
    auto record = [&](int step) {
        curve.steps.push_back(step);
        curve.seconds.push_back(elapsed);
        curve.losses.push_back(meanLoss(fitter.renderCurrent().readColor(), target));
    };
    record(0);
    int step = 0;
    while (step < maxSteps && (o.seconds <= 0.0 || elapsed < o.seconds)) {
        const auto start = std::chrono::steady_clock::now();
        fitter.step(std::uint32_t(step), targetTexture.id());
        glFinish();
        stepSeconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        elapsed += stepSeconds.back();
        ++step;
        if (step % every == 0 || step == maxSteps) record(step);
    }
    if (curve.steps.back() != step) record(step);
    curve.stepsRun = step;
    // Median: robust to the other load of a shared machine.
    std::nth_element(stepSeconds.begin(), stepSeconds.begin() + step / 2, stepSeconds.end());
    curve.stepMs = 1000.0 * stepSeconds[size_t(step / 2)];
    io::writeImage(png, fitter.renderCurrent().readColor(), o.resolution, o.resolution);
    std::printf("%-11s %6d steps  %8.1f ms/step (median)  %7.1f s  loss %.4f -> %.4f\n", curve.name.c_str(), step,
                curve.stepMs, elapsed, curve.losses.front(), curve.losses.back());
    std::fflush(stdout);
    return curve;
}

}  // namespace

int runSoup(const SoupOptions& o) {
    if (o.triangles < 1 || o.resolution < 16 || (o.steps <= 0 && o.seconds <= 0.0))
        throw Error("soup: need --triangles >= 1, --res >= 16 and a positive --steps or --seconds");
    auto context = context::createHeadlessContext(o.glProvider);
    const auto info = context::currentGlInfo();
    gl::ProgramCache programs(gl::platformDefines());
    std::filesystem::create_directories(o.out);

    const auto target = makeTargetImage(o.resolution);
    const gl::Texture targetTexture(GL_RGBA32F, o.resolution, o.resolution);
    glTextureSubImage2D(targetTexture.id(), 0, 0, 0, o.resolution, o.resolution, GL_RGBA, GL_FLOAT, target.data());
    io::writeImage(o.out / "soup_target.png", target, o.resolution, o.resolution);

    const auto soup = makeInitialSoup(o.triangles);
    std::printf("renderer: %s\n", info.renderer.c_str());
    std::printf("soup: %d triangles, %d parameters, %dx%d, ", o.triangles, 12 * o.triangles, o.resolution,
                o.resolution);
    if (o.steps > 0) std::printf("%d steps", o.steps);
    if (o.seconds > 0.0) std::printf("%s%.0f s of steps", o.steps > 0 ? ", at most " : "", o.seconds);
    std::printf(" per estimator\n");

    // Compile (and let llvmpipe JIT) every program of both estimators on a one-triangle soup
    // first, so that neither curve's time axis carries compilation.
    for (bool fullImage : {false, true}) {
        SoupFitter warmUp(
            programs,
            Soup{{soup.positions.begin(), soup.positions.begin() + 9}, {soup.colors.begin(), soup.colors.begin() + 3}},
            16, fullImage);
        warmUp.step(0, targetTexture.id());
        glFinish();
    }

    const Curve perPixel = fit(programs, soup, o, false, targetTexture, target, o.out / "soup_per_pixel.png");
    const Curve fullImage = fit(programs, soup, o, true, targetTexture, target, o.out / "soup_full_image.png");

    std::vector<std::vector<std::string>> rows{{"estimator", "step", "seconds", "loss"}};
    for (const Curve* c : {&perPixel, &fullImage})
        for (size_t k = 0; k < c->steps.size(); ++k)
            rows.push_back(
                {c->name, std::to_string(c->steps[k]), std::to_string(c->seconds[k]), std::to_string(c->losses[k])});
    writeCsv(o.out / "soup.csv", rows);

    std::printf("\n%8s %14s %14s\n", "step", "per-pixel", "full-image");
    const size_t rowsShown = std::max(perPixel.steps.size(), fullImage.steps.size());
    const size_t stride = std::max<size_t>(1, rowsShown / 10);
    auto cell = [](const Curve& c, size_t k) { return k < c.losses.size() ? c.losses[k] : c.losses.back(); };
    for (size_t k = 0; k < rowsShown; k += stride) {
        const Curve& longer = perPixel.steps.size() >= fullImage.steps.size() ? perPixel : fullImage;
        std::printf("%8d %14.5f %14.5f\n", longer.steps[k], cell(perPixel, k), cell(fullImage, k));
    }
    std::printf("%8s %14.5f %14.5f\n", "final", perPixel.losses.back(), fullImage.losses.back());

    PlotSpec plot;
    plot.title = "Triangle soup (" + std::to_string(o.triangles) + " triangles): per-pixel vs full-image SGE";
    plot.xLabel = "step";
    plot.yLabel = "mean per-pixel squared error";
    plot.logY = true;
    for (const Curve* c : {&perPixel, &fullImage}) {
        std::vector<double> x(c->steps.begin(), c->steps.end());
        plot.series.push_back({c->name == "per_pixel" ? "per-pixel" : "full-image", x, c->losses});
    }
    writePlot(o.out / "soup_loss.png", plot);

    std::printf("peak_rss_mib=%.0f\n", peakResidentMiB());
    std::printf("soup_loss_ratio=%.3f\n", fullImage.losses.back() / std::max(perPixel.losses.back(), 1e-12));
    return 0;
}

}  // namespace subdfit::bench
