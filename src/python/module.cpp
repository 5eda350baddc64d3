// tracer's Python extension (_tracer): scenes loaded from files or text, rendered into NumPy
// arrays that own the renderer's own pixels (nothing copied), described as JSON, and images
// written as the command line writes them. tracer/__init__.py is the public API over it.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "app/diagnostics_json.h"
#include "app/load_files.h"
#include "app/render_call.h"
#include "io/image_file.h"
#include "io/native_images.h"
#include "scene/scene_json.h"

namespace nb = nanobind;
using namespace nb::literals;

namespace {

using Pixels = nb::ndarray<nb::numpy, float, nb::shape<-1, -1, 3>, nb::c_contig>;
using Bytes = nb::ndarray<nb::numpy, uint8_t, nb::shape<-1, -1, 3>, nb::c_contig>;
using PixelsIn = nb::ndarray<const float, nb::shape<-1, -1, 3>, nb::c_contig, nb::device::cpu>;

// A scene loaded with its meshes and image files, shared by every render made of it, and the
// world last built of it (the next render with the same accelerator settings reuses it).
struct Scene {
    std::shared_ptr<const tracer::LoadedScene> loaded;
    std::shared_ptr<tracer::WorldCache> worlds = std::make_shared<tracer::WorldCache>();
};

// Loads a scene from `path`, or from `text` (then `path` only names it), with -D `defines` and
// -I `include` folders; returns (Scene or None, the load's report as JSON text: diagnostics_json.h).
nb::tuple load(const std::string& path, std::optional<std::string> text,
               std::vector<std::pair<std::string, std::string>> defines, std::vector<std::string> include) {
    const tracer::SceneInput input{path, path, {std::move(defines), std::move(include)}, std::move(text)};
    std::string report_json;
    std::optional<tracer::LoadedScene> loaded;
    {
        nb::gil_scoped_release unlocked;
        loaded = tracer::load_scene_with_meshes(input, nullptr, [&](const tracer::LoadReport& found) {
            report_json =
                tracer::load_report_json(path, found).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
        });
    }
    if (!loaded) return nb::make_tuple(nb::none(), report_json);
    return nb::make_tuple(Scene{std::make_shared<const tracer::LoadedScene>(std::move(*loaded))}, report_json);
}

// The resolved description (what --dump-json prints), as JSON text.
std::string describe(const Scene& scene) {
    std::ostringstream out;
    tracer::write_scene_json(out, scene.loaded->scene, &scene.loaded->meshes);
    return out.str();
}

// The encoding named `name` ("linear" or "srgb"), or ValueError.
tracer::Encoding encoding_of(const std::string& name) {
    tracer::Encoding encoding = tracer::Encoding::Linear;
    if (!tracer::encoding_from_name(name, encoding))
        throw std::invalid_argument("encoding must be 'linear' or 'srgb', not '" + name + "'");
    return encoding;
}

// Renders `scene` with the command line's `overrides` (KEY, TEXT pairs: width, samples, ...),
// `threads` and `region` (x0, y0, width, height; empty: the frame); returns (pixels as a float32
// array of shape (height, width, 3) that owns them, or with `encoding` ("linear", "srgb") a uint8
// array of an 8-bit file's bytes; the statistics as JSON text), or None if `stop` (None or a
// callable asked every tracer::kSignalLook) returned true. Ctrl-C raises KeyboardInterrupt within
// kSignalLook, as does what `stop` raises; a bad setting ValueError.
nb::object render(const Scene& scene, const std::vector<std::pair<std::string, std::string>>& overrides, int threads,
                  const std::vector<int>& region, nb::object stop, std::optional<std::string> encoding) {
    std::optional<tracer::Encoding> eight_bit;
    if (encoding) eight_bit = encoding_of(*encoding);
    tracer::RenderCall call(scene.loaded, scene.worlds, overrides, threads, region, eight_bit);  // invalid_argument
    void* pixels = call.allocate();                                                              // std::bad_alloc
    void (*free_bytes)(void*) noexcept = [](void* p) noexcept { delete[] static_cast<unsigned char*>(p); };
    void (*free_floats)(void*) noexcept = [](void* p) noexcept { delete[] static_cast<float*>(p); };
    nb::capsule owner(pixels, eight_bit ? free_bytes : free_floats);
    bool raised = false;  // a Python exception is set: a signal handler's or stop's
    bool finished = false;
    {
        nb::gil_scoped_release unlocked;
        finished = call.run([&] {
            nb::gil_scoped_acquire locked;
            if (PyErr_CheckSignals() != 0) {  // a signal handler raised (KeyboardInterrupt)
                raised = true;
                return false;
            }
            if (stop.is_none()) return true;
            PyObject* answer = PyObject_CallNoArgs(stop.ptr());
            const int truth = answer ? PyObject_IsTrue(answer) : -1;
            Py_XDECREF(answer);
            if (truth < 0) raised = true;
            return truth == 0;
        });
    }
    if (raised) throw nb::python_error();
    if (!finished) return nb::none();
    const size_t shape[3] = {size_t(call.height()), size_t(call.width()), 3};
    if (eight_bit) return nb::make_tuple(Bytes(static_cast<uint8_t*>(pixels), 3, shape, owner), call.stats_json());
    return nb::make_tuple(Pixels(static_cast<float*>(pixels), 3, shape, owner), call.stats_json());
}

// `pixels` (float32, height x width x 3, linear) as a tracer image.
tracer::Image image_of(const PixelsIn& pixels) {
    tracer::Image image;
    image.width = image.frame_width = int(pixels.shape(1));
    image.height = image.frame_height = int(pixels.shape(0));
    image.rgb.assign(pixels.data(), pixels.data() + pixels.size());
    return image;
}

// Writes `pixels` to `path` as the command line would (the format by the extension, 8-bit
// formats by `encoding`, atomically); OSError if it cannot.
void write_image(const std::string& path, const PixelsIn& pixels, const std::string& encoding) {
    const tracer::Encoding chosen = encoding_of(encoding);
    std::optional<std::string> problem;
    {
        nb::gil_scoped_release unlocked;
        problem = tracer::check_output_path(path);
        if (!problem) problem = tracer::write_image(path, image_of(pixels), chosen);
    }
    if (problem) {
        PyErr_SetString(PyExc_OSError, problem->c_str());
        throw nb::python_error();
    }
}

// `pixels` as PNG bytes (8-bit, by `encoding`): what a notebook shows.
nb::bytes png_bytes(const PixelsIn& pixels, const std::string& encoding) {
    const bool srgb = encoding_of(encoding) == tracer::Encoding::Srgb;
    std::vector<unsigned char> encoded;
    std::optional<std::string> problem;
    {
        nb::gil_scoped_release unlocked;
        problem = tracer::encode_native(tracer::NativeFormat::Png, image_of(pixels), srgb, encoded);
    }
    if (problem) throw std::runtime_error(*problem);
    return nb::bytes(reinterpret_cast<const char*>(encoded.data()), encoded.size());
}

}  // namespace

NB_MODULE(_tracer, m) {
    m.doc() = "tracer's engine: use the tracer package (tracer.load, tracer.loads, Scene.render).";
    nb::class_<Scene>(m, "Scene", "A scene loaded with its meshes and image files.");
    m.def("load", &load, "path"_a, "text"_a.none(), "defines"_a, "include"_a,
          "Loads a scene from path (or from text, named path); returns (Scene or None, report JSON).");
    m.def("describe", &describe, "scene"_a, "The resolved scene description as JSON text (tracer --dump-json).");
    m.def("render", &render, "scene"_a, "overrides"_a, "threads"_a, "region"_a, "stop"_a.none(), "encoding"_a.none(),
          "Renders the scene; returns (float32 pixels of shape (height, width, 3), or uint8 ones with "
          "an encoding, statistics JSON), or None if stop() said so.");
    m.def("write_image", &write_image, "path"_a, "pixels"_a, "encoding"_a,
          "Writes pixels to path as the command line writes images (atomically).");
    m.def("png_bytes", &png_bytes, "pixels"_a, "encoding"_a, "The pixels as an 8-bit PNG file's bytes.");
    m.attr("version") = TRACER_VERSION;
}
