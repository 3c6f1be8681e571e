// The unit that builds the library's precompiled header, which every layer
// reuses (CMakeLists.txt); it has no code of its own.
