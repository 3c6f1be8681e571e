// A test file that puts its helper in the anonymous namespace, which the
// unity build shares between files: test_files_keep_their_own_scope.py
// must report it (tests/CMakeLists.txt).
namespace {
int helper() { return 1; }
}  // namespace
