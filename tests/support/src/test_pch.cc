// The target that builds the test binaries' shared precompiled header
// (cmake/Seaplan.cmake, seaplan_test_pch_target); it has no code of its own.
