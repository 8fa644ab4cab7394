#include "export/gltf/draco_encoding.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <limits>
#include <memory>

#include "util/error.h"

namespace subdfit::exporter {
namespace {

constexpr int kGenericBits = 10, kMinTexcoordBits = 12;
constexpr int kSpeed = 5;  // Draco's middle ground between size and encode/decode time

// Adds a float attribute with one value per point; returns its unique id.
int addAttribute(draco::Mesh& mesh, draco::GeometryAttribute::Type type, int components, const float* values) {
    draco::GeometryAttribute attribute;
    attribute.Init(type, nullptr, uint8_t(components), draco::DT_FLOAT32, false, int64_t(sizeof(float)) * components,
                   0);
    const int id = mesh.AddAttribute(attribute, true, mesh.num_points());
    SUBDFIT_CHECK(id >= 0);
    draco::PointAttribute* added = mesh.attribute(id);
    for (uint32_t p = 0; p < mesh.num_points(); ++p)
        added->SetAttributeValue(draco::AttributeValueIndex(p), values + size_t(p) * size_t(components));
    return int(added->unique_id());
}

// 6 bits below the texel: the error stays under 1/64 texel however large the atlas.
int texcoordBits(const glm::ivec2& atlasSize) {
    const int largest = std::max({atlasSize.x, atlasSize.y, 1});
    return std::clamp(int(std::ceil(std::log2(double(largest)))) + 6, kMinTexcoordBits, 30);
}

// draco::Mesh can be neither copied nor moved.
std::unique_ptr<draco::Mesh> toDraco(const GltfMesh& tess, DracoEncodedMesh& ids) {
    auto owned = std::make_unique<draco::Mesh>();
    draco::Mesh& mesh = *owned;
    mesh.set_num_points(uint32_t(tess.vertexCount()));
    mesh.SetNumFaces(tess.triangleCount());
    for (size_t t = 0; t < tess.triangleCount(); ++t)
        mesh.SetFace(draco::FaceIndex(uint32_t(t)),
                     {draco::PointIndex(tess.indices[3 * t]), draco::PointIndex(tess.indices[3 * t + 1]),
                      draco::PointIndex(tess.indices[3 * t + 2])});
    ids.position = addAttribute(mesh, draco::GeometryAttribute::POSITION, 3, &tess.positions[0].x);
    if (tess.hasNormals()) ids.normal = addAttribute(mesh, draco::GeometryAttribute::NORMAL, 3, &tess.normals[0].x);
    if (tess.hasTangents()) ids.tangent = addAttribute(mesh, draco::GeometryAttribute::GENERIC, 4, &tess.tangents[0].x);
    if (tess.hasUvs()) ids.texcoord = addAttribute(mesh, draco::GeometryAttribute::TEX_COORD, 2, &tess.uvs[0].x);
    return owned;
}

// Decodes what we encoded: the accessors describe the decoded mesh (its point count and
// quantised bounds), and a Draco failure is caught here rather than in a viewer.
void describeDecoded(DracoEncodedMesh& encoded) {
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(encoded.bytes.data()), encoded.bytes.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) throw Error("Draco cannot decode its own output: " + decoded.status().error_msg_string());
    const draco::Mesh& mesh = *decoded.value();
    for (int id : {encoded.position, encoded.normal, encoded.tangent, encoded.texcoord})
        SUBDFIT_CHECK(id < 0 || mesh.GetAttributeByUniqueId(uint32_t(id)) != nullptr);
    const draco::PointAttribute* positions = mesh.GetAttributeByUniqueId(uint32_t(encoded.position));
    encoded.vertexCount = mesh.num_points();
    encoded.triangleCount = mesh.num_faces();
    encoded.positionMin = glm::vec3(std::numeric_limits<float>::max());
    encoded.positionMax = glm::vec3(-std::numeric_limits<float>::max());
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p) {
        glm::vec3 value;
        SUBDFIT_CHECK(positions->ConvertValue<float>(positions->mapped_index(p), 3, &value.x));
        encoded.positionMin = glm::min(encoded.positionMin, value);
        encoded.positionMax = glm::max(encoded.positionMax, value);
    }
}

}  // namespace

DracoEncodedMesh encodeDraco(const GltfMesh& tess, DracoBits bits) {
    SUBDFIT_CHECK(bits.position >= 1 && bits.position <= 30 && bits.normal >= 1 && bits.normal <= 30);
    SUBDFIT_CHECK(tess.vertexCount() > 0 && tess.triangleCount() > 0);
    SUBDFIT_CHECK(tess.attributesConsistent());
    DracoEncodedMesh encoded;
    const std::unique_ptr<draco::Mesh> mesh = toDraco(tess, encoded);

    draco::Encoder encoder;
    encoder.SetSpeedOptions(kSpeed, kSpeed);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits.position);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, bits.normal);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::GENERIC, kGenericBits);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, texcoordBits(tess.atlasSize));
    draco::EncoderBuffer buffer;
    const draco::Status status = encoder.EncodeMeshToBuffer(*mesh, &buffer);
    if (!status.ok()) throw Error("Draco could not encode the mesh: " + status.error_msg_string());
    encoded.bytes.assign(buffer.data(), buffer.data() + buffer.size());
    describeDecoded(encoded);
    return encoded;
}

}  // namespace subdfit::exporter
