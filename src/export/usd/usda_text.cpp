#include "export/usd/usda_text.h"

#include <charconv>
#include <cmath>
#include <initializer_list>

#include "util/error.h"

namespace subdfit::exporter::usda {
namespace {

template <class T>
std::string shortest(T value) {
    SUBDFIT_CHECK(std::isfinite(value));
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    SUBDFIT_CHECK(result.ec == std::errc());
    return std::string(buffer, result.ptr);
}

template <class T, class Format>
std::string joined(std::span<const T> values, Format format) {
    std::string out = "[";
    for (std::size_t k = 0; k < values.size(); ++k) {
        if (k) out += ", ";
        out += format(values[k]);
    }
    return out + "]";
}

}  // namespace

std::string number(float value) { return shortest(value); }
std::string number(double value) { return shortest(value); }
namespace {

// "(a, b, ...)", appended piece by piece (GCC 12 misreads chains of string + as overlapping
// copies, -Wrestrict).
std::string parenthesised(std::initializer_list<float> values) {
    std::string out = "(";
    for (float v : values) {
        if (out.size() > 1) out += ", ";
        out += number(v);
    }
    out += ')';
    return out;
}

}  // namespace

std::string tuple(glm::vec2 v) { return parenthesised({v.x, v.y}); }
std::string tuple(glm::vec3 v) { return parenthesised({v.x, v.y, v.z}); }
std::string tuple(glm::vec4 v) { return parenthesised({v.x, v.y, v.z, v.w}); }

std::string quoted(std::string_view text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        out += c == '\n' ? ' ' : c;
    }
    return out + "\"";
}

std::string array(std::span<const int> values) {
    return joined(values, [](int v) { return std::to_string(v); });
}
std::string array(std::span<const float> values) {
    return joined(values, [](float v) { return number(v); });
}
std::string array(std::span<const glm::vec2> values) {
    return joined(values, [](glm::vec2 v) { return tuple(v); });
}
std::string array(std::span<const glm::vec3> values) {
    return joined(values, [](glm::vec3 v) { return tuple(v); });
}

void Layer::line(std::string_view text) {
    text_.append(std::size_t(4 * depth_), ' ');
    text_ += text;
    text_ += '\n';
}

void Layer::block(std::string_view header) {
    line(header);
    line("{");
    ++depth_;
}

void Layer::end() {
    SUBDFIT_CHECK(depth_ > 0);
    --depth_;
    line("}");
}

const std::string& Layer::text() const {
    SUBDFIT_CHECK(depth_ == 0);
    return text_;
}

}  // namespace subdfit::exporter::usda
