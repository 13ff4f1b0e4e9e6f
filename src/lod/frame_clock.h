// The clock the refiner's time budget reads (§6: a frame stops at its budget).
//
// In WebAssembly, std::chrono::steady_clock goes through clock_gettime, a JavaScript import
// that splits the time into seconds and nanoseconds with double arithmetic and writes them into
// memory: garbage on the page's heap at every reading, several times a frame. emscripten_get_now
// hands performance.now() straight back as a double. Natively, the steady clock.
#pragma once

#ifdef __EMSCRIPTEN__
#include <emscripten/emscripten.h>
#else
#include <chrono>
#endif

namespace hexlod {

/// Milliseconds since an arbitrary start, monotonic.
inline double frameClockMs() {
#ifdef __EMSCRIPTEN__
    return emscripten_get_now();
#else
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count();
#endif
}

} // namespace hexlod
