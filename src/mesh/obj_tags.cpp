#include "mesh/obj_tags.h"

#include <algorithm>
#include <cstdint>
#include <charconv>

namespace subdfit::mesh::obj {

namespace {

// The values of one tag line, split by the declared counts.
struct TagValues {
    std::string name;
    std::vector<int64_t> ints;
    std::vector<float> floats;
    std::vector<std::string_view> strings;
};

int64_t parseCount(std::string_view text, const LineContext& at, const std::string& name, std::string_view counts) {
    int64_t n = 0;
    if (!parseInt(text, n) || n < 0)
        at.fail("t " + name + ": bad value counts " + quoted(counts) + " (expected nInts/nFloats/nStrings)");
    return n;
}

TagValues splitTagLine(std::string_view line, const LineContext& at) {
    Tokens tokens(line);
    tokens.next();  // "t"
    TagValues tag;
    tag.name = std::string(tokens.next());
    if (tag.name.empty()) at.fail("t line without a tag name");

    const std::string_view counts = tokens.next();
    const size_t slash1 = counts.find('/');
    const size_t slash2 = slash1 == std::string_view::npos ? slash1 : counts.find('/', slash1 + 1);
    if (slash2 == std::string_view::npos)
        at.fail("t " + tag.name + ": bad value counts " + quoted(counts) + " (expected nInts/nFloats/nStrings)");
    const int64_t nInts = parseCount(counts.substr(0, slash1), at, tag.name, counts);
    const int64_t nFloats = parseCount(counts.substr(slash1 + 1, slash2 - slash1 - 1), at, tag.name, counts);
    const int64_t nStrings = parseCount(counts.substr(slash2 + 1), at, tag.name, counts);

    std::vector<std::string_view> values;
    for (std::string_view v = tokens.next(); !v.empty(); v = tokens.next()) values.push_back(v);
    // Checked before anything is sized by the counts, so an absurd count costs nothing; each
    // count is compared with the line on its own first, so their sum cannot overflow.
    const auto have = int64_t(values.size());
    if (nInts > have || nFloats > have || nStrings > have || nInts + nFloats + nStrings != have)
        at.fail("t " + tag.name + " declares " + std::to_string(nInts) + "/" + std::to_string(nFloats) + "/" +
                std::to_string(nStrings) + " values but the line has " + std::to_string(have));

    size_t i = 0;
    for (; i < size_t(nInts); ++i) {
        int64_t n = 0;
        if (!parseInt(values[i], n)) at.fail("t " + tag.name + ": bad integer " + quoted(values[i]));
        tag.ints.push_back(n);
    }
    for (; i < size_t(nInts + nFloats); ++i) {
        float f = 0;
        if (!parseFloat(values[i], f) || !std::isfinite(f))
            at.fail("t " + tag.name + ": bad number " + quoted(values[i]));
        tag.floats.push_back(f);
    }
    for (; i < values.size(); ++i) tag.strings.push_back(values[i]);
    return tag;
}

void expect(bool ok, const LineContext& at, const TagValues& tag, const char* shape) {
    if (!ok) at.fail("t " + tag.name + " expects " + shape);
}

float sharpness(float s, const LineContext& at, const TagValues& tag) {
    if (s < 0.0f) at.fail("t " + tag.name + ": negative sharpness " + std::to_string(s));
    return s;
}

int singleChoice(const TagValues& tag, const LineContext& at, int64_t maxValue, const char* shape) {
    expect(tag.ints.size() == 1 && tag.floats.empty() && tag.strings.empty(), at, tag, shape);
    if (tag.ints[0] < 0 || tag.ints[0] > maxValue)
        at.fail("t " + tag.name + ": value " + std::to_string(tag.ints[0]) + " is not in 0.." +
                std::to_string(maxValue));
    return int(tag.ints[0]);
}

std::string_view singleWord(const TagValues& tag, const LineContext& at, const char* shape) {
    expect(tag.ints.empty() && tag.floats.empty() && tag.strings.size() == 1, at, tag, shape);
    return tag.strings[0];
}

// Trailing blanks and a CR from Windows line endings are not part of a passthrough line.
std::string_view trimmed(std::string_view line) {
    while (!line.empty() && isSpace(line.back())) line.remove_suffix(1);
    while (!line.empty() && isSpace(line.front())) line.remove_prefix(1);
    return line;
}

// A space and the shortest text that reads back as the same float.
void appendFloat(std::string& out, float f) {
    char buf[32];
    const auto result = std::to_chars(buf, buf + sizeof buf, f);
    out += ' ';
    out.append(buf, result.ptr);
}

}  // namespace

void parseTagLine(std::string_view line, const LineContext& at, SubdivisionTags& tags,
                  std::vector<TagIndexUse>& indexUses) {
    const TagValues tag = splitTagLine(line, at);
    auto useVertex = [&](int64_t v) {
        indexUses.push_back({TagIndexUse::Kind::Vertex, v, at.line, tag.name});
        return int(std::clamp<int64_t>(v, -1, INT32_MAX));
    };

    if (tag.name == "crease") {
        // Vertex pairs, with one sharpness for all of them or one per pair.
        const size_t pairs = tag.ints.size() / 2;
        expect(pairs >= 1 && tag.ints.size() % 2 == 0 && tag.strings.empty() &&
                   (tag.floats.size() == 1 || tag.floats.size() == pairs),
               at, tag, "vertex pairs and 1 sharpness or one per pair (2k/1/0 or 2k/k/0)");
        for (size_t p = 0; p < pairs; ++p) {
            const float s = sharpness(tag.floats[tag.floats.size() == 1 ? 0 : p], at, tag);
            tags.creases.push_back({useVertex(tag.ints[2 * p]), useVertex(tag.ints[2 * p + 1]), s});
        }
    } else if (tag.name == "corner") {
        expect(!tag.ints.empty() && tag.strings.empty() &&
                   (tag.floats.size() == 1 || tag.floats.size() == tag.ints.size()),
               at, tag, "vertices and 1 sharpness or one per vertex (k/1/0 or k/k/0)");
        for (size_t i = 0; i < tag.ints.size(); ++i) {
            const float s = sharpness(tag.floats[tag.floats.size() == 1 ? 0 : i], at, tag);
            tags.corners.push_back({useVertex(tag.ints[i]), s});
        }
    } else if (tag.name == "hole") {
        expect(tag.floats.empty() && tag.strings.empty(), at, tag, "face indices only (k/0/0)");
        for (int64_t f : tag.ints) {
            indexUses.push_back({TagIndexUse::Kind::Face, f, at.line, tag.name});
            tags.holes.push_back(int(std::clamp<int64_t>(f, -1, INT32_MAX)));
        }
    } else if (tag.name == "interpolateboundary") {
        tags.boundary = BoundaryInterpolation(singleChoice(tag, at, 2, "one integer 0..2 (1/0/0)"));
        tags.hasBoundary = true;
    } else if (tag.name == "facevaryinginterpolateboundary") {
        tags.faceVaryingBoundary = singleChoice(tag, at, 5, "one integer 0..5 (1/0/0)");
        tags.hasFaceVaryingBoundary = true;
    } else if (tag.name == "creasemethod") {
        const std::string_view word = singleWord(tag, at, "one word, normal or chaikin (0/0/1)");
        if (word == "normal") tags.creaseMethod = CreaseMethod::Uniform;
        else if (word == "chaikin") tags.creaseMethod = CreaseMethod::Chaikin;
        else at.fail("t creasemethod: " + quoted(word) + " is neither normal nor chaikin");
        tags.hasCreaseMethod = true;
    } else if (tag.name == "smoothtriangles") {
        const std::string_view word = singleWord(tag, at, "one word, catmark or smooth (0/0/1)");
        if (word == "catmark") tags.triangles = TriangleSubdivision::Catmark;
        else if (word == "smooth") tags.triangles = TriangleSubdivision::Smooth;
        else at.fail("t smoothtriangles: " + quoted(word) + " is neither catmark nor smooth");
        tags.hasTriangles = true;
    } else {
        // Hierarchical edits and anything newer: not ours to apply, but the cage written back
        // should still carry them.
        tags.passthrough.emplace_back(trimmed(line));
    }
}

std::string formatTagLines(const SubdivisionTags& tags) {
    std::string out;
    if (tags.hasBoundary) out += "t interpolateboundary 1/0/0 " + std::to_string(int(tags.boundary)) + "\n";
    if (tags.hasFaceVaryingBoundary)
        out += "t facevaryinginterpolateboundary 1/0/0 " + std::to_string(tags.faceVaryingBoundary) + "\n";
    if (tags.hasCreaseMethod)
        out += std::string("t creasemethod 0/0/1 ") +
               (tags.creaseMethod == CreaseMethod::Chaikin ? "chaikin" : "normal") + "\n";
    if (tags.hasTriangles)
        out += std::string("t smoothtriangles 0/0/1 ") +
               (tags.triangles == TriangleSubdivision::Smooth ? "smooth" : "catmark") + "\n";
    for (const Crease& c : tags.creases) {
        out += "t crease 2/1/0 " + std::to_string(c.v0) + " " + std::to_string(c.v1);
        appendFloat(out, c.sharpness);
        out += "\n";
    }
    for (const Corner& c : tags.corners) {
        out += "t corner 1/1/0 " + std::to_string(c.vertex);
        appendFloat(out, c.sharpness);
        out += "\n";
    }
    if (!tags.holes.empty()) {
        out += "t hole " + std::to_string(tags.holes.size()) + "/0/0";
        for (int f : tags.holes) {
            out += ' ';
            out += std::to_string(f);
        }
        out += "\n";
    }
    for (const std::string& line : tags.passthrough) out += line + "\n";
    return out;
}

}  // namespace subdfit::mesh::obj
