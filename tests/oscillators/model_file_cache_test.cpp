// The compile cache of model files (oscillators/model_file/compile_cache.hpp)
// cannot be poisoned: an object planted at a model's cache path, or behind a
// symbolic link there, is never loaded (its constructor would leave a marker
// file); a folder others may write is bypassed; with HOME unset the cache is
// not in the shared temporary folder; a cache folder named like a compiler
// option is a folder; an empty object is rebuilt; a compiler past its time
// limit is stopped and the model refused.
#include <sys/stat.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/oscillators/model_file/compiled_model.hpp>
#include <impactlab/platform/run_program.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

namespace fs = std::filesystem;
using namespace impactlab;
using impactlab::testing::ScratchFolder;
using impactlab::testing::slurp;

const std::string model_file =
    std::string(IMPACTLAB_SOURCE_DIR) + "/oscillators/model_file/examples/linear_impact_model.toml";

std::shared_ptr<const CompiledModel> compiled_in(const fs::path& cache) {
  CompileOptions options;
  options.cache_directory = cache.string();
  return compile_model(read_model_file(model_file), options);
}

// A shared object whose constructor creates `marker`: loading it runs code.
fs::path planted_object(const ScratchFolder& scratch, const fs::path& marker) {
  const fs::path source = scratch / "planted.c";
  std::ofstream(source) << "#include <stdio.h>\n"
                           "__attribute__((constructor)) static void planted(void) {\n"
                           "  FILE* f = fopen(\"" << marker.string() << "\", \"w\");\n"
                           "  if (f) fclose(f);\n"
                           "}\n";
  const fs::path object = scratch / "planted.so";
  EXPECT_EQ(run_program({"cc", "-shared", "-fPIC", "-o", object.string(), source.string()}), 0);
  return object;
}

// The SHA-256 of a file as sha256sum prints it, with a line break.
std::string sha256_line(const ScratchFolder& scratch, const fs::path& file) {
  const fs::path log = scratch / "sha256sum.log";
  EXPECT_EQ(run_program_logged({"sha256sum", file.string()}, log.string()), 0);
  return slurp(log).substr(0, 64) + "\n";
}

// The model's object name in a cache (the same in every folder).
std::string object_name(const ScratchFolder& scratch) {
  const auto model = compiled_in(scratch / "private");
  EXPECT_TRUE(model->compiled) << model->slow_path_reason;
  return fs::path(model->library).filename().string();
}

// The model runs the linear impact oscillator's right-hand side: the loaded
// code is the model's own.
void expect_model_code(const CompiledModel& model) {
  ASSERT_TRUE(model.compiled) << model.slow_path_reason;
  std::vector<double> p;
  for (const auto& parameter : model.parameters) p.push_back(parameter.default_value);
  const double x[2] = {0.3, -0.7};
  double rhs[2];
  model.free_rhs(x, 0.0, p.data(), rhs);
  EXPECT_EQ(rhs[0], -0.7);
}

TEST(ModelFileCache, APlantedObjectAtTheCachePathIsNotLoaded) {
  const ScratchFolder scratch;
  const fs::path marker = scratch / "constructor_ran";
  const fs::path planted = planted_object(scratch, marker);
  const auto first = compiled_in(scratch / "cache");
  ASSERT_TRUE(first->compiled) << first->slow_path_reason;
  // a new file in its place (the loaded one stays as it was)
  fs::remove(first->library);
  fs::copy_file(planted, first->library);

  const auto second = compiled_in(scratch / "cache");
  EXPECT_FALSE(fs::exists(marker));
  expect_model_code(*second);
  EXPECT_FALSE(second->from_cache);
  // rebuilt in place: the planted object is gone
  EXPECT_NE(slurp(second->library), slurp(planted));
}

TEST(ModelFileCache, ASymbolicLinkAtTheCachePathIsNotFollowed) {
  const ScratchFolder scratch;
  const fs::path marker = scratch / "constructor_ran";
  const fs::path planted = planted_object(scratch, marker);
  const auto first = compiled_in(scratch / "cache");
  ASSERT_TRUE(first->compiled) << first->slow_path_reason;
  fs::remove(first->library);
  fs::create_symlink(planted, first->library);
  // a digest that matches the link's target
  for (const auto& entry : fs::directory_iterator(scratch / "cache"))
    if (entry.path().extension() == ".sha256") std::ofstream(entry.path()) << sha256_line(scratch, planted);

  const auto second = compiled_in(scratch / "cache");
  EXPECT_FALSE(fs::exists(marker));
  expect_model_code(*second);
  EXPECT_FALSE(fs::is_symlink(second->library));
}

TEST(ModelFileCache, AFolderOthersMayWriteIsBypassed) {
  const ScratchFolder scratch;
  const fs::path marker = scratch / "constructor_ran";
  const fs::path planted = planted_object(scratch, marker);
  const std::string name = object_name(scratch);
  // another user's folder, as a shared /tmp fallback could be: mode 0777,
  // a planted object with a digest that matches it
  const fs::path shared = scratch / "shared";
  fs::create_directory(shared);
  ASSERT_EQ(::chmod(shared.c_str(), 0777), 0);
  fs::copy_file(planted, shared / name);
  std::ofstream(shared / (name + ".sha256")) << sha256_line(scratch, planted);

  const auto model = compiled_in(shared);
  EXPECT_FALSE(fs::exists(marker));
  expect_model_code(*model);
  EXPECT_TRUE(model->library.empty()) << model->library;
  EXPECT_NE(model->cache_note.find("writable by others (mode 0777)"), std::string::npos)
      << model->cache_note;
}

// Sets or unsets an environment variable for the scope, restoring it after.
class ScopedVariable {
 public:
  ScopedVariable(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) ::setenv(name, value, 1);
    else ::unsetenv(name);
  }
  ~ScopedVariable() {
    if (old_) ::setenv(name_, old_->c_str(), 1);
    else ::unsetenv(name_);
  }
  ScopedVariable(const ScopedVariable&) = delete;
  ScopedVariable& operator=(const ScopedVariable&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(ModelFileCache, WithoutHomeTheCacheIsNotInTheSharedTemporaryFolder) {
  const ScopedVariable no_cache("IMPACTLAB_CACHE_DIR", nullptr);
  const ScopedVariable no_xdg("XDG_CACHE_HOME", nullptr);
  const ScopedVariable no_home("HOME", nullptr);
  const std::string cache = compile_options_from_environment().cache_directory;
  const std::string temporary = fs::temp_directory_path().string();
  EXPECT_NE(cache.rfind(temporary, 0), 0u) << cache;
}

// IMPACTLAB_CACHE_DIR=-o once made the compiler read its paths as options
TEST(ModelFileCache, ACacheFolderNamedLikeAnOptionIsAFolder) {
  const ScratchFolder scratch;
  const fs::path working = fs::current_path();
  fs::current_path(scratch.path());
  const auto model = compiled_in("-o");
  fs::current_path(working);
  expect_model_code(*model);
  EXPECT_EQ(fs::path(model->library).parent_path(), scratch / "-o");
  EXPECT_TRUE(fs::is_regular_file(model->library));
}

TEST(ModelFileCache, AnEmptyObjectIsRebuilt) {
  const ScratchFolder scratch;
  auto first = compiled_in(scratch / "cache");
  ASSERT_TRUE(first->compiled) << first->slow_path_reason;
  const std::string library = first->library;
  first.reset();  // unloaded: a loaded object is not truncated under its mapping
  fs::resize_file(library, 0);
  const auto second = compiled_in(scratch / "cache");
  expect_model_code(*second);
  EXPECT_FALSE(second->from_cache);
  EXPECT_GT(fs::file_size(second->library), 0u);
  // and the rebuilt object is trusted again
  const auto third = compiled_in(scratch / "cache");
  EXPECT_TRUE(third->from_cache);
}

// a compiler that runs past the limit is killed with the processes it
// started, and the model refused (exit status 2), not left to run for minutes
TEST(ModelFileCache, ACompilerPastItsTimeLimitIsRefused) {
  const ScratchFolder scratch;
  const fs::path slow_compiler = scratch / "slow_cc";
  std::ofstream(slow_compiler) << "#!/bin/sh\nsleep 60\n";
  fs::permissions(slow_compiler, fs::perms::owner_all);
  CompileOptions options;
  options.cache_directory = (scratch / "cache").string();
  options.compiler = {slow_compiler.string()};
  options.compile_time_limit_s = 0.5;
  const auto start = std::chrono::steady_clock::now();
  const std::string key = impactlab::testing::bad_input_key(
      [&] { compile_model(read_model_file(model_file), options); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(key, "model");
  EXPECT_LT(seconds, 20.0);
  EXPECT_TRUE(fs::is_empty(scratch / "cache"));
}

TEST(ModelFileCache, ANewFolderIsPrivate) {
  const ScratchFolder scratch;
  const auto model = compiled_in(scratch / "new" / "cache");
  ASSERT_TRUE(model->compiled) << model->slow_path_reason;
  EXPECT_EQ(fs::status(scratch / "new" / "cache").permissions() & fs::perms::all, fs::perms::owner_all);
}

}  // namespace
