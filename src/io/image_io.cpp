#include "io/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>

#include "io/atomic_file.h"
#include "util/error.h"

namespace subdfit::io {

void writeImage(const std::filesystem::path& path, const std::vector<glm::vec4>& pixels, int width, int height) {
    std::vector<unsigned char> rgb(size_t(width) * height * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const auto& p = pixels[size_t(height - 1 - y) * width + x];  // GL rows are bottom-up
            for (int c = 0; c < 3; ++c)
                rgb[(size_t(y) * width + x) * 3 + c] = (unsigned char)(std::clamp(p[c], 0.0f, 1.0f) * 255.0f + 0.5f);
        }
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        auto out = OIIO::ImageOutput::create(temporary.string());
        if (!out) throw fileError(path.string(), "no image writer for this extension");
        OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
        if (!out->open(temporary.string(), spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) ||
            !out->close())
            throw fileError(path.string(), "could not write image: " + out->geterror());
    });
}

}  // namespace subdfit::io
