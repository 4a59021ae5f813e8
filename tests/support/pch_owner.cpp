// The target that owns the test executables' shared precompiled header (tests/CMakeLists.txt).
