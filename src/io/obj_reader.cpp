#include "io/obj_reader.h"

#include <charconv>
#include <climits>
#include <cmath>
#include <string_view>

#include "base/portable.h"
#include "scene/scene.h"

namespace tracer {
namespace {

bool is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\r';
}

struct Token {
    std::string_view text;
    Span span;
};

class ObjReader {
public:
    ObjReader(const SourceFile& file, Diagnostics& diagnostics) : file_(file), diagnostics_(diagnostics) {}

    std::optional<ObjContents> read() {
        const std::string_view text = file_.text();
        if (const size_t nul = text.find('\0'); nul != std::string_view::npos) {
            error({uint32_t(nul), uint32_t(nul + 1)}, "NUL byte: this is not a text OBJ file");
            return std::nullopt;
        }
        // Step 1: count vertices and normals, so a face may name one defined further down.
        for_each_statement([&](std::string_view keyword) {
            vertex_total_ += keyword == "v";
            normal_total_ += keyword == "vn";
            texcoord_total_ += keyword == "vt";
            out_.material_statements += keyword == "usemtl" || keyword == "mtllib";
        });
        out_.positions.reserve(vertex_total_);
        out_.normals.reserve(normal_total_);
        out_.texcoords.reserve(texcoord_total_);
        out_.face_starts.push_back(0);

        // Step 2: read them, checking every number and index.
        for_each_statement([&](std::string_view keyword) {
            if (keyword == "v" || keyword == "vn") {
                read_coordinates(keyword, keyword == "v" ? out_.positions : out_.normals);
            } else if (keyword == "vt") {
                glm::dvec3 uvw(0.0);
                read_numbers(keyword, 1, 3, uvw);
                out_.texcoords.push_back({uvw.x, uvw.y});
            } else if (keyword == "f") {
                read_face();
            }
        });
        if (!ok_) return std::nullopt;
        return std::move(out_);
    }

private:
    // Calls `visit(keyword)` for each statement, with tokens_ holding its other words
    // (comments removed); stops early once the error limit is reached.
    template <typename Visit>
    void for_each_statement(Visit visit) {
        const std::string_view text = file_.text();
        size_t pos = 0;
        while (pos < text.size() && !diagnostics_.saturated()) {
            size_t end = text.find('\n', pos);
            if (end == std::string_view::npos) end = text.size();
            tokens_.clear();
            size_t i = pos;
            while (i < end && text[i] != '#') {
                while (i < end && is_blank(text[i])) ++i;
                const size_t start = i;
                while (i < end && !is_blank(text[i]) && text[i] != '#') ++i;
                if (i > start) tokens_.push_back({text.substr(start, i - start), {uint32_t(start), uint32_t(i)}});
                if (tokens_.size() > kMaxFaceCorners + 1) break;  // more is refused anyway: bound the memory
            }
            if (!tokens_.empty()) {
                keyword_span_ = tokens_.front().span;
                const std::string_view keyword = tokens_.front().text;
                tokens_.erase(tokens_.begin());
                visit(keyword);
            }
            pos = end + 1;
        }
    }

    // `v x y z [w | r g b]` and `vn x y z`: three finite numbers in range (any extra ones of a
    // `v`, a weight or a colour, are checked as numbers and not used).
    void read_coordinates(std::string_view keyword, std::vector<glm::dvec3>& into) {
        glm::dvec3 point(0.0);
        read_numbers(keyword, 3, keyword == "v" ? 6 : 3, point);
        into.push_back(point);  // even when wrong, so later indices still count right
    }

    // The numbers of a `v`, `vn` or `vt`: `least` to `allowed` finite ones in range, the first
    // three (at most) into `point`.
    void read_numbers(std::string_view keyword, size_t least, size_t allowed, glm::dvec3& point) {
        if (tokens_.size() < least) {
            error(tokens_.empty() ? keyword_span_ : tokens_.back().span,
                  "'" + std::string(keyword) + "' needs " + (least == 3 ? "three coordinates" : "a coordinate"));
        } else if (tokens_.size() > allowed) {
            error(tokens_[allowed].span,
                  "'" + std::string(keyword) + "' has more than " + std::to_string(allowed) + " numbers");
        } else {
            for (size_t i = 0; i < tokens_.size(); ++i) {
                const Token& token = tokens_[i];
                double value = 0;
                const char* end = token.text.data() + token.text.size();
                auto [stop, status] = parse_double(token.text.data(), end, value);
                if (status != std::errc() || stop != end || !std::isfinite(value))
                    error(token.span, "coordinate " + in_quotes(token.text) + " is not a finite number");
                else if (std::abs(value) > kLargestMagnitude)
                    error(token.span, "coordinate " + in_quotes(token.text) +
                                          " lies beyond +-1e30 (the renderer keeps bounding boxes in float and "
                                          "squares and cubes lengths)");
                else if (i < 3)
                    point[int(i)] = value;
            }
        }
    }

    // `f v v v ...`, each corner v, v/vt, v/vt/vn or v//vn.
    void read_face() {
        if (tokens_.size() < 3) error(keyword_span_, "a face needs at least three vertices");
        if (tokens_.size() > kMaxFaceCorners) {
            error(keyword_span_, "this face has more than " + std::to_string(kMaxFaceCorners) + " corners (the limit)");
            return;
        }
        if (tokens_.size() >= 5) polygon_work_ += double(tokens_.size()) * double(tokens_.size());
        if (polygon_work_ > kMaxPolygonWork && !work_reported_) {
            work_reported_ = true;
            error(keyword_span_,
                  "the faces of 5 or more corners up to this one are too large in all to triangulate "
                  "(the sum of their squared corner counts passes 2e10); split them into smaller faces");
            return;
        }
        for (const Token& token : tokens_) {
            const std::string_view corner = token.text;
            const size_t slash = corner.find('/');
            if (slash == 0) error(token.span, in_quotes(token.text) + " has no vertex index");
            const long vertex =
                index(token, corner.substr(0, slash), out_.positions.size(), vertex_total_, "vertex", "vertices");
            long normal = -1, texcoord = -1;
            if (slash != std::string_view::npos) {
                const size_t second = corner.find('/', slash + 1);
                texcoord = index(token, corner.substr(slash + 1, second - slash - 1), out_.texcoords.size(),
                                 texcoord_total_, "texture coordinate", "texture coordinates");
                if (second != std::string_view::npos)
                    normal = index(token, corner.substr(second + 1), out_.normals.size(), normal_total_, "normal",
                                   "normals");
            }
            out_.corner_vertex.push_back(uint32_t(std::max(vertex, 0L)));
            out_.corner_normal.push_back(int32_t(normal));
            out_.corner_texcoord.push_back(int32_t(texcoord));
        }
        out_.face_starts.push_back(uint32_t(out_.corner_vertex.size()));
    }

    // One index of a face corner, 0-based, or -1 if absent or wrong (reported; an absent one
    // is read_face's to judge).
    long index(const Token& token, std::string_view digits, size_t so_far, size_t total, const char* what,
               const char* plural) {
        if (digits.empty()) return -1;
        long number = 0;
        auto [end, status] = std::from_chars(digits.data(), digits.data() + digits.size(), number);
        if (status != std::errc() || end != digits.data() + digits.size() || number < INT_MIN || number > INT_MAX) {
            error(token.span, in_quotes(token.text) + " is not a valid face corner");
            return -1;
        }
        const long resolved = number < 0 ? long(so_far) + number + 1 : number;  // negative: relative to here
        if (number == 0 || resolved < 1 || resolved > long(total)) {
            error(token.span, std::string(what) + " index " + std::to_string(number) +
                                  " is out of range (the file has " + std::to_string(total) + " " +
                                  (total == 1 ? what : plural) + ")");
            return -1;
        }
        return resolved - 1;
    }

    void error(Span span, std::string message) {
        diagnostics_.error(file_, span, std::move(message));
        ok_ = false;
    }

    const SourceFile& file_;
    Diagnostics& diagnostics_;
    ObjContents out_;
    std::vector<Token> tokens_;
    Span keyword_span_;
    size_t vertex_total_ = 0, normal_total_ = 0, texcoord_total_ = 0;
    double polygon_work_ = 0;  // corner pairs of the faces of 5 or more corners so far
    bool work_reported_ = false;
    bool ok_ = true;
};

}  // namespace

std::optional<ObjContents> read_obj(const SourceFile& file, Diagnostics& diagnostics) {
    return ObjReader(file, diagnostics).read();
}

}  // namespace tracer
