#include "io/image_file.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <system_error>
#include <vector>

#include <OpenImageIO/imageio.h>

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

std::optional<std::string> check_output_path(const std::string& path) {
    auto output = OIIO::ImageOutput::create(path);
    if (!output)
        return "cannot write '" + path + "': unknown image format (use an extension such as .png, .exr, .jpg, .tif)";
    fs::path folder = fs::absolute(fs::path(path)).parent_path();
    std::error_code error;
    if (!fs::is_directory(folder, error)) return "cannot write '" + path + "': no such folder '" + folder.string() + "'";
    if (fs::is_directory(path, error)) return "cannot write '" + path + "': it is a directory";
    return std::nullopt;
}

std::optional<std::string> write_image(const std::string& path, const Image& image) {
    auto output = OIIO::ImageOutput::create(path);
    if (!output) return "cannot write '" + path + "': unknown image format";

    // Step 1: pixels in the file's type.
    const bool as_float = is_float_format(path);
    OIIO::ImageSpec spec(image.width, image.height, 3, as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    std::vector<float> floats;
    std::vector<unsigned char> bytes;
    if (as_float)
        floats.assign(image.rgb.begin(), image.rgb.end());
    else
        std::transform(image.rgb.begin(), image.rgb.end(), std::back_inserter(bytes), to_8bit);

    // Step 2: write beside the target, then rename over it (atomic on one file system).
    const fs::path target(path);
    const fs::path temporary =
        target.parent_path() / ("." + target.filename().string() + ".tmp" + std::to_string(::getpid()));
    bool ok = output->open(temporary.string(), spec) &&
              output->write_image(as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8,
                                  as_float ? static_cast<const void*>(floats.data()) : bytes.data()) &&
              output->close();
    std::error_code error;
    if (!ok) {
        std::string message = output->geterror();
        fs::remove(temporary, error);
        return "cannot write '" + path + "': " + (message.empty() ? "write failed" : message);
    }
    fs::rename(temporary, target, error);
    if (error) {
        fs::remove(temporary, error);
        return "cannot write '" + path + "': " + error.message();
    }
    return std::nullopt;
}

}  // namespace tracer
