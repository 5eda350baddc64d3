// Ending the process without waiting for the kernel to free its memory: after an interrupted
// render, an 8192 x 8192 image (1.5 GiB) took the kernel 65-95 ms to free on the exit, most of
// the time from Ctrl-C to the shell's prompt (docs/bench/interrupt.md).
#pragma once

namespace tracer {

// Ends the process now with `code` (as std::_Exit: no destructors, no flushing). A helper that
// shares its memory (a process, not a thread) keeps that memory alive past the exit and lets it
// go once the process is gone, in the background; a plain std::_Exit if it cannot be started.
[[noreturn]] void exit_leaving_memory_to_a_helper(int code);

}  // namespace tracer
