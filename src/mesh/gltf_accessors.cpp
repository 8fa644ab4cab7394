#include "mesh/gltf_accessors.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mesh/input_limits.h"
#include "util/checked_size.h"
#include "util/error.h"

namespace subdfit::mesh::gltf {

namespace {

// An accessor resolved to raw memory: element i starts at data + i * stride, or for a sparse
// accessor wherever `sparse` says. `data` is null for an accessor without a buffer view, whose
// elements are zero (glTF 2.0, 3.6.2.1) unless sparse values replace some.
struct ElementSpan {
    const unsigned char* data = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int componentType = 0;
    size_t components = 0;
    bool normalized = false;
    std::vector<const unsigned char*> sparse;  // every element's bytes, for a sparse accessor

    bool allZero() const { return !data && sparse.empty(); }
    const unsigned char* element(size_t i) const { return sparse.empty() ? data + i * stride : sparse[i]; }
};

const char* typeName(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return "SCALAR";
        case TINYGLTF_TYPE_VEC2: return "VEC2";
        case TINYGLTF_TYPE_VEC3: return "VEC3";
        default: return "VEC3 or VEC4";
    }
}

size_t componentSize(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;  // INT and DOUBLE are not valid glTF 2.0 accessor types
    }
}

template <typename T>
T load(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof value);  // buffer data need not be aligned
    return value;
}

// `bytes` bytes at `offset` in buffer view `view`, checked.
const unsigned char* viewRange(const tinygltf::Model& model, int view, int offset, size_t bytes,
                               const std::string& path, const std::string& what) {
    const std::string_view range = bufferViewBytes(model, view, path);
    if (offset < 0 || size_t(offset) > range.size() || bytes > range.size() - size_t(offset))
        throw fileError(path, what + " (" + std::to_string(bytes) + " bytes at offset " + std::to_string(offset) +
                                  ") run past the end of buffer view " + std::to_string(view));
    return reinterpret_cast<const unsigned char*>(range.data()) + offset;
}

// A sparse accessor's substitutions (glTF 2.0, 3.6.2.3): `count` indices, strictly increasing
// and below the accessor's count, and as many tightly packed elements that replace those.
void substituteSparse(const tinygltf::Model& model, const tinygltf::Accessor& accessor, size_t elementSize,
                      ElementSpan& span, const std::string& path, const std::string& name) {
    static constexpr unsigned char kZero[16] = {};  // the largest element read here: a float VEC4
    const auto& sparse = accessor.sparse;
    if (sparse.count < 1 || size_t(sparse.count) > span.count)
        throw fileError(path, name + ": " + std::to_string(sparse.count) + " sparse values, where 1 to " +
                                  std::to_string(span.count) + " may be");
    const size_t n = size_t(sparse.count);
    const int indexType = sparse.indices.componentType;
    const size_t indexSize = indexType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                             : indexType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                             : indexType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                                   : 0;
    if (indexSize == 0) throw fileError(path, name + ": sparse indices must be unsigned byte, short or int");
    const unsigned char* indices = viewRange(model, sparse.indices.bufferView, sparse.indices.byteOffset, n * indexSize,
                                             path, name + "'s sparse indices");
    const unsigned char* values = viewRange(model, sparse.values.bufferView, sparse.values.byteOffset, n * elementSize,
                                            path, name + "'s sparse values");
    span.sparse.resize(span.count);
    for (size_t i = 0; i < span.count; ++i) span.sparse[i] = span.data ? span.data + i * span.stride : kZero;
    for (size_t k = 0, next = 0; k < n; ++k) {
        const unsigned char* p = indices + k * indexSize;
        const std::uint32_t i = indexSize == 1 ? *p : indexSize == 2 ? load<std::uint16_t>(p) : load<std::uint32_t>(p);
        if (i < next || i >= span.count)
            throw fileError(path, name + ": sparse index " + std::to_string(i) + " is " +
                                      (i >= span.count ? "past its " + std::to_string(span.count) + " elements"
                                                       : "not above the one before it"));
        next = size_t(i) + 1;
        span.sparse[i] = values + k * elementSize;
    }
}

ElementSpan resolve(const tinygltf::Model& model, int index, int expectedType, const std::string& path) {
    const std::string name = "accessor " + std::to_string(index);
    if (index < 0 || size_t(index) >= model.accessors.size())
        throw fileError(path, name + " does not exist (" + std::to_string(model.accessors.size()) + " accessors)");
    const tinygltf::Accessor& accessor = model.accessors[size_t(index)];
    const bool colorType = expectedType == TINYGLTF_TYPE_VEC4 && accessor.type == TINYGLTF_TYPE_VEC3;  // COLOR_0
    if (accessor.type != expectedType && !colorType)
        throw fileError(path,
                        name + " has type " + std::to_string(accessor.type) + ", expected " + typeName(expectedType));
    const size_t components = size_t(tinygltf::GetNumComponentsInType(uint32_t(accessor.type)));
    const size_t elementSize = components * componentSize(accessor.componentType);
    if (elementSize == 0)
        throw fileError(path, name + " has unsupported componentType " + std::to_string(accessor.componentType));

    if (accessor.count > size_t(kMaxVertices))
        throw fileError(path, name + " has " + std::to_string(accessor.count) + " elements, more than " +
                                  std::to_string(kMaxVertices) + ", the most subdfit reads");
    ElementSpan span;
    span.count = accessor.count;
    span.componentType = accessor.componentType;
    span.components = components;
    span.normalized = accessor.normalized;
    span.stride = elementSize;
    if (span.count == 0) return span;
    // Without a buffer view every element is zero but those sparse values replace: nothing a
    // file needs many of, and a few bytes of JSON must not allocate gigabytes of zeros.
    constexpr size_t kMostZeroElements = size_t(1) << 16;
    if (accessor.bufferView < 0) {
        if (span.count > kMostZeroElements)
            throw fileError(path, name + " has no buffer view and " + std::to_string(span.count) +
                                      " elements (zero), more than " + std::to_string(kMostZeroElements));
        if (accessor.sparse.isSparse) substituteSparse(model, accessor, elementSize, span, path, name);
        return span;
    }

    const std::string_view view = bufferViewBytes(model, accessor.bufferView, path);
    const size_t declaredStride = model.bufferViews[size_t(accessor.bufferView)].byteStride;
    if (declaredStride != 0) {
        if (declaredStride < elementSize)
            throw fileError(path, name + ": byteStride " + std::to_string(declaredStride) +
                                      " is smaller than its element (" + std::to_string(elementSize) + " bytes)");
        span.stride = declaredStride;
    }
    const size_t offset = accessor.byteOffset;
    const bool fits = offset <= view.size() && elementSize <= view.size() - offset &&
                      !productExceeds(span.count - 1, span.stride, view.size() - offset - elementSize);
    if (!fits)
        throw fileError(path, name + " (" + std::to_string(span.count) + " elements at offset " +
                                  std::to_string(offset) + ", stride " + std::to_string(span.stride) +
                                  ") runs past the end of buffer view " + std::to_string(accessor.bufferView) + " (" +
                                  std::to_string(view.size()) + " bytes)");
    span.data = reinterpret_cast<const unsigned char*>(view.data()) + offset;
    if (accessor.sparse.isSparse) substituteSparse(model, accessor, elementSize, span, path, name);
    return span;
}

// One VEC3 component; integer encodings follow KHR_mesh_quantization's normalisation.
float component(const unsigned char* p, int type, bool normalized) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const float v = load<int8_t>(p);
            return normalized ? std::max(v / 127.0f, -1.0f) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            const float v = load<uint8_t>(p);
            return normalized ? v / 255.0f : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const float v = load<int16_t>(p);
            return normalized ? std::max(v / 32767.0f, -1.0f) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const float v = load<uint16_t>(p);
            return normalized ? v / 65535.0f : v;
        }
        default: return load<float>(p);  // readVec3 admits no other type
    }
}

}  // namespace

std::string_view bufferViewBytes(const tinygltf::Model& model, int index, const std::string& path) {
    const std::string name = "buffer view " + std::to_string(index);
    if (index < 0 || size_t(index) >= model.bufferViews.size())
        throw fileError(path, name + " does not exist (" + std::to_string(model.bufferViews.size()) + " buffer views)");
    const tinygltf::BufferView& view = model.bufferViews[size_t(index)];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
        throw fileError(path, name + " names buffer " + std::to_string(view.buffer) + ", which does not exist");
    const std::vector<unsigned char>& data = model.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
        throw fileError(path, name + " (" + std::to_string(view.byteLength) + " bytes at offset " +
                                  std::to_string(view.byteOffset) + ") runs past the end of buffer " +
                                  std::to_string(view.buffer) + " (" + std::to_string(data.size()) + " bytes)");
    return {reinterpret_cast<const char*>(data.data()) + view.byteOffset, view.byteLength};
}

namespace {

// A VEC3 attribute (POSITION, NORMAL): float, or (KHR_mesh_quantization) 8/16-bit integers.
std::vector<glm::vec3> readVec3(const tinygltf::Model& model, int accessor, const std::string& path, const char* what) {
    const ElementSpan span = resolve(model, accessor, TINYGLTF_TYPE_VEC3, path);
    if (span.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        throw fileError(path, "accessor " + std::to_string(accessor) + ": " + what + "s cannot be UNSIGNED_INT");
    std::vector<glm::vec3> values(span.count, glm::vec3(0.0f));
    if (span.allZero()) return values;
    const size_t size = componentSize(span.componentType);
    for (size_t i = 0; i < span.count; ++i) {
        const unsigned char* element = span.element(i);
        for (int c = 0; c < 3; ++c) {
            const float v = component(element + size_t(c) * size, span.componentType, span.normalized);
            if (!std::isfinite(v))
                throw fileError(path, "accessor " + std::to_string(accessor) + ": non-finite " + what + " at vertex " +
                                          std::to_string(i));
            values[i][c] = v;
        }
    }
    return values;
}

}  // namespace

std::vector<glm::vec3> readPositions(const tinygltf::Model& model, int accessor, const std::string& path) {
    return readVec3(model, accessor, path, "position");
}

std::vector<glm::vec3> readNormals(const tinygltf::Model& model, int accessor, const std::string& path) {
    return readVec3(model, accessor, path, "normal");
}

namespace {

// Texture coordinates and colours: float, or normalized unsigned byte / short (spec 3.7.2.1);
// texture coordinates also (KHR_mesh_quantization) signed, and not normalized (gltfpack's -vt
// writes them so, scaled back by the texture transform).
template <int N>
std::vector<glm::vec<N, float>> readNormalizedAttribute(const tinygltf::Model& model, int accessor, int type,
                                                        const std::string& path, const char* what, bool quantized) {
    const ElementSpan span = resolve(model, accessor, type, path);
    const int t = span.componentType;
    const bool unsignedInteger =
        t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    const bool signedInteger = t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_SHORT;
    const bool allowed = t == TINYGLTF_COMPONENT_TYPE_FLOAT || (span.normalized && unsignedInteger) ||
                         (quantized && (unsignedInteger || signedInteger));
    if (!allowed)
        throw fileError(path, "accessor " + std::to_string(accessor) + ": " + what +
                                  (quantized ? " must be float or (un)signed byte or short"
                                             : " must be float or normalized unsigned byte or short"));
    glm::vec<N, float> fill(0.0f);
    if constexpr (N == 4) fill.w = 1.0f;  // a VEC3 colour is opaque
    std::vector<glm::vec<N, float>> values(span.count, fill);
    if (span.allZero()) return values;
    const size_t size = componentSize(t);
    for (size_t i = 0; i < span.count; ++i) {
        const unsigned char* element = span.element(i);
        for (size_t c = 0; c < span.components; ++c) {
            const float v = component(element + c * size, t, span.normalized);
            if (!std::isfinite(v))
                throw fileError(path, "accessor " + std::to_string(accessor) + ": non-finite " + what + " at vertex " +
                                          std::to_string(i));
            values[i][int(c)] = v;
        }
    }
    return values;
}

}  // namespace

std::vector<glm::vec2> readTexCoords(const tinygltf::Model& model, int accessor, const std::string& path) {
    return readNormalizedAttribute<2>(model, accessor, TINYGLTF_TYPE_VEC2, path, "texture coordinates", true);
}

std::vector<glm::vec4> readColors(const tinygltf::Model& model, int accessor, const std::string& path) {
    return readNormalizedAttribute<4>(model, accessor, TINYGLTF_TYPE_VEC4, path, "colours", false);
}

std::vector<uint32_t> readIndices(const tinygltf::Model& model, int accessor, const std::string& path) {
    const ElementSpan span = resolve(model, accessor, TINYGLTF_TYPE_SCALAR, path);
    const int type = span.componentType;
    if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        throw fileError(path, "accessor " + std::to_string(accessor) + ": indices must be unsigned byte, short or int");
    std::vector<uint32_t> indices(span.count, 0u);
    if (span.allZero()) return indices;
    for (size_t i = 0; i < span.count; ++i) {
        const unsigned char* p = span.element(i);
        indices[i] = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? load<uint8_t>(p)
                     : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? load<uint16_t>(p)
                                                                      : load<uint32_t>(p);
    }
    return indices;
}

}  // namespace subdfit::mesh::gltf
