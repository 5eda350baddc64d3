#include "io/image_file.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <vector>

#include "base/input_file.h"
#include "base/output_file.h"
#include "io/native_images.h"

namespace tracer {
namespace fs = std::filesystem;

namespace {

// The encoder module's entry points (io/oiio_codec.cpp), loaded on first use.
struct Codec {
    void (*can_write)(const std::string& path, bool& ok) = nullptr;
    void (*encode)(const std::string& path, const Image& image, bool srgb, std::vector<unsigned char>& encoded,
                   std::string& error) = nullptr;
    void (*read)(const std::string& path, Texels& out, size_t most_bytes, std::string& error) = nullptr;
    std::string problem;  // why it could not be loaded
};

const Codec& codec() {
    static Codec loaded;
    static std::once_flag once;
    std::call_once(once, [] {
        // Next to the executable (tracer, the tests and the benchmarks are built into one
        // folder), else next to the shared object holding this code (the Python package's
        // extension, installed beside it), else where the build put it.
        std::error_code ignored;
        const fs::path beside = fs::read_symlink("/proc/self/exe", ignored).parent_path() / "libtracer_oiio.so";
        void* module = dlopen(beside.c_str(), RTLD_NOW | RTLD_LOCAL);
        Dl_info holder{};
        if (!module && dladdr(reinterpret_cast<void*>(&codec), &holder) && holder.dli_fname)
            module =
                dlopen((fs::path(holder.dli_fname).parent_path() / "libtracer_oiio.so").c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!module) module = dlopen(TRACER_MODULE_DIR "/libtracer_oiio.so", RTLD_NOW | RTLD_LOCAL);
        if (!module) {
            const char* why = dlerror();
            loaded.problem = std::string("cannot load the image writer libtracer_oiio.so: ") + (why ? why : "");
            return;
        }
        loaded.can_write = reinterpret_cast<decltype(loaded.can_write)>(dlsym(module, "tracer_oiio_can_write"));
        loaded.encode = reinterpret_cast<decltype(loaded.encode)>(dlsym(module, "tracer_oiio_encode"));
        loaded.read = reinterpret_cast<decltype(loaded.read)>(dlsym(module, "tracer_oiio_read"));
        if (!loaded.can_write || !loaded.encode || !loaded.read)
            loaded.problem = "libtracer_oiio.so lacks its entry points";
    });
    return loaded;
}

}  // namespace

std::optional<std::string> check_output_path(const std::string& path) {
    if (native_format(path)) {  // PNG and PPM: no module to load
        if (auto problem = output_path_problem(path)) return "cannot write '" + path + "': " + *problem;
        return std::nullopt;
    }
    const Codec& writer = codec();
    if (!writer.problem.empty()) return "cannot write '" + path + "': " + writer.problem;
    bool known = false;
    writer.can_write(path, known);
    if (!known)
        return "cannot write '" + path +
               "': unknown image format (use an extension such as .png, .exr, .jpg, .tif, .bmp, .hdr)";
    if (auto problem = output_path_problem(path)) return "cannot write '" + path + "': " + *problem;
    return std::nullopt;
}

bool load_images(SceneDescription& scene, Diagnostics& diagnostics) {
    bool ok = true;
    for (ImageFile& image : scene.images) {
        if (image.texels) continue;
        const Codec& reader = codec();
        auto texels = std::make_shared<Texels>();
        std::string error = reader.problem;
        if (error.empty()) {
            if (auto problem = input_file_problem(image.path, kMaxImageFileBytes); !problem.empty())
                error = problem;
            else
                reader.read(image.path, *texels, kMostTexelBytes, error);
        }
        if (!error.empty()) {
            diagnostics.report(Severity::Error, image.named_at,
                               "cannot read image file '" + image.path + "': " + error);
            ok = false;
            continue;
        }
        image.texels = std::move(texels);
    }
    return ok;
}

std::optional<std::string> write_image(const std::string& path, const Image& image, Encoding encoding) {
    // The encoded file in memory (PNG and PPM by tracer, the rest by OpenImageIO), then on disk
    // in one atomic write.
    std::vector<unsigned char> encoded;
    const bool srgb = encoding == Encoding::Srgb;
    if (const auto format = native_format(path)) {
        if (auto error = encode_native(*format, image, srgb, encoded)) return "cannot write '" + path + "': " + *error;
    } else {
        const Codec& writer = codec();
        if (!writer.problem.empty()) return "cannot write '" + path + "': " + writer.problem;
        std::string error;
        writer.encode(path, image, srgb, encoded, error);
        if (!error.empty()) return "cannot write '" + path + "': " + error;
    }
    const std::string_view file(reinterpret_cast<const char*>(encoded.data()), encoded.size());
    if (auto problem = write_file_atomically(path, file)) return "cannot write '" + path + "': " + *problem;
    return std::nullopt;
}

}  // namespace tracer
