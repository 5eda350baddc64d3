// The image encoder through OpenImageIO, built as a module (libtracer_oiio.so) that tracer
// loads only when it writes an image: OpenImageIO and the 260 libraries it needs take 0.15 s
// and 130 MB to load, which --check, --dump-json and the language have no use for. The two
// entry points below are all image_file.cpp calls (same compiler, so C++ types cross).
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "base/image.h"
#include "scene/pattern.h"

namespace tracer {
namespace {

namespace fs = std::filesystem;

// Standard error sent to /dev/null while one lives: libpng prints a line of its own ("libpng
// error: ...") before OpenImageIO returns the same failure, which tracer then reports at the
// scene's `file` value. Images are read one at a time, before rendering starts.
class QuietStandardError {
public:
    QuietStandardError() {
        std::fflush(stderr);
        saved_ = dup(STDERR_FILENO);
        const int null = open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (saved_ >= 0 && null >= 0) dup2(null, STDERR_FILENO);
        if (null >= 0) close(null);
    }
    ~QuietStandardError() {
        if (saved_ < 0) return;
        std::fflush(stderr);
        dup2(saved_, STDERR_FILENO);
        close(saved_);
    }
    QuietStandardError(const QuietStandardError&) = delete;
    QuietStandardError& operator=(const QuietStandardError&) = delete;

private:
    int saved_ = -1;
};

// The last line of one of OpenImageIO's messages, which may stack a library's lines (the
// most specific last), for a diagnostic of one line.
std::string last_line(std::string message) {
    while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
    const size_t newline = message.rfind('\n');
    return newline == std::string::npos ? message : message.substr(newline + 1);
}

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

// The texels of the image file `path` into `out` (scene/pattern.h's Texels: 8-bit files as
// bytes, other integer files decoded from sRGB into floats, float files as they are; grey or
// RGB, other channels dropped); `error` says why not, if they could not be read. A picture of
// more than `most_bytes` of texels is refused before any is read.
extern "C" void tracer_oiio_read(const std::string& path, tracer::Texels& out, size_t most_bytes, std::string& error) {
    using namespace tracer;
    const QuietStandardError quiet;
    auto input = OIIO::ImageInput::open(path);
    if (!input) {
        const std::string message = last_line(OIIO::geterror());
        error = message.empty() ? "not an image OpenImageIO can read" : message;
        return;
    }
    // Step 1: the header: size and channels, checked before a texel is read.
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
        error = "the image has no texels (" + std::to_string(spec.width) + " x " + std::to_string(spec.height) + ")";
        return;
    }
    const int channels = spec.nchannels >= 3 ? 3 : 1;
    const bool bytes = spec.format == OIIO::TypeDesc::UINT8;
    const bool floats = spec.format.is_floating_point();
    const size_t texels = size_t(spec.width) * size_t(spec.height);
    if (texels * size_t(channels) * (bytes ? 1 : sizeof(float)) > most_bytes) {
        error = "the image is " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                " texels, more than tracer holds (" + std::to_string(most_bytes >> 20) + " MB of texels)";
        return;
    }
    // Step 2: the texels, the first `channels` of each.
    out.width = spec.width, out.height = spec.height, out.channels = channels;
    bool ok = true;
    if (bytes) {
        out.bytes.resize(texels * size_t(channels));
        ok = input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, out.bytes.data());
    } else {
        out.floats.resize(texels * size_t(channels));
        ok = input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, out.floats.data());
        if (ok && !floats)  // 16-bit and other integer files hold sRGB-encoded values, as 8-bit ones do
            for (float& v : out.floats) {
                const double c = std::clamp(double(v), 0.0, 1.0);
                v = float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
            }
    }
    if (!ok) {
        const std::string message = last_line(input->geterror());
        error = message.empty() ? "reading the texels failed" : message;
        out = Texels{};
    }
}
