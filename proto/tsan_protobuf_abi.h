// Force-included into every C++ file that uses Protobuf in the
// ThreadSanitizer build (proto/CMakeLists.txt).
//
// Debian's libprotobuf is compiled without ThreadSanitizer, but its
// map_field.h gives MapFieldBase two more members (race-detection counters)
// when the file including it is compiled with it: the library and our code
// would then disagree on where every map field's data lies. Code compiled
// with TSan reading a map the library built (google.protobuf.Struct's
// fields, parsed from JSON) reads 8 bytes off and crashes in Map::find, and
// the library's MapFieldBase functions misread our own map fields. Reading
// that header here first, without the sanitizer's macro, gives our code the
// library's layout; its include guard keeps it so for the rest of the file.
#pragma once

#if !defined(__SANITIZE_THREAD__)
#error "tsan_protobuf_abi.h is for the ThreadSanitizer build only"
#endif

// libstdc++ reads the macro in its configuration (c++config.h): let it see
// it before the macro is lifted.
#include <cstddef>

#undef __SANITIZE_THREAD__
#include <google/protobuf/map_field.h>
#define __SANITIZE_THREAD__ 1
