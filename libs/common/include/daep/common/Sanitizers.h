#pragma once

namespace daep {

/**
 * Call before loading a system library that uses dynamic TLS (the EGL driver of the scene
 * PNGs). Under LeakSanitizer it runs the leak check now, once, instead of at exit: clang 14's
 * end-of-process check crashes walking such a library's dynamic TLS on glibc 2.36 ("Tracer
 * caught signal 11" on a garbage DTLS entry, depending on the memory layout), so a clean run
 * failed. Leaks made after this point go unchecked in that process. A no-op in other builds.
 */
void leakCheckBeforeDynamicTls();

}  // namespace daep
