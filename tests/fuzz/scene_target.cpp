// Fuzz target: the scene front end (lex, parse, run, validate), its messages, the JSON dump, and
// a tiny render of what it accepts (mesh blocks left out, and meshes in solids left empty: their
// paths would read real files).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "fuzz/render_small.h"
#include "lang/load_scene.h"
#include "scene/scene_json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace tracer;
    // Small generation limits: the fuzzer's time and memory per input are short (the real
    // limits are tested in tests/cli).
    InterpretLimits limits;
    limits.max_blocks = 20'000;
    limits.max_iterations = 100'000;
    limits.max_operations = 10'000'000;
    limits.max_list_items = 100'000;
    limits.max_call_depth = 1'000;
    LoadResult loaded =
        load_scene_text("fuzz.scn", std::string(reinterpret_cast<const char*>(data), size), false, {}, limits);
    std::ostringstream messages;
    loaded.diagnostics.print(messages);
    if (!loaded.scene) return 0;
    std::ostringstream json;
    json << scene_to_json(*loaded.scene).dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
    loaded.scene->meshes.clear();
    render_small(*loaded.scene, {});
    return 0;
}
