// The compile cache of model files: a model's C source compiled by the system
// compiler into a shared object, kept in a private folder, and loaded with
// dlopen only when it is the object this program wrote there.
//
// The cache folder: $IMPACTLAB_CACHE_DIR, else $XDG_CACHE_HOME/impactlab,
// else $HOME/.cache/impactlab, else the user's home directory from the
// password database; never a shared temporary folder. The compiler:
// $IMPACTLAB_CC, else `cc`; $IMPACTLAB_CC may hold the compiler and flags of
// its own separated by spaces ("gcc -march=native"), split into an argument
// vector: the compiler runs from that vector (platform/run_program.hpp), never
// through a shell, and every path it is given is absolute, so no path is read
// as shell text or as an option.
//
// Who may write where, and what is checked before a load:
// - The folder is created with mode 0700. It is used only if it is a
//   directory (not a symbolic link) owned by this user that neither the group
//   nor others may write. A folder that fails a check is bypassed, not
//   refused: the model is compiled in a fresh private temporary folder
//   (mkdtemp, mode 0700), loaded, and the folder removed; `cache_note` says
//   why, and the run goes on at full speed without a cache.
// - Every object is written under a unique temporary name and renamed into
//   place, beside `<object>.sha256`, the SHA-256 of its content, written by
//   this program after it compiled the object.
// - Before a load, the object and its digest file are opened inside the
//   checked folder without following a symbolic link; both must be regular,
//   non-empty files of this user that nobody else may write, and the
//   object's SHA-256 must be the recorded one. The load is of the very file
//   that was hashed (dlopen of /proc/self/fd/N), so it cannot be swapped
//   between the check and the load.
// - A mismatch, a missing or foreign digest, an empty or corrupt object: the
//   object is compiled anew and replaces the old one; nothing unverified is
//   ever loaded.
#pragma once

#include <string>
#include <vector>

namespace impactlab {

struct CompileOptions {
  std::string cache_directory;   // where the shared objects are kept; empty: no cache
  // the C compiler and flags of its own, as an argument vector (no shell);
  // impactlab adds its flags, the output and the source after them
  std::vector<std::string> compiler = {"cc"};
  bool use_compiler = true;      // false: go straight to the interpreted evaluator
  // the longest a compilation may run (s): a model whose C takes longer is
  // refused (BadInput, exit status 2), not left to run for minutes
  double compile_time_limit_s = 120.0;
};

// The options from the environment ($IMPACTLAB_CACHE_DIR, $XDG_CACHE_HOME,
// $HOME, the password database, $IMPACTLAB_CC).
CompileOptions compile_options_from_environment();

// A model's shared object, loaded (or why not).
struct LoadedObject {
  void* handle = nullptr;   // dlopen's handle; null when there is none (then `why`)
  int descriptor = -1;      // the object's file, open while it is loaded (closed after dlclose)
  std::string path;         // where the object is kept; empty when not kept
  bool from_cache = false;  // it was in the cache, with its digest
  std::string why;          // why there is no object: the slow path
  std::string cache_note;   // why the cache was bypassed (compiled in a temporary folder)
};

// The object for `source`, found in the cache under a name derived from the
// source and the compiler command, or compiled and stored there.
LoadedObject load_or_compile(const std::string& source, const CompileOptions& options);

}  // namespace impactlab
