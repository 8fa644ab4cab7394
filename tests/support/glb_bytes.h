#pragma once
// A GLB container around a JSON document and a binary chunk, for tests and fuzz targets that
// craft glTF files byte by byte (meshopt views with hostile sizes).
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace subdfit::test {

inline void appendU32(std::string& out, std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); }

inline std::string glb(const nlohmann::json& doc, std::string bin) {
    std::string text = doc.dump();
    text.append((4 - text.size() % 4) % 4, ' ');
    bin.append((4 - bin.size() % 4) % 4, '\0');
    std::string out = "glTF";
    appendU32(out, 2);
    appendU32(out, std::uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    appendU32(out, std::uint32_t(text.size()));
    appendU32(out, 0x4E4F534A);  // JSON
    out += text;
    appendU32(out, std::uint32_t(bin.size()));
    appendU32(out, 0x004E4942);  // BIN
    out += bin;
    return out;
}

}  // namespace subdfit::test
