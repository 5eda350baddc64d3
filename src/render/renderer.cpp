#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <optional>

#include "accel/world.h"
#include "base/parallel.h"
#include "render/adaptive.h"
#include "render/camera.h"

namespace tracer {

// Primary rays are traced in tiles this many rows high and columns wide (one packet each:
// measured on the bunny's crop, 2 x 4 tiles needed fewer box and triangle tests than 1 x 8).
constexpr int kTileRows = 2;
constexpr int kTileColumns = kPacket / kTileRows;

// The mean of N x N rays through the centers of a regular grid of sub-pixel cells (N = 1:
// the pixel center).
static Color shade_pixel(const World& world, const PinholeCamera& camera, const RenderSettings& settings, int x, int y,
                         int grid, RayCounts& counts, const std::atomic<bool>* cancel) {
    Color sum(0.0);
    const Real cell = Real(1) / grid;  // exact for grid 1 (offset 0.5: the pixel center)
    for (int sy = 0; sy < grid; ++sy)
        for (int sx = 0; sx < grid; ++sx) {
            if (cancel && cancel->load(std::memory_order_relaxed)) return sum;
            const Real px = x + (sx + Real(0.5)) * cell;
            const Real py = y + (sy + Real(0.5)) * cell;
            sum += trace(world, settings, camera.ray_through(px, py), counts, cancel);
        }
    return grid == 1 ? sum : sum * (1.0 / double(grid * grid));
}

// Where finished pixels go: the image's doubles, or the caller's floats (RenderOptions::float_pixels).
struct PixelStore {
    double* doubles;
    float* floats;
    // Pixel `index` (of its red value) set to `c`.
    void put(size_t index, const Color& c) const {
        if (floats)
            floats[index] = float(c.r), floats[index + 1] = float(c.g), floats[index + 2] = float(c.b);
        else
            doubles[index] = c.r, doubles[index + 1] = c.g, doubles[index + 2] = c.b;
    }
};

// Rows first .. first + rows - 1 of `area` (rows at most kTileRows), one sample a pixel, in
// tiles of kTileRows x kTileColumns rays traced together (trace_packet).
static void trace_tiles(const World& world, const PinholeCamera& camera, const RenderSettings& settings,
                        const PixelRect& area, int first, int rows, const PixelStore& store, RayCounts& counts,
                        const std::atomic<bool>* cancel) {
    // The rows' rays are made before any is traced (see render's worker).
    thread_local std::vector<Ray> row_rays[kTileRows];
    thread_local std::vector<Vec3> directions;
    directions.resize(size_t(area.width));
    for (int r = 0; r < rows; ++r) {
        camera.row_directions(area.x0 + Real(0.5), area.y0 + first + r + Real(0.5), area.width, directions.data());
        row_rays[r].resize(size_t(area.width));
        for (size_t i = 0; i < directions.size(); ++i) row_rays[r][i] = {camera.eye(), directions[i]};
    }
    for (int x = 0; x < area.width; x += kTileColumns) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return;
        const int columns = std::min(kTileColumns, area.width - x);
        const Ray* rays[kPacket];
        Color colors[kPacket];
        int n = 0;
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < columns; ++c) rays[n++] = &row_rays[r][size_t(x + c)];
        trace_packet(world, settings, rays, n, colors, counts, cancel);
        n = 0;
        for (int r = 0; r < rows; ++r)
            for (int c = 0; c < columns; ++c) {
                store.put((size_t(first + r) * size_t(area.width) + size_t(x + c)) * 3, colors[n]);
                ++n;
            }
    }
}

// The pixels to render (the crop, kept inside the frame; no crop: the frame), with `image`
// sized and placed for just them.
static PixelRect image_of_crop(const RenderSettings& settings, const PixelRect& crop, const float* float_pixels,
                               Image& image) {
    PixelRect area = crop.width > 0 ? crop : PixelRect{0, 0, settings.width, settings.height};
    area.x0 = std::clamp(area.x0, 0, settings.width);
    area.y0 = std::clamp(area.y0, 0, settings.height);
    area.width = std::clamp(area.width, 0, settings.width - area.x0);
    area.height = std::clamp(area.height, 0, settings.height - area.y0);
    image.width = area.width;
    image.height = area.height;
    image.x0 = area.x0;
    image.y0 = area.y0;
    image.frame_width = settings.width;
    image.frame_height = settings.height;
    image.rgb.resize(float_pixels ? 0 : size_t(area.width) * size_t(area.height) * 3);
    return area;
}

// Row y of `area` traced ray by ray, grid x grid samples a pixel, into `out` (RGB triples);
// `directions` and `rays` are the thread's buffers, a row wide. Stops early when cancelled.
static void trace_row(const World& world, const PinholeCamera& camera, const RenderSettings& settings,
                      const PixelRect& area, int y, int grid, std::vector<Vec3>& directions, std::vector<Ray>& rays,
                      double* out, RayCounts& counts, const std::atomic<bool>* cancel) {
    if (grid == 1) {
        // The row's rays are made before any is traced: a Ray built just before the call that
        // takes it by value is copied out of half-written memory, and the processor stalls on
        // every pixel: store-to-load forwarding fails (docs/bench/code-figures.md).
        camera.row_directions(area.x0 + Real(0.5), y + Real(0.5), area.width, directions.data());
        for (size_t i = 0; i < rays.size(); ++i) rays[i] = {camera.eye(), directions[i]};
    }
    for (int x = area.x0; x < area.x0 + area.width; ++x) {
        // Checked at every pixel and inside the ray tree: a pixel may cost up to
        // kMostRaysPerTree rays per sample.
        if (cancel && cancel->load(std::memory_order_relaxed)) break;
        const Color c = grid == 1 ? trace(world, settings, rays[size_t(x - area.x0)], counts, cancel)
                                  : shade_pixel(world, camera, settings, x, y, grid, counts, cancel);
        double* pixel = out + size_t(x - area.x0) * 3;
        pixel[0] = c.r, pixel[1] = c.g, pixel[2] = c.b;
    }
}

bool render(const World& world, const SceneDescription& scene, const RenderOptions& options, Image& image,
            RenderStats& stats) {
    const RenderSettings& settings = scene.render;
    const PinholeCamera camera(scene.camera, settings.width, settings.height);
    const int grid = int(std::lround(std::sqrt(double(settings.samples))));

    // Step 1: the pixels to render, and an image of just them.
    const PixelRect area = image_of_crop(settings, options.crop, options.float_pixels, image);
    const PixelStore store{image.rgb.data(), options.float_pixels};

    // Step 2: rows handed to the threads one at a time (adaptive: in bands, whose rows share
    // their edges' samples). The time is the render loop's (as embree_bench's): it leaves out
    // the image's allocation.
    const bool adaptive = settings.antialias == Antialias::Adaptive;
    // One sample a pixel: tiles of kTileRows x kTileColumns primary rays traced as one packet.
    const bool tiles =
        !adaptive && grid == 1 && world.frame_takes_tiles(size_t(settings.width) * size_t(settings.height));
    const int band = adaptive ? kMostAdaptiveCell : tiles ? kTileRows : 1;
    const int band_offset = adaptive ? area.y0 % band : 0;  // bands start at the frame's multiples of a cell row
    const auto start = std::chrono::steady_clock::now();
    const int threads = std::max(1, std::min(thread_count(options.threads), std::max(area.height, 1)));
    std::atomic<int> next_row{0};
    std::atomic<int> rows_done{0};
    std::mutex merge;
    stats = {};
    stats.threads = threads;

    const std::atomic<bool>* cancel = options.cancel;
    auto worker = [&](int index) {
        RayCounts counts;
        std::vector<Vec3> directions(size_t(area.width));
        std::vector<Ray> rays(size_t(area.width));  // made before any is traced (trace_row)
        std::vector<double> float_row(store.floats ? size_t(area.width) * 3 : 0);  // a row before it is floats
        std::optional<AdaptivePixels> corners;
        if (adaptive) corners.emplace(world, camera, settings, cancel, area.x0, area.y0, area.width, area.height);
        for (int first; (first = next_row.fetch_add(band) - band_offset) < area.height;) {
            if (tiles) {
                const int rows = std::min(band, area.height - first);
                trace_tiles(world, camera, settings, area, first, rows, store, counts, cancel);
                const int done = rows_done.fetch_add(rows) + rows;
                if (index == 0 && options.progress) options.progress(double(done) / area.height);
                continue;
            }
            for (int row = std::max(first, 0); row < std::min(first + band, area.height); ++row) {
                if (cancel && cancel->load()) break;
                const size_t row_start = size_t(row) * size_t(area.width) * 3;
                double* out = store.floats ? float_row.data() : store.doubles + row_start;
                if (adaptive)
                    corners->row(area.y0 + row, out, counts);
                else
                    trace_row(world, camera, settings, area, area.y0 + row, grid, directions, rays, out, counts,
                              cancel);
                if (store.floats) std::copy(float_row.begin(), float_row.end(), store.floats + row_start);
                const int done = rows_done.fetch_add(1) + 1;
                if (index == 0 && options.progress) options.progress(double(done) / area.height);
            }
        }
        std::lock_guard lock(merge);
        stats.rays += counts;
    };
    run_workers(threads, worker);

    // Step 3: how long it took.
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return !(options.cancel && options.cancel->load()) && rows_done.load() == area.height;
}

}  // namespace tracer
