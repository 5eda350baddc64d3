// Rendering scene text in a test, and an area light written out as its samples: what the light
// tests (tests/unit/render/*light*, area_shadows) share.
#pragma once

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "lang/load_scene.h"
#include "render/renderer.h"

namespace tracer {

// The image of scene `text` on `threads` threads, of the window `crop` if given (its statistics
// into *stats if given); each diagnostic is a test failure.
inline Image render_scene_text(const std::string& text, int threads = 2, PixelRect crop = {},
                               RenderStats* stats = nullptr) {
    LoadResult loaded = load_scene_text("test.scn", text);
    for (const Diagnostic& d : loaded.diagnostics.all()) ADD_FAILURE() << d.message;
    EXPECT_TRUE(loaded.scene);
    if (!loaded.scene) return {};
    const World world(*loaded.scene);
    RenderOptions options;
    options.threads = threads;
    options.crop = crop;
    Image image;
    RenderStats own;
    EXPECT_TRUE(render(world, *loaded.scene, options, image, stats ? *stats : own));
    return image;
}

// `light`'s grid samples (Light::sample) as point lights of `color` / samples each, with the
// keys `extra` written into each block.
inline std::string samples_as_point_lights(const Light& light, double color, const std::string& extra = "") {
    std::ostringstream out;
    out.precision(17);
    for (int i = 0; i < light.samples1; ++i)
        for (int j = 0; j < light.samples2; ++j) {
            const dvec3 p = light.sample(i, j);
            out << "light { position (" << p.x << ", " << p.y << ", " << p.z << ") color "
                << color * (1.0 / light.samples()) << extra << " }\n";
        }
    return out.str();
}

}  // namespace tracer
