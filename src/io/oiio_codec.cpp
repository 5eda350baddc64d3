// The image encoder through OpenImageIO, built as a module (libtracer_oiio.so) that tracer
// loads only when it writes an image: OpenImageIO and the 260 libraries it needs take 0.15 s
// and 130 MB to load, which --check, --dump-json and the language have no use for. The two
// entry points below are all image_file.cpp calls (same compiler, so C++ types cross).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "base/image.h"

namespace tracer {
namespace {

namespace fs = std::filesystem;

unsigned char eight_bit_srgb(double value) {
    return to_8bit(srgb_encoded(value));
}

bool is_float_format(const std::string& path) {
    std::string extension = fs::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
    return extension == ".exr" || extension == ".hdr" || extension == ".pfm";
}

// OpenImageIO writers that can write into memory (ImageOutput's "ioproxy"): the only kind
// tracer uses, so that every byte reaches the disk through one checked, atomic write.
std::unique_ptr<OIIO::ImageOutput> memory_writer(const std::string& path) {
    auto output = OIIO::ImageOutput::create(path);
    if (output && !output->supports("ioproxy")) output.reset();
    return output;
}

}  // namespace
}  // namespace tracer

// True in `ok` if `path`'s extension names a format tracer can write.
extern "C" void tracer_oiio_can_write(const std::string& path, bool& ok) {
    ok = tracer::memory_writer(path) != nullptr;
}

// The image encoded as `path`'s format into `encoded` (8-bit formats by the sRGB curve and marked
// so if `srgb`); `error` says why not, if it could not be.
extern "C" void tracer_oiio_encode(const std::string& path, const tracer::Image& image, bool srgb,
                                   std::vector<unsigned char>& encoded, std::string& error) {
    using namespace tracer;
    auto output = memory_writer(path);
    if (!output) {
        error = "unknown image format";
        return;
    }
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
        std::transform(image.rgb.begin(), image.rgb.end(), std::back_inserter(bytes), srgb ? eight_bit_srgb : to_8bit);
    if (srgb && !as_float) spec.attribute("oiio:ColorSpace", "sRGB");  // PNG: its sRGB chunk
    // Step 2: the file encoded in memory.
    OIIO::Filesystem::IOVecOutput memory(encoded);
    const bool ok = output->set_ioproxy(&memory) && output->open(path, spec, OIIO::ImageOutput::Create) &&
                    output->write_image(as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8,
                                        as_float ? static_cast<const void*>(floats.data()) : bytes.data()) &&
                    output->close();
    if (!ok) {
        const std::string message = output->geterror();
        error = message.empty() ? "encoding the image failed" : message;
    }
}
