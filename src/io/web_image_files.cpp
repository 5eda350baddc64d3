// io/image_file.h in the browser's build: no image file is written (the page makes the PNG it
// downloads from the pixels) and image patterns take the pictures the page decoded
// (io/web_pictures.h).
#include <map>
#include <memory>
#include <mutex>

#include "io/image_file.h"
#include "io/web_pictures.h"

namespace tracer {
namespace {

struct Pictures {
    std::mutex guard;
    std::map<std::string, std::shared_ptr<const Texels>> by_path;
};

Pictures& pictures() {
    static Pictures held;
    return held;
}

}  // namespace

void provide_picture(const std::string& path, Texels texels) {
    Pictures& held = pictures();
    const std::lock_guard lock(held.guard);
    held.by_path[path] = std::make_shared<const Texels>(std::move(texels));
}

std::optional<std::string> check_output_path(const std::string& path) {
    return "cannot write '" + path + "': the browser's tracer writes no files (the page downloads the image)";
}

std::optional<std::string> write_image(const std::string& path, const Image&, Encoding) {
    return check_output_path(path);
}

bool load_images(SceneDescription& scene, Diagnostics& diagnostics) {
    Pictures& held = pictures();
    const std::lock_guard lock(held.guard);
    bool ok = true;
    for (ImageFile& image : scene.images) {
        if (image.texels) continue;
        const auto found = held.by_path.find(image.path);
        if (found == held.by_path.end()) {
            diagnostics.report(Severity::Error, image.named_at,
                               "cannot read image file '" + image.path +
                                   "': the page has no such picture (in the browser, tracer reads the PNG and "
                                   "JPEG files of its gallery and those you add)");
            ok = false;
            continue;
        }
        image.texels = found->second;
    }
    return ok;
}

}  // namespace tracer
