// What binary this is: the release (CMake's project version) and the commit it was built
// from, for run.json and `adrsph --version`, so that a result names the code that made it.
// Defined in a source generated at build time (cmake/build_info.cmake).
#pragma once

namespace adrsph {
const char* build_version();  // "0.1.0"
const char* build_commit();   // hash of HEAD, 12 hex digits (+ "-dirty"), or "unknown"
}  // namespace adrsph
