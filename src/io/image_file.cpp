#include "io/image_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <system_error>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "base/output_file.h"

namespace tracer {
namespace fs = std::filesystem;

unsigned char to_8bit(double value) {
    if (!(value > 0)) return 0;  // also NaN
    return static_cast<unsigned char>(std::lround(255.0 * std::min(value, 1.0)));
}

static bool is_float_format(const std::string& path) {
    std::string extension = fs::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
    return extension == ".exr" || extension == ".hdr" || extension == ".pfm";
}

// OpenImageIO writers that can write into memory (ImageOutput's "ioproxy"): the only kind
// tracer uses, so that every byte reaches the disk through one checked, atomic write.
static std::unique_ptr<OIIO::ImageOutput> memory_writer(const std::string& path) {
    auto output = OIIO::ImageOutput::create(path);
    if (output && !output->supports("ioproxy")) output.reset();
    return output;
}

std::optional<std::string> check_output_path(const std::string& path) {
    if (!memory_writer(path))
        return "cannot write '" + path +
               "': unknown image format (use an extension such as .png, .exr, .jpg, .tif, .bmp, .hdr)";
    if (auto problem = output_path_problem(path)) return "cannot write '" + path + "': " + *problem;
    return std::nullopt;
}

std::optional<std::string> write_image(const std::string& path, const Image& image) {
    auto output = memory_writer(path);
    if (!output) return "cannot write '" + path + "': unknown image format";

    // Step 1: pixels in the file's type.
    const bool as_float = is_float_format(path);
    OIIO::ImageSpec spec(image.width, image.height, 3, as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    // A window of a larger frame (a render region) keeps its place where the format can say it
    // (EXR's data window inside the display window); elsewhere it is just the window.
    if (image.is_window() && output->supports("displaywindow") && output->supports("origin")) {
        spec.x = image.x0;
        spec.y = image.y0;
        spec.full_x = 0;
        spec.full_y = 0;
        spec.full_width = image.frame_width;
        spec.full_height = image.frame_height;
    }
    std::vector<float> floats;
    std::vector<unsigned char> bytes;
    if (as_float)
        floats.assign(image.rgb.begin(), image.rgb.end());
    else
        std::transform(image.rgb.begin(), image.rgb.end(), std::back_inserter(bytes), to_8bit);

    // Step 2: the encoded file in memory, then on disk in one atomic write.
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    const bool ok = output->set_ioproxy(&memory) && output->open(path, spec, OIIO::ImageOutput::Create) &&
                    output->write_image(as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8,
                                        as_float ? static_cast<const void*>(floats.data()) : bytes.data()) &&
                    output->close();
    if (!ok) {
        const std::string message = output->geterror();
        return "cannot write '" + path + "': " + (message.empty() ? "encoding the image failed" : message);
    }
    const std::string_view file(reinterpret_cast<const char*>(encoded.data()), encoded.size());
    if (auto problem = write_file_atomically(path, file)) return "cannot write '" + path + "': " + *problem;
    return std::nullopt;
}

}  // namespace tracer
