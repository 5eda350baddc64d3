// A one-line progress indicator on stderr, shown only when stderr is a terminal.
#pragma once

#include <mutex>

namespace tracer {

class ProgressLine {
public:
    explicit ProgressLine(bool wanted);
    // Shows the finished fraction in [0, 1] (redraws only when the percentage changes).
    void update(double fraction);
    // Erases the line.
    void finish();

private:
    bool enabled_;
    int shown_ = -1;
    std::mutex mutex_;
};

}  // namespace tracer
