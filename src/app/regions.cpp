#include "app/regions.h"

#include <istream>
#include <ostream>
#include <sstream>

#include "io/image_file.h"

namespace tracer {

std::optional<std::string> region_problem(const std::vector<int>& region, const RenderSettings& render) {
    if (region.size() != 4) return "a region is four whole numbers: X0 Y0 W H";
    const int x0 = region[0], y0 = region[1], width = region[2], height = region[3];
    const std::string text = "region " + std::to_string(x0) + " " + std::to_string(y0) + " " + std::to_string(width) +
                             " " + std::to_string(height);
    const std::string frame =
        " (the image is " + std::to_string(render.width) + " x " + std::to_string(render.height) + ")";
    if (width < 1 || height < 1) return text + " is empty: its width and height must be at least 1" + frame;
    if (x0 < 0 || y0 < 0) return text + " starts outside the image: X0 and Y0 must be 0 or more" + frame;
    if (int64_t(x0) + width > render.width)
        return text + " reaches past the image's right edge: X0 + W must be at most the width" + frame;
    if (int64_t(y0) + height > render.height)
        return text + " reaches past the image's bottom edge: Y0 + H must be at most the height" + frame;
    return std::nullopt;
}

// The region and output path of a request line, or an error message.
static std::optional<std::string> parse_request(const std::string& line, std::vector<int>& region,
                                                std::string& output) {
    std::istringstream in(line);
    region.assign(4, 0);
    for (int& value : region)
        if (!(in >> value)) return "expected 'X0 Y0 W H OUTPUT', got '" + line + "'";
    std::getline(in >> std::ws, output);
    while (!output.empty() && (output.back() == ' ' || output.back() == '\r')) output.pop_back();
    if (output.empty()) return "expected 'X0 Y0 W H OUTPUT': no output path in '" + line + "'";
    return std::nullopt;
}

// The next line of `in` (without its newline) if it has at most `limit` characters; a longer one
// is skipped up to its newline and reported by `too_long`. False at the end of the input.
static bool read_line(std::istream& in, std::string& line, size_t limit, bool& too_long) {
    line.clear();
    too_long = false;
    for (int c; (c = in.get()) != std::char_traits<char>::eof();) {
        if (c == '\n') return true;
        if (line.size() < limit)
            line.push_back(char(c));
        else
            too_long = true;
    }
    return !line.empty() || too_long;
}

bool render_region_list(const World& world, const SceneDescription& scene, RenderOptions options,
                        const OutputCheck& output_problem, std::istream& requests, std::ostream& replies,
                        std::atomic<bool>& waiting) {
    std::string line;
    for (;;) {
        // Step 1: the next request.
        constexpr size_t kLongestLine = 16384;  // four numbers and a path (PATH_MAX is 4096)
        bool too_long = false;
        waiting = true;
        const bool got = read_line(requests, line, kLongestLine, too_long);
        waiting = false;
        if (!got) return true;
        if (!too_long && line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::vector<int> region;
        std::string output;
        auto problem = too_long ? "a request line longer than " + std::to_string(kLongestLine) + " characters"
                                : parse_request(line, region, output);
        if (!problem) problem = region_problem(region, scene.render);
        if (!problem) problem = output_problem(output);

        // Step 2: the region, rendered and written, or why not.
        if (!problem) {
            options.crop = {region[0], region[1], region[2], region[3]};
            Image image;
            RenderStats stats;
            if (!render(world, scene, options, image, stats)) return false;
            problem = write_image(output, image, scene.render.encoding);
        }
        if (problem)
            replies << "error" << (output.empty() ? "" : " " + output) << ": " << *problem << std::endl;
        else
            replies << "done " << output << std::endl;
    }
}

}  // namespace tracer
