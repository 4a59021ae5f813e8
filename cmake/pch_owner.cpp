// The target that owns the library layers' shared precompiled header (cmake/layers.cmake).
