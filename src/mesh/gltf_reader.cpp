#include "mesh/gltf_reader.h"

#include <tiny_gltf.h>

#include <cctype>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>

#include "io/input_file.h"
#include "mesh/draco_reader.h"
#include "mesh/gltf_accessors.h"
#include "mesh/gltf_file_access.h"
#include "mesh/gltf_materials.h"
#include "mesh/gltf_meshopt.h"
#include "mesh/gltf_preflight.h"
#include "mesh/input_limits.h"
#include "mesh/mesh_geometry.h"
#include "util/error.h"
#include "util/interrupt.h"
#include "util/printable.h"

namespace subdfit::mesh {

namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";

// A cage (or a reference read for its geometry) does not even decode its images.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

tinygltf::Model parseModel(const std::filesystem::path& path, bool decodeImages) {
    const std::string name = path.string();
    std::string bytes = io::readInputFile(path);
    // Binary or text by content, not by extension: a .gltf that is really a GLB still loads.
    const bool binary = bytes.size() >= 4 && std::string_view(bytes.data(), 4) == "glTF";
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".glb" && !binary) throw fileError(name, "not a GLB file (it does not start with 'glTF')");
    gltf::expandMeshopt(bytes, name);
    gltf::preflight(bytes, name);
    if (bytes.size() > UINT32_MAX) throw fileError(name, "larger than 4 GiB, which glTF cannot address");

    gltf::FileAccess files(path);
    tinygltf::TinyGLTF loader;
    if (decodeImages) loader.SetImageLoader(&gltf::keepImageBytes, nullptr);
    else loader.SetImageLoader(&skipImage, nullptr);
    loader.SetFsCallbacks(files.callbacks());
    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
    try {
        ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                                  reinterpret_cast<const unsigned char*>(bytes.data()),
                                                  unsigned(bytes.size()), files.baseDir())
                    : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), unsigned(bytes.size()),
                                                 files.baseDir());
    } catch (const std::exception& e) {
        err = e.what();  // the JSON parser may throw on some inputs
        ok = false;
    }
    throwIfStopRequested();  // a read cut short by a stop request is not a bad file
    // An image outside the folder only warns in tinygltf (it is optional to it); here it is refused.
    if (!files.refusal().empty()) throw fileError(name, files.refusal());
    if (!ok) throw fileError(name, std::string(binary ? "invalid GLB: " : "invalid glTF: ") + oneLine(err));
    return model;
}

// tinygltf 2.7 records extensionsRequired but enforces none of them, so a file whose geometry
// we would misread (e.g. meshopt-compressed buffers) must be refused here. Extensions that only
// change shading cannot change the silhouette a reference render needs.
void checkRequiredExtensions(const tinygltf::Model& model, const std::string& path) {
    for (const std::string& ext : model.extensionsRequired) {
        const bool geometryWeRead = ext == kDraco || ext == "KHR_mesh_quantization";
        const bool shadingOnly = ext.rfind("KHR_materials_", 0) == 0 || ext.rfind("KHR_texture_", 0) == 0 ||
                                 ext.rfind("EXT_texture_", 0) == 0 || ext == "KHR_lights_punctual";
        if (!geometryWeRead && !shadingOnly) throw fileError(path, "requires unsupported glTF extension " + ext);
    }
}

glm::dmat4 localTransform(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());  // column-major, as glTF
    glm::dmat4 m(1.0);
    if (node.translation.size() == 3) m = glm::translate(m, glm::make_vec3(node.translation.data()));
    if (node.rotation.size() == 4) {
        const auto& q = node.rotation;  // glTF stores x, y, z, w
        m *= glm::mat4_cast(glm::normalize(glm::dquat(q[3], q[0], q[1], q[2])));
    }
    if (node.scale.size() == 3) m = glm::scale(m, glm::make_vec3(node.scale.data()));
    return m;
}

// One mesh's triangles in its own space, decoded once however often the scene instances it.
struct MeshTriangles {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;  // a triangle list
    // With appearance: per vertex (zero / white where a primitive has none), per triangle.
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec4> colors;
    std::vector<glm::vec3> normals;  // the file's, or computed per primitive where it has none
    std::vector<int> materials;      // the glTF material, -1 for none
};

// What unfolding part of a scene costs, counting every instance; saturating, so that a DAG of
// 2^30 paths is counted without being walked.
struct UnfoldCost {
    static constexpr std::int64_t kSaturated = std::int64_t(1) << 60;
    std::int64_t nodes = 0, triangles = 0, vertices = 0;

    UnfoldCost& operator+=(const UnfoldCost& other) {
        nodes = std::min(nodes + other.nodes, kSaturated);
        triangles = std::min(triangles + other.triangles, kSaturated);
        vertices = std::min(vertices + other.vertices, kSaturated);
        return *this;
    }
};

// Collects the scene's triangles into one PolygonMesh, after checking what that will cost.
class SceneMerger {
public:
    SceneMerger(const tinygltf::Model& model, std::string path, bool appearance)
        : model_(model),
          path_(std::move(path)),
          appearance_(appearance),
          meshes_(model.meshes.size()),
          costs_(model.nodes.size()),
          visit_(model.nodes.size(), Visit::New) {
        mesh_.sourcePath = path_;
    }

    void addScene(const std::vector<int>& roots) {
        UnfoldCost total;
        for (int root : roots) total += cost(root, 0);
        checkLimits(total);
        for (int root : roots) addNode(root, glm::dmat4(1.0));
    }

    void addEveryMesh() {
        UnfoldCost total;
        for (size_t m = 0; m < model_.meshes.size(); ++m) total += meshCost(int(m));
        checkLimits(total);
        for (size_t m = 0; m < model_.meshes.size(); ++m) append(triangles(int(m)), glm::dmat4(1.0));
    }

    PolygonMesh finish() {
        if (mesh_.faceSizes.empty()) throw fileError(path_, "no triangle primitives in the scene");
        if (appearance_) finishAppearance();
        return std::move(mesh_);
    }

private:
    enum class Visit : char { New, OnPath, Done };

    void checkNode(int index) const {
        if (index < 0 || size_t(index) >= model_.nodes.size())
            throw fileError(path_, "node " + std::to_string(index) + " does not exist");
    }

    // glTF nodes form a forest, but files may share nodes between parents (a DAG) or loop.
    UnfoldCost cost(int index, int depth) {
        constexpr int kMaxDepth = 1024;  // a deeper chain would exhaust the stack
        checkNode(index);
        const size_t n = size_t(index);
        if (visit_[n] == Visit::OnPath)
            throw fileError(path_, "node " + std::to_string(index) + " is its own ancestor");
        if (visit_[n] == Visit::Done) return costs_[n];
        if (depth > kMaxDepth) throw fileError(path_, "node hierarchy deeper than " + std::to_string(kMaxDepth));
        visit_[n] = Visit::OnPath;
        const tinygltf::Node& node = model_.nodes[n];
        UnfoldCost c{.nodes = 1};
        if (node.mesh >= 0) c += meshCost(node.mesh);
        for (int child : node.children) c += cost(child, depth + 1);
        visit_[n] = Visit::Done;
        return costs_[n] = c;
    }

    UnfoldCost meshCost(int index) {
        const MeshTriangles& mesh = triangles(index);
        return {.triangles = std::int64_t(mesh.indices.size() / 3), .vertices = std::int64_t(mesh.positions.size())};
    }

    void checkLimits(const UnfoldCost& total) const {
        auto refuse = [&](const std::string& what, std::int64_t count, std::int64_t limit) {
            const std::string amount =
                count >= UnfoldCost::kSaturated ? "an astronomical number of" : std::to_string(count);
            throw fileError(path_, "the scene unfolds into " + amount + " " + what +
                                       " (counting every instance), more than " + std::to_string(limit) +
                                       ", the most subdfit takes");
        };
        if (total.nodes > kMaxNodeInstances) refuse("nodes", total.nodes, kMaxNodeInstances);
        if (total.triangles > kMaxTriangles) refuse("triangles", total.triangles, kMaxTriangles);
        if (total.vertices > kMaxVertices) refuse("vertices", total.vertices, kMaxVertices);
    }

    void addNode(int index, const glm::dmat4& parent) {
        throwIfStopRequested();
        const tinygltf::Node& node = model_.nodes[size_t(index)];
        const glm::dmat4 world = parent * localTransform(node);
        if (node.mesh >= 0) append(triangles(node.mesh), world);
        for (int child : node.children) addNode(child, world);
    }

    const MeshTriangles& triangles(int index) {
        if (index < 0 || size_t(index) >= model_.meshes.size())
            throw fileError(path_, "mesh " + std::to_string(index) + " does not exist");
        auto& cached = meshes_[size_t(index)];
        if (!cached) {
            MeshTriangles mesh;
            for (const tinygltf::Primitive& primitive : model_.meshes[size_t(index)].primitives)
                addPrimitive(primitive, mesh);
            cached = std::move(mesh);
        }
        return *cached;
    }

    void addPrimitive(const tinygltf::Primitive& primitive, MeshTriangles& mesh) {
        throwIfStopRequested();
        const int mode = primitive.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN)
            return;  // points and lines have no area to render

        std::vector<glm::vec3> positions;
        std::vector<uint32_t> indices;
        std::vector<glm::vec2> uvs;
        std::vector<glm::vec4> colors;
        std::vector<glm::vec3> normals;
        if (const auto draco = primitive.extensions.find(kDraco); draco != primitive.extensions.end()) {
            PolygonMesh decoded = decodeDraco(draco->second);
            positions = std::move(decoded.positions);
            indices.assign(decoded.faceIndices.begin(), decoded.faceIndices.end());
            uvs = std::move(decoded.uvs);
            colors = std::move(decoded.colors);
            normals = std::move(decoded.normals);
        } else {
            const auto position = primitive.attributes.find("POSITION");
            if (position == primitive.attributes.end())
                throw fileError(path_, "a triangle primitive has no POSITION attribute");
            positions = gltf::readPositions(model_, position->second, path_);
            if (primitive.indices >= 0) {
                indices = gltf::readIndices(model_, primitive.indices, path_);
            } else {
                indices.resize(positions.size());
                for (size_t i = 0; i < indices.size(); ++i) indices[i] = uint32_t(i);
            }
            if (mode != TINYGLTF_MODE_TRIANGLES) indices = triangleList(indices, mode);
            if (appearance_) {
                if (const auto a = primitive.attributes.find("TEXCOORD_0"); a != primitive.attributes.end())
                    uvs = gltf::readTexCoords(model_, a->second, path_);
                if (const auto a = primitive.attributes.find("COLOR_0"); a != primitive.attributes.end())
                    colors = gltf::readColors(model_, a->second, path_);
                if (const auto a = primitive.attributes.find("NORMAL"); a != primitive.attributes.end())
                    normals = gltf::readNormals(model_, a->second, path_);
            }
        }
        if ((!uvs.empty() && uvs.size() != positions.size()) ||
            (!colors.empty() && colors.size() != positions.size()) ||
            (!normals.empty() && normals.size() != positions.size()))
            throw fileError(path_, "a primitive's TEXCOORD_0, COLOR_0 or NORMAL has another count than its POSITION");
        if (indices.size() % 3 != 0)
            throw fileError(
                path_, "a TRIANGLES primitive has " + std::to_string(indices.size()) + " indices, not a multiple of 3");
        for (uint32_t i : indices)
            if (i >= positions.size())
                throw fileError(path_, "index " + std::to_string(i) + " is out of range (the primitive has " +
                                           std::to_string(positions.size()) + " vertices)");
        if (appearance_ && normals.empty()) splitFlat(positions, indices, uvs, colors, normals);
        const auto base = uint32_t(mesh.positions.size());
        if (std::int64_t(base) + std::int64_t(positions.size()) > kMaxVertices)
            throw fileError(path_, "a mesh has more than " + std::to_string(kMaxVertices) + " vertices");
        mesh.positions.insert(mesh.positions.end(), positions.begin(), positions.end());
        for (uint32_t i : indices) mesh.indices.push_back(base + i);
        if (appearance_) {
            hasUvs_ = hasUvs_ || !uvs.empty();
            hasColors_ = hasColors_ || !colors.empty();
            hasNormals_ = hasNormals_ || !normals.empty();
            completeNormals(positions, indices, normals);
            mesh.normals.insert(mesh.normals.end(), normals.begin(), normals.end());
            uvs.resize(positions.size(), glm::vec2(0.0f));
            colors.resize(positions.size(), glm::vec4(1.0f));
            mesh.uvs.insert(mesh.uvs.end(), uvs.begin(), uvs.end());
            mesh.colors.insert(mesh.colors.end(), colors.begin(), colors.end());
            mesh.materials.insert(mesh.materials.end(), indices.size() / 3, primitive.material);
        }
    }

    // A primitive without NORMAL is shaded flat, as glTF asks of viewers (3.7.2.1): each triangle
    // gets three vertices of its own, with its face's normal.
    static void splitFlat(std::vector<glm::vec3>& positions, std::vector<uint32_t>& indices,
                          std::vector<glm::vec2>& uvs, std::vector<glm::vec4>& colors,
                          std::vector<glm::vec3>& normals) {
        PolygonMesh primitive;
        primitive.positions = std::move(positions);
        primitive.uvs = std::move(uvs);
        primitive.colors = std::move(colors);
        primitive.faceIndices.assign(indices.begin(), indices.end());
        primitive.faceSizes.assign(indices.size() / 3, 3);
        PolygonMesh flat = flatShaded(primitive);
        positions = std::move(flat.positions);
        uvs = std::move(flat.uvs);
        colors = std::move(flat.colors);
        normals = std::move(flat.normals);
        indices.assign(flat.faceIndices.begin(), flat.faceIndices.end());
    }

    // Where a vertex has a zero NORMAL, the smooth normal of its primitive's triangles.
    static void completeNormals(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                                std::vector<glm::vec3>& normals) {
        normals.resize(positions.size(), glm::vec3(0.0f));
        std::vector<glm::vec3> computed;  // only for a primitive that needs them
        for (size_t v = 0; v < normals.size(); ++v) {
            const float length = glm::length(normals[v]);
            if (length > 0.0f) {
                normals[v] /= length;
                continue;
            }
            if (computed.empty()) {
                PolygonMesh primitive;
                primitive.positions = positions;
                primitive.faceIndices.assign(indices.begin(), indices.end());
                primitive.faceSizes.assign(indices.size() / 3, 3);
                computed = vertexNormals(primitive);
            }
            normals[v] = computed[v];
        }
    }

    PolygonMesh decodeDraco(const tinygltf::Value& extension) {
        const tinygltf::Value& view = extension.Get("bufferView");
        const tinygltf::Value& position = extension.Get("attributes").Get("POSITION");
        if (!view.IsNumber() || !position.IsNumber())
            throw fileError(path_, std::string(kDraco) + " without bufferView or attributes.POSITION");
        const std::string_view bytes = gltf::bufferViewBytes(model_, view.GetNumberAsInt(), path_);
        DracoAttributeIds ids{.position = position.GetNumberAsInt()};
        if (appearance_) {
            const tinygltf::Value& texCoord = extension.Get("attributes").Get("TEXCOORD_0");
            const tinygltf::Value& color = extension.Get("attributes").Get("COLOR_0");
            if (texCoord.IsNumber()) ids.texCoord = texCoord.GetNumberAsInt();
            if (color.IsNumber()) ids.color = color.GetNumberAsInt();
            const tinygltf::Value& normal = extension.Get("attributes").Get("NORMAL");
            if (normal.IsNumber()) ids.normal = normal.GetNumberAsInt();
        }
        return decodeDracoMesh(bytes.data(), bytes.size(), path_, ids);
    }

    // Strips and fans as a plain list, keeping glTF's winding (spec 3.7.2.1).
    static std::vector<uint32_t> triangleList(const std::vector<uint32_t>& v, int mode) {
        std::vector<uint32_t> list;
        for (size_t i = 0; i + 2 < v.size(); ++i) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
                list.insert(list.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
            else list.insert(list.end(), {v[0], v[i + 1], v[i + 2]});
        }
        return list;
    }

    void append(const MeshTriangles& triangles, const glm::dmat4& transform) {
        const size_t base = mesh_.positions.size();
        for (const glm::vec3& p : triangles.positions) {
            const glm::vec3 q(transform * glm::dvec4(p, 1.0));
            if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
                throw fileError(path_, "a node transform makes a position non-finite");
            mesh_.positions.push_back(q);
        }
        // A mirroring transform turns triangles inside out; swap two corners to undo it.
        const bool mirrored = glm::determinant(transform) < 0.0;
        const auto& v = triangles.indices;
        for (size_t t = 0; t < v.size(); t += 3) {
            const int a = int(base + v[t]), b = int(base + v[t + 1]), c = int(base + v[t + 2]);
            mesh_.faceIndices.insert(mesh_.faceIndices.end(), {a, mirrored ? c : b, mirrored ? b : c});
            mesh_.faceSizes.push_back(3);
        }
        if (appearance_) {
            // Normals transform by the inverse transpose, which also keeps them outward on the
            // triangles a mirroring transform turned round above.
            const glm::dmat3 normalTransform = glm::transpose(glm::inverse(glm::dmat3(transform)));
            for (const glm::vec3& n : triangles.normals) {
                const glm::dvec3 m = normalTransform * glm::dvec3(n);
                const double length = glm::length(m);
                mesh_.normals.push_back(length > 0.0 && std::isfinite(length) ? glm::vec3(m / length) : n);
            }
            mesh_.uvs.insert(mesh_.uvs.end(), triangles.uvs.begin(), triangles.uvs.end());
            mesh_.colors.insert(mesh_.colors.end(), triangles.colors.begin(), triangles.colors.end());
            mesh_.faceMaterials.insert(mesh_.faceMaterials.end(), triangles.materials.begin(),
                                       triangles.materials.end());
        }
    }

    // The materials of the file, a default one for primitives without (glTF's, spec 3.9.6), or,
    // for a file with vertex colours and no materials at all, one plain material (not metallic)
    // that shows them: what a scan's exporter means by colours without a material.
    void finishAppearance() {
        if (!hasUvs_) mesh_.uvs.clear();
        if (!hasColors_) mesh_.colors.clear();
        if (!hasNormals_) mesh_.normals.clear();
        if (model_.materials.empty() && !hasColors_) {
            mesh_.faceMaterials.clear();
            return;
        }
        auto set = std::make_shared<MaterialSet>(gltf::readMaterials(model_, path_));
        int fallback = -1;
        for (int& m : mesh_.faceMaterials) {
            if (m >= 0 && size_t(m) < set->materials.size()) continue;
            if (m >= 0)
                throw fileError(path_, "a primitive names material " + std::to_string(m) + ", which does not exist");
            if (fallback < 0) {
                Material plain = defaultMaterial();
                if (model_.materials.empty()) plain.metallicFactor = 0.0f;
                fallback = int(set->materials.size());
                set->materials.push_back(plain);
            }
            m = fallback;
        }
        mesh_.materials = std::move(set);
    }

    const tinygltf::Model& model_;
    std::string path_;
    bool appearance_;
    bool hasUvs_ = false, hasColors_ = false, hasNormals_ = false;
    std::vector<std::optional<MeshTriangles>> meshes_;
    std::vector<UnfoldCost> costs_;
    std::vector<Visit> visit_;
    PolygonMesh mesh_;
};

}  // namespace

PolygonMesh readGltf(const std::filesystem::path& path, MeshContent content) {
    const std::string name = path.string();
    const bool appearance = content == MeshContent::WithAppearance;
    const tinygltf::Model model = parseModel(path, appearance);
    checkRequiredExtensions(model, name);

    SceneMerger merger(model, name, appearance);
    if (model.scenes.empty()) {
        merger.addEveryMesh();
    } else {
        const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
        if (size_t(scene) >= model.scenes.size())
            throw fileError(name, "default scene " + std::to_string(scene) + " does not exist");
        merger.addScene(model.scenes[size_t(scene)].nodes);
    }
    return merger.finish();
}

}  // namespace subdfit::mesh
