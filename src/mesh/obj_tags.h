#pragma once
// OpenSubdiv's OBJ tag lines, `t <name> <nInts>/<nFloats>/<nStrings> <ints> <floats> <strings>`
// (see osd-shapes/README.md): read into SubdivisionTags, and written back in the same syntax.
#include <string>
#include <string_view>
#include <vector>

#include "mesh/obj_tokens.h"
#include "mesh/polygon_mesh.h"

namespace subdfit::mesh::obj {

// A vertex or face index named by a tag, checked once the whole file has been read (tags may
// come before the vertices they name).
struct TagIndexUse {
    enum class Kind { Vertex, Face };
    Kind kind = Kind::Vertex;
    int64_t index = 0;
    int line = 0;
    std::string tag;
};

// Parses one `t` line (without its line ending) into `tags`. Unknown tags are kept verbatim in
// tags.passthrough. Throws subdfit::Error naming `at` for malformed lines.
void parseTagLine(std::string_view line, const LineContext& at, SubdivisionTags& tags,
                  std::vector<TagIndexUse>& indexUses);

// The `t` lines for `tags`: the rule tags the source named explicitly, then creases, corners,
// holes and passthrough lines; each line ends in '\n'.
std::string formatTagLines(const SubdivisionTags& tags);

}  // namespace subdfit::mesh::obj
