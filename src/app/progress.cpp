#include "app/progress.h"

#include <unistd.h>

#include <cstdio>

namespace tracer {

ProgressLine::ProgressLine(bool wanted) : enabled_(wanted && ::isatty(STDERR_FILENO)) {}

void ProgressLine::update(double fraction) {
    if (!enabled_) return;
    std::lock_guard lock(mutex_);
    int percent = int(fraction * 100);
    if (percent == shown_) return;
    shown_ = percent;
    std::fprintf(stderr, "\rrendering %3d%%", percent);
    std::fflush(stderr);
}

void ProgressLine::finish() {
    if (!enabled_ || shown_ < 0) return;
    std::fprintf(stderr, "\r               \r");
    std::fflush(stderr);
}

}  // namespace tracer
