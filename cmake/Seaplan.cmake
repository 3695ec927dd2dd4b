# Helpers shared by every folder: warnings, libraries, tests.

# Where the shared benchmark/chart data lives (../shared beside the clone by
# default). Tests read it from the SEAPLAN_SHARED environment variable, which
# the test support library bakes in as its default (the environment variable
# still wins at run time); tests skip with a reason when it is absent.
set(SEAPLAN_SHARED "$ENV{SEAPLAN_SHARED}" CACHE PATH "Path to the shared data folder")
if(NOT SEAPLAN_SHARED)
  get_filename_component(SEAPLAN_SHARED "${CMAKE_SOURCE_DIR}/../shared" ABSOLUTE)
endif()

function(seaplan_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
    -Wnon-virtual-dtor -Wcast-align -Wunused -Woverloaded-virtual
    -Wno-missing-field-initializers)
  # GCC 12 reports -Wrestrict inside libstdc++'s std::string when a short
  # literal is inserted in front of a string ("(" + s, ":" + std::to_string(n)):
  # a false positive, fixed in GCC 13
  # (https://gcc.gnu.org/bugzilla/show_bug.cgi?id=105329). Here it appears
  # only with -O3's inlining, so only the Release build (the Dockerfile's)
  # turns the warning off; RelWithDebInfo keeps it.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_GREATER_EQUAL 12
     AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE $<$<CONFIG:Release>:-Wno-restrict>)
  endif()
endfunction()

# seaplan_library(name SOURCES a.cc ... DEPS lib ... [PUBLIC_INCLUDE dir])
function(seaplan_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include
                                     PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  seaplan_warnings(${name})
endfunction()

# How test sources compile. Test files are more than half of a build's compile
# time, nearly all of it GoogleTest's and GoogleMock's headers and the code
# their macros expand to, while the code they test sits in the libraries,
# which keep the build type's flags. engine/validate/src/validator_test.cc, in
# CPU-s: 25.0 at -O2 -g1, 19.1 with the shared header below, 13.0 at -O1 with
# it; under ASan+UBSan 45.7 at -O1, 20.2 at -O0.
#  - SEAPLAN_TEST_OPTIMIZATION: the optimisation of the test sources
#    themselves in optimised builds (Debug keeps its own -O0); the sanitizer
#    builds set -O0 (scripts/sanitize.sh).
#  - One precompiled header for every test binary (GoogleTest, GoogleMock and
#    the standard headers most tests include), built once in seaplan_test_pch
#    and reused; each test file still includes what it uses.
set(SEAPLAN_TEST_OPTIMIZATION "-O1" CACHE STRING
    "Optimisation flag of test sources in optimised builds (the code under test keeps the build type's)")
function(seaplan_test_compile_options target)
  # -pthread everywhere: the gRPC suites get it (with its _REENTRANT) from
  # gRPC's flags, and a precompiled header serves only identical macros.
  target_compile_options(${target} PRIVATE $<$<NOT:$<CONFIG:Debug>>:${SEAPLAN_TEST_OPTIMIZATION}>
                                           -pthread)
endfunction()
function(seaplan_test_pch_target)
  add_library(seaplan_test_pch OBJECT ${PROJECT_SOURCE_DIR}/tests/support/src/test_pch.cc)
  target_link_libraries(seaplan_test_pch PRIVATE GTest::gtest GTest::gmock)
  seaplan_warnings(seaplan_test_pch)  # -Wpedantic changes predefined macros
  seaplan_test_compile_options(seaplan_test_pch)
  target_precompile_headers(seaplan_test_pch PRIVATE <gmock/gmock.h> <gtest/gtest.h>
    <algorithm> <chrono> <cmath> <cstdint> <filesystem> <fstream> <functional> <map>
    <memory> <optional> <set> <sstream> <string> <string_view> <thread> <unordered_map>
    <utility> <vector>)
endfunction()
# seaplan_test_target(target): what every test binary gets (output folder,
# warnings, test flags, the shared precompiled header); seaplan_test calls it,
# and so do test binaries made by hand.
function(seaplan_test_target target)
  set_target_properties(${target} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  seaplan_warnings(${target})
  seaplan_test_compile_options(${target})
  target_precompile_headers(${target} REUSE_FROM seaplan_test_pch)
endfunction()

# seaplan_test(name SOURCES a_test.cc ... DEPS lib ...): one GoogleTest binary,
# each TEST registered with ctest. Labels let `ctest -L unit` pick fast ones.
function(seaplan_test name)
  if(NOT SEAPLAN_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "LABEL" "SOURCES;DEPS" ${ARGN})
  if(NOT ARG_LABEL)
    set(ARG_LABEL unit)
  endif()
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} seaplan_testing GTest::gtest GTest::gmock GTest::gtest_main)
  seaplan_test_target(${name})
  gtest_discover_tests(${name}
    DISCOVERY_TIMEOUT 60
    PROPERTIES LABELS ${ARG_LABEL} TIMEOUT 600)
endfunction()

# seaplan_bench_smoke(target [NEEDS_SHARED rel/path] ARGS ...): runs a
# benchmark once on a tiny input as a ctest test labelled bench-smoke, so that
# every benchmark keeps building and running (`ctest -L bench-smoke`). Its
# figures mean nothing at this size; each README gives the real command.
# NEEDS_SHARED: skipped with the reason when ${SEAPLAN_SHARED}/<path> is
# absent, failed instead under CI (environment variable CI set).
function(seaplan_bench_smoke target)
  if(NOT SEAPLAN_BUILD_TESTS OR NOT TARGET ${target})
    return()
  endif()
  cmake_parse_arguments(ARG "" "NEEDS_SHARED;PASS_REGEX" "ARGS" ${ARGN})
  set(command $<TARGET_FILE:${target}> ${ARG_ARGS})
  if(ARG_NEEDS_SHARED)
    set(command ${CMAKE_SOURCE_DIR}/bench/run_if_shared.sh ${SEAPLAN_SHARED}/${ARG_NEEDS_SHARED}
                ${command})
  endif()
  add_test(NAME bench_smoke.${target} COMMAND ${command} WORKING_DIRECTORY ${CMAKE_BINARY_DIR})
  set_tests_properties(bench_smoke.${target} PROPERTIES LABELS bench-smoke TIMEOUT 600
    SKIP_RETURN_CODE 77 ENVIRONMENT "SEAPLAN_SHARED=${SEAPLAN_SHARED}")
  if(ARG_PASS_REGEX)
    set_tests_properties(bench_smoke.${target} PROPERTIES PASS_REGULAR_EXPRESSION "${ARG_PASS_REGEX}")
  endif()
endfunction()
