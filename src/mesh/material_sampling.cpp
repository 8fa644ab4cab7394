#include "mesh/material_sampling.h"

#include <algorithm>
#include <cmath>

namespace subdfit::mesh {
namespace {

// A texel index under a wrap mode.
int wrapped(int i, int size, Wrap wrap) {
    switch (wrap) {
        case Wrap::ClampToEdge: return std::clamp(i, 0, size - 1);
        case Wrap::MirroredRepeat: {
            const int period = 2 * size;
            int k = ((i % period) + period) % period;
            return k < size ? k : period - 1 - k;
        }
        case Wrap::Repeat: break;
    }
    return ((i % size) + size) % size;
}

}  // namespace

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

float linearToSrgb(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

glm::vec4 sampleTexture(const MaterialSet& set, const TextureRef& texture, glm::vec2 uv, bool srgb) {
    if (!texture.present()) return glm::vec4(1.0f);
    const Image& image = set.images[size_t(texture.image)];
    if (image.rgba.empty()) return glm::vec4(1.0f);
    const glm::vec3 t = texture.uvTransform * glm::vec3(uv, 1.0f);
    // Texel centres at (i + ½) / width, as GL samples.
    const float x = t.x * float(image.width) - 0.5f, y = t.y * float(image.height) - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    if (!std::isfinite(fx) || !std::isfinite(fy)) return glm::vec4(1.0f);
    const int x0 = int(std::clamp(fx, -1e8f, 1e8f)), y0 = int(std::clamp(fy, -1e8f, 1e8f));
    auto texel = [&](int i, int j) {
        const int xi = wrapped(i, image.width, texture.wrapS), yj = wrapped(j, image.height, texture.wrapT);
        const std::uint8_t* p = image.rgba.data() + (size_t(yj) * size_t(image.width) + size_t(xi)) * 4;
        glm::vec4 c(p[0], p[1], p[2], p[3]);
        c /= 255.0f;
        if (srgb) c = glm::vec4(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b), c.a);
        return c;
    };
    if (texture.nearest) return texel(int(std::lround(x)), int(std::lround(y)));
    const float ax = x - fx, ay = y - fy;
    return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), ax),
                    glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), ax), ay);
}

MaterialSample sampleMaterial(const PolygonMesh& triangles, int triangle, float u, float v) {
    MaterialSample s;
    const float w0 = 1.0f - u - v;
    auto corner = [&](int k) { return size_t(triangles.faceIndices[size_t(3 * triangle + k)]); };
    if (!triangles.colors.empty())
        s.baseColor =
            w0 * triangles.colors[corner(0)] + u * triangles.colors[corner(1)] + v * triangles.colors[corner(2)];
    if (!triangles.materials) return s;
    const Material& m = triangles.materials->materials[size_t(triangles.faceMaterials[size_t(triangle)])];
    const glm::vec2 uv = triangles.uvs.empty() ? glm::vec2(0.0f)
                                               : w0 * triangles.uvs[corner(0)] + u * triangles.uvs[corner(1)] +
                                                     v * triangles.uvs[corner(2)];
    s.baseColor *= m.baseColorFactor * sampleTexture(*triangles.materials, m.baseColorTexture, uv, true);
    const glm::vec4 mr = sampleTexture(*triangles.materials, m.metallicRoughnessTexture, uv, false);
    s.roughness = m.roughnessFactor * mr.g;
    s.metallic = m.metallicFactor * mr.b;
    if (m.occlusionTexture.present())
        s.occlusion =
            1.0f + m.occlusionStrength * (sampleTexture(*triangles.materials, m.occlusionTexture, uv, false).r - 1.0f);
    if (m.emissiveFactor != glm::vec3(0.0f))
        s.emissive = m.emissiveFactor * glm::vec3(sampleTexture(*triangles.materials, m.emissiveTexture, uv, true));
    return s;
}

}  // namespace subdfit::mesh
