#pragma once
// The web decoder's work, without its WebAssembly glue (subd_web.cpp), so that it builds natively
// too: the fuzz target tests/fuzz/fuzz_web.cpp runs it under ASan and UBSan. asset.subd bytes in,
// the surface `subdfit decode` writes out as arrays, through the same reader (readShippedSubd),
// decode budget and density choice (pricedDensity: codec/decode_budget.h,
// codec/decode_density.h) and surface (surfaceGltfMesh, surfaceNormalImage, surfaceMaterial).
// Appearance images stay the JPEGs the file carries (their markers checked by the reader): the
// browser decodes them. apps/web/js/subd_core.mjs reads the Result.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "export/gltf_mesh.h"
#include "codec/subd_format.h"

namespace subdfit::web {

// An image of the material. Roles: 0 base colour, 1 metallic-roughness (its red channel the
// occlusion when Result::flags says so), 2 normal, 3 emissive.
struct Image {
    std::uint32_t role, encoding;  // encoding 0: RGBA8 pixels, rows top first; 1: JPEG bytes
    std::uint32_t width, height;
    const std::uint8_t* data;
    std::uint32_t size;
};

// Read word by word (4 bytes each) by subd_core.mjs: keep the two in step.
struct Result {
    std::uint32_t vertexCount, indexCount, segments, flags;  // flags: 1 tangents, 2 occlusion
    const float *positions, *normals, *tangents, *uvs;
    const std::uint32_t* indices;
    float baseColorFactor[4], metallicFactor, roughnessFactor, emissiveFactor[3];
    std::uint32_t imageCount;
    const Image* images;
    const char* warnings;  // '\n'-separated, empty when none
};
// In WebAssembly (32-bit pointers); a native build (the fuzz target) lays them out its own way.
static_assert(sizeof(void*) != 4 || sizeof(Result) == 21 * 4, "subd_core.mjs reads Result as 21 words");
static_assert(sizeof(void*) != 4 || sizeof(Image) == 6 * 4, "subd_core.mjs reads Image as 6 words");

constexpr std::uint32_t kTangents = 1, kOcclusion = 2;

struct Decoded {
    Result result{};
    exporter::GltfMesh mesh;
    std::vector<Image> images;
    std::vector<std::vector<std::uint8_t>> pixels;
    std::vector<codec::ShippedImage> shipped;
    std::string warnings;
};

// The decoded surface of `bytes` (`triangles` 0: the default density; `name` names the file in
// messages; `ending` Prefix: the file's first bytes, as they arrive, a coarser asset). Throws
// subdfit::Error as decodeSubd does, in one line naming the file.
std::unique_ptr<Decoded> decode(std::span<const std::uint8_t> bytes, std::int64_t triangles, const std::string& name,
                                codec::SubdEnding ending = codec::SubdEnding::Whole);

}  // namespace subdfit::web
