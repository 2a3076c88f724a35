// toml++'s implementation for a fuzzer: compiled once here, with the fuzzer's
// instrumentation, while every other file of the fuzzer includes toml++ with
// TOML_HEADER_ONLY=0 (tests/fuzz/CMakeLists.txt).
#define TOML_IMPLEMENTATION
#include <toml++/toml.h>
