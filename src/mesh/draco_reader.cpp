#include "mesh/draco_reader.h"

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>

#include <cmath>

#include "io/input_file.h"
#include "mesh/input_limits.h"
#include "util/error.h"

namespace subdfit::mesh {

namespace {

const draco::PointAttribute* positionAttribute(const draco::Mesh& mesh, int uniqueId, const std::string& path) {
    const draco::PointAttribute* attribute = uniqueId >= 0 ? mesh.GetAttributeByUniqueId(uint32_t(uniqueId))
                                                           : mesh.GetNamedAttribute(draco::GeometryAttribute::POSITION);
    if (!attribute)
        throw fileError(path, uniqueId >= 0 ? "Draco mesh has no attribute with id " + std::to_string(uniqueId)
                                            : std::string("Draco mesh has no POSITION attribute"));
    if (attribute->num_components() != 3)
        throw fileError(path, "Draco position attribute has " + std::to_string(int(attribute->num_components())) +
                                  " components, needs 3");
    return attribute;
}

// A per-point attribute of N float components (texture coordinates, colours).
template <int N>
std::vector<glm::vec<N, float>> pointValues(const draco::Mesh& mesh, int uniqueId, glm::vec<N, float> fill,
                                            const std::string& path, const char* what) {
    const draco::PointAttribute* attribute = mesh.GetAttributeByUniqueId(uint32_t(uniqueId));
    if (!attribute)
        throw fileError(path,
                        std::string("Draco mesh has no ") + what + " attribute with id " + std::to_string(uniqueId));
    const int components = attribute->num_components();
    if (components < 2 || components > N)
        throw fileError(path,
                        std::string("Draco ") + what + " attribute has " + std::to_string(components) + " components");
    std::vector<glm::vec<N, float>> values(mesh.num_points(), fill);
    for (draco::PointIndex p(0); p < mesh.num_points(); ++p) {
        float v[N];
        for (int c = 0; c < N; ++c) v[c] = fill[c];  // what the attribute has fewer components for
        if (!attribute->ConvertValue<float>(attribute->mapped_index(p), int8_t(components), v))
            throw fileError(path, std::string("Draco ") + what + " cannot be converted to float");
        for (int c = 0; c < N; ++c) {
            if (!std::isfinite(v[c]))
                throw fileError(path,
                                std::string("non-finite Draco ") + what + " at point " + std::to_string(p.value()));
            values[p.value()][c] = v[c];
        }
    }
    return values;
}

}  // namespace

PolygonMesh decodeDracoMesh(const char* data, size_t size, const std::string& pathForErrors,
                            const DracoAttributeIds& ids) {
    const int positionUniqueId = ids.position;
    const std::string& path = pathForErrors;
    draco::DecoderBuffer buffer;
    buffer.Init(data, size);

    auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
    if (!type.ok()) throw fileError(path, "not Draco data: " + type.status().error_msg_string());
    if (type.value() != draco::TRIANGULAR_MESH)
        throw fileError(path, "Draco data is a point cloud, not a triangle mesh");

    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) throw fileError(path, "corrupt Draco mesh: " + decoded.status().error_msg_string());
    const draco::Mesh& dracoMesh = *decoded.value();

    if (std::int64_t(dracoMesh.num_points()) > kMaxVertices || std::int64_t(dracoMesh.num_faces()) > kMaxTriangles)
        throw fileError(path, "Draco mesh of " + std::to_string(dracoMesh.num_points()) + " points and " +
                                  std::to_string(dracoMesh.num_faces()) + " faces, more than subdfit takes");
    const draco::PointAttribute* positions = positionAttribute(dracoMesh, positionUniqueId, path);
    PolygonMesh mesh;
    mesh.sourcePath = path;
    mesh.positions.resize(dracoMesh.num_points());
    for (draco::PointIndex p(0); p < dracoMesh.num_points(); ++p) {
        glm::vec3& out = mesh.positions[p.value()];
        if (!positions->ConvertValue<float>(positions->mapped_index(p), 3, &out[0]))
            throw fileError(path, "Draco positions cannot be converted to float");
        if (!std::isfinite(out.x) || !std::isfinite(out.y) || !std::isfinite(out.z))
            throw fileError(path, "non-finite Draco position at point " + std::to_string(p.value()));
    }

    mesh.faceSizes.assign(dracoMesh.num_faces(), 3);
    mesh.faceIndices.reserve(size_t(dracoMesh.num_faces()) * 3);
    for (draco::FaceIndex f(0); f < dracoMesh.num_faces(); ++f)
        for (const draco::PointIndex& p : dracoMesh.face(f)) {
            if (p.value() >= dracoMesh.num_points())
                throw fileError(path, "Draco face " + std::to_string(f.value()) + " names a missing point");
            mesh.faceIndices.push_back(int(p.value()));
        }
    if (ids.texCoord >= 0)
        mesh.uvs = pointValues<2>(dracoMesh, ids.texCoord, glm::vec2(0.0f), path, "texture coordinate");
    if (ids.color >= 0) mesh.colors = pointValues<4>(dracoMesh, ids.color, glm::vec4(1.0f), path, "colour");
    if (ids.normal >= 0) mesh.normals = pointValues<3>(dracoMesh, ids.normal, glm::vec3(0.0f), path, "normal");
    return mesh;
}

PolygonMesh readDraco(const std::filesystem::path& path) {
    const std::string bytes = io::readInputFile(path);
    return decodeDracoMesh(bytes.data(), bytes.size(), path.string());
}

}  // namespace subdfit::mesh
