#include "mesh/gltf_accessors.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mesh/input_limits.h"
#include "util/checked_size.h"
#include "util/error.h"

namespace subdfit::mesh::gltf {

namespace {

// An accessor resolved to raw memory: element i starts at data + i * stride. `data` is null
// for an accessor without a buffer view, whose elements are all zero (glTF 2.0, 3.6.2.1).
struct ElementSpan {
    const unsigned char* data = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int componentType = 0;
    size_t components = 0;
    bool normalized = false;
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

ElementSpan resolve(const tinygltf::Model& model, int index, int expectedType, const std::string& path) {
    const std::string name = "accessor " + std::to_string(index);
    if (index < 0 || size_t(index) >= model.accessors.size())
        throw fileError(path, name + " does not exist (" + std::to_string(model.accessors.size()) + " accessors)");
    const tinygltf::Accessor& accessor = model.accessors[size_t(index)];
    if (accessor.sparse.isSparse) throw fileError(path, name + ": sparse accessors are not supported");
    const bool colorType = expectedType == TINYGLTF_TYPE_VEC4 && accessor.type == TINYGLTF_TYPE_VEC3;  // COLOR_0
    if (accessor.type != expectedType && !colorType)
        throw fileError(path, name + " has type " + std::to_string(accessor.type) + ", expected " + typeName(expectedType));
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
    // Without a buffer view every element is zero (sparse accessors are refused above): nothing a
    // file needs many of, and a few bytes of JSON must not allocate gigabytes of zeros.
    constexpr size_t kMostZeroElements = size_t(1) << 16;
    if (accessor.bufferView < 0) {
        if (span.count > kMostZeroElements)
            throw fileError(path, name + " has no buffer view and " + std::to_string(span.count) +
                                      " elements (all zero), more than " + std::to_string(kMostZeroElements));
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
                                  ") runs past the end of buffer view " +
                                  std::to_string(accessor.bufferView) + " (" + std::to_string(view.size()) +
                                  " bytes)");
    span.data = reinterpret_cast<const unsigned char*>(view.data()) + offset;
    return span;
}

template <typename T>
T load(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof value);  // buffer data need not be aligned
    return value;
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
    if (!span.data) return values;
    const size_t size = componentSize(span.componentType);
    for (size_t i = 0; i < span.count; ++i) {
        const unsigned char* element = span.data + i * span.stride;
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
    const bool unsignedInteger = t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
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
    if (!span.data) return values;
    const size_t size = componentSize(t);
    for (size_t i = 0; i < span.count; ++i) {
        const unsigned char* element = span.data + i * span.stride;
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
    if (!span.data) return indices;
    for (size_t i = 0; i < span.count; ++i) {
        const unsigned char* p = span.data + i * span.stride;
        indices[i] = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? load<uint8_t>(p)
                     : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? load<uint16_t>(p)
                                                                      : load<uint32_t>(p);
    }
    return indices;
}

}  // namespace subdfit::mesh::gltf
