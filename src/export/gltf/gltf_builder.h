#pragma once
// What every GLB writer of subdfit builds a document with: buffers[0] and its buffer views, and
// accessors (glTF 2.0 spec 5.1, 5.11).
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace subdfit::exporter::gltf {

// glTF enums (spec 5.1.1, 5.25).
inline constexpr int kByte = 5120, kUnsignedShort = 5123, kFloat = 5126, kUnsignedInt = 5125;
inline constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
inline constexpr int kNearest = 9728, kLinear = 9729, kLinearMipmapLinear = 9987;
inline constexpr int kRepeat = 10497, kClampToEdge = 33071, kMirroredRepeat = 33648;
inline constexpr int kTriangles = 4;
inline constexpr const char* kDraco = "KHR_draco_mesh_compression";
inline constexpr const char* kMeshopt = "EXT_meshopt_compression";
inline constexpr const char* kQuantization = "KHR_mesh_quantization";

// buffers[0] and its bufferViews, each view starting 4-byte aligned (glTF requires accessor
// offsets to be multiples of the component size; ours are all 4 bytes).
class BinaryBuilder {
public:
    // `byteStride` 0: none (tightly packed, or not vertex data).
    int addView(std::span<const unsigned char> bytes, int target = 0, int byteStride = 0) {
        data_.resize((data_.size() + 3) & ~size_t(3), 0);
        nlohmann::json view = {{"buffer", 0}, {"byteOffset", data_.size()}, {"byteLength", bytes.size()}};
        if (byteStride) view["byteStride"] = byteStride;
        if (target) view["target"] = target;
        data_.insert(data_.end(), bytes.begin(), bytes.end());
        views_.push_back(std::move(view));
        return int(views_.size()) - 1;
    }

    template <typename T>
    int addArray(const std::vector<T>& values, int target) {
        return addView({reinterpret_cast<const unsigned char*>(values.data()), values.size() * sizeof(T)}, target);
    }

    // An EXT_meshopt_compression view: `compressed` goes into buffers[0]; the view itself lies in
    // the fallback buffer (buffers[1], no data: the extension is required), `count` elements of
    // `stride` bytes, `mode` ATTRIBUTES or TRIANGLES, `filter` (if any) the one its decoder undoes.
    int addMeshoptView(std::span<const unsigned char> compressed, std::size_t count, int stride, const char* mode,
                       int target, const char* filter = nullptr) {
        data_.resize((data_.size() + 3) & ~size_t(3), 0);
        const std::size_t length = count * std::size_t(stride);
        nlohmann::json view = {{"buffer", 1}, {"byteOffset", fallbackBytes_}, {"byteLength", length}};
        if (mode == std::string_view("ATTRIBUTES")) view["byteStride"] = stride;
        if (target) view["target"] = target;
        view["extensions"]["EXT_meshopt_compression"] = {{"buffer", 0},
                                                         {"byteOffset", data_.size()},
                                                         {"byteLength", compressed.size()},
                                                         {"byteStride", stride},
                                                         {"count", count},
                                                         {"mode", mode}};
        if (filter) view["extensions"]["EXT_meshopt_compression"]["filter"] = filter;
        data_.insert(data_.end(), compressed.begin(), compressed.end());
        fallbackBytes_ += (length + 3) & ~std::size_t(3);
        views_.push_back(std::move(view));
        return int(views_.size()) - 1;
    }

    const std::vector<unsigned char>& data() const { return data_; }
    const nlohmann::json& views() const { return views_; }
    // The buffers the views lie in: buffers[0] (the GLB's binary chunk), and the fallback buffer
    // of meshopt-compressed views when there are any.
    nlohmann::json buffers() const {
        nlohmann::json buffers = nlohmann::json::array({{{"byteLength", data_.size()}}});
        if (fallbackBytes_ > 0)
            buffers.push_back(
                {{"byteLength", fallbackBytes_}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
        return buffers;
    }

private:
    std::vector<unsigned char> data_;
    nlohmann::json views_ = nlohmann::json::array();
    std::size_t fallbackBytes_ = 0;
};

inline nlohmann::json accessor(int view, int componentType, size_t count, const char* type) {
    nlohmann::json a = {{"componentType", componentType}, {"count", count}, {"type", type}};
    if (view >= 0) a["bufferView"] = view;  // a Draco-compressed accessor has none (KHR spec)
    return a;
}

inline nlohmann::json vec3Json(const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

}  // namespace subdfit::exporter::gltf
