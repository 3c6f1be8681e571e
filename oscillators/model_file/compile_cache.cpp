#include <impactlab/oscillators/model_file/compile_cache.hpp>

#include <dlfcn.h>
#include <fcntl.h>
#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <random>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include <impactlab/io/bad_input.hpp>
#include <impactlab/platform/run_program.hpp>
#include <impactlab/platform/sha256.hpp>

namespace impactlab {

namespace {

namespace fs = std::filesystem;

// run_program_logged's status for a compiler killed at its time limit
constexpr int compiler_killed_at_limit = -2;

// impactlab's flags, after the compiler's own from CompileOptions
constexpr std::array<std::string_view, 4> compiler_flags = {"-O2", "-fno-math-errno", "-shared", "-fPIC"};

// An open file descriptor, closed when it goes out of scope.
class FileDescriptor {
 public:
  explicit FileDescriptor(int descriptor = -1) : descriptor_(descriptor) {}
  FileDescriptor(FileDescriptor&& other) noexcept : descriptor_(std::exchange(other.descriptor_, -1)) {}
  FileDescriptor& operator=(FileDescriptor&& other) noexcept {
    if (this != &other) {
      if (descriptor_ >= 0) ::close(descriptor_);
      descriptor_ = std::exchange(other.descriptor_, -1);
    }
    return *this;
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (descriptor_ >= 0) ::close(descriptor_);
  }
  [[nodiscard]] int get() const { return descriptor_; }
  int release() { return std::exchange(descriptor_, -1); }
  explicit operator bool() const { return descriptor_ >= 0; }

 private:
  int descriptor_;
};

std::string system_error_text() { return std::strerror(errno); }

// Why an open folder may not hold objects to load, or empty: it must be a
// directory of this user that neither the group nor others may write.
std::string unsafe_folder_reason(const struct stat& info) {
  if (!S_ISDIR(info.st_mode)) return "is not a directory";
  if (info.st_uid != ::geteuid())
    return fmt::format("is owned by another user (uid {}, not {})", info.st_uid, ::geteuid());
  if ((info.st_mode & (S_IWGRP | S_IWOTH)) != 0)
    return fmt::format("is writable by others (mode {:04o})", info.st_mode & 07777);
  return {};
}

// Whether a file of the cache may be trusted as written by this program:
// regular, this user's, writable by nobody else, not empty.
bool trusted_file(int descriptor) {
  struct stat info {};
  return ::fstat(descriptor, &info) == 0 && S_ISREG(info.st_mode) && info.st_uid == ::geteuid() &&
         (info.st_mode & (S_IWGRP | S_IWOTH)) == 0 && info.st_size > 0;
}

// `name` inside the folder, opened for reading without following a symbolic link.
FileDescriptor open_inside(int folder, const std::string& name) {
  return FileDescriptor(::openat(folder, name.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC));
}

// The whole content of an open file, from its start; nothing when unreadable.
std::optional<std::string> read_all(int descriptor) {
  if (::lseek(descriptor, 0, SEEK_SET) != 0) return std::nullopt;
  std::string content;
  std::array<char, 65536> buffer{};
  for (;;) {
    const ssize_t got = ::read(descriptor, buffer.data(), buffer.size());
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) return std::nullopt;
    if (got == 0) return content;
    content.append(buffer.data(), static_cast<std::size_t>(got));
  }
}

// Writes `content` into a new file `name` inside the folder (mode 0600; an
// existing file or symbolic link of that name is an error, not a target).
bool write_new_file(int folder, const std::string& name, std::string_view content) {
  FileDescriptor file(
      ::openat(folder, name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600));
  if (!file) return false;
  while (!content.empty()) {
    const ssize_t written = ::write(file.get(), content.data(), content.size());
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) return false;
    content.remove_prefix(static_cast<std::size_t>(written));
  }
  return true;
}

// The first line of a file inside the folder (the compiler's log).
std::string first_line_inside(int folder, const std::string& name) {
  const FileDescriptor file = open_inside(folder, name);
  if (!file) return {};
  const std::string content = read_all(file.get()).value_or("");
  return content.substr(0, content.find('\n'));
}

// A name no other run uses at the same time: pid and random bits.
std::string unique_suffix() {
  std::random_device device;
  return fmt::format("{}-{:08x}", static_cast<long>(::getpid()), device());
}

// The object behind an open descriptor, loaded: the very file that was
// checked, whatever happens to its name meanwhile. The descriptor stays open
// while the object is loaded (LoadedObject::descriptor): glibc takes a name it
// has loaded before for the same library, so /proc/self/fd/N must not name
// another loaded object.
void* load_open_file(FileDescriptor& object, const fs::path& shown_as, LoadedObject& loaded) {
  void* handle =
      ::dlopen(fmt::format("/proc/self/fd/{}", object.get()).c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    loaded.why = fmt::format("cannot load {} ({})", shown_as.string(), ::dlerror());
    return nullptr;
  }
  loaded.handle = handle;
  loaded.descriptor = object.release();
  return handle;
}

// The folder at `path` (absolute), created with mode 0700 where missing (its
// parents as usual), opened without following a symbolic link and checked
// (unsafe_folder_reason). An invalid descriptor and the reason otherwise.
FileDescriptor open_private_folder(const fs::path& path, std::string& why) {
  std::error_code error;
  fs::create_directories(path.parent_path(), error);
  if (::mkdir(path.c_str(), 0700) != 0 && errno != EEXIST) {
    why = fmt::format("cannot be created ({})", system_error_text());
    return FileDescriptor();
  }
  struct stat link_info {};
  if (::lstat(path.c_str(), &link_info) == 0 && S_ISLNK(link_info.st_mode)) {
    why = "is a symbolic link";
    return FileDescriptor();
  }
  FileDescriptor folder(::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
  if (!folder) {
    why = fmt::format("cannot be opened ({})", system_error_text());
    return FileDescriptor();
  }
  struct stat info {};
  if (::fstat(folder.get(), &info) != 0) {
    why = fmt::format("cannot be examined ({})", system_error_text());
    return FileDescriptor();
  }
  why = unsafe_folder_reason(info);
  return why.empty() ? std::move(folder) : FileDescriptor();
}

// The cached object `name` in the folder, loaded, if it is the object this
// program wrote there: it and `name`.sha256 are trusted files and the
// object's SHA-256 is the recorded one. Null when any of that fails (the
// caller compiles anew); `loaded.why` is set only when a verified object fails to load.
void* load_verified(int folder, const fs::path& folder_path, const std::string& name,
                    LoadedObject& loaded) {
  FileDescriptor object = open_inside(folder, name);
  const FileDescriptor digest = open_inside(folder, name + ".sha256");
  if (!object || !digest || !trusted_file(object.get()) || !trusted_file(digest.get())) return nullptr;
  const std::optional<std::string> content = read_all(object.get());
  const std::optional<std::string> recorded = read_all(digest.get());
  if (!content || !recorded || *recorded != sha256_hex(*content) + "\n") return nullptr;
  return load_open_file(object, folder_path / name, loaded);
}

// Compiles `source` inside the open folder at `folder_path` into the object
// `name`, with its digest beside it, and loads it. Null and the reason in
// `loaded.why` when the compiler fails or the folder cannot be written.
void* compile_into(int folder, const fs::path& folder_path, const std::string& name,
                   const std::string& source, const CompileOptions& options, LoadedObject& loaded) {
  std::string& why = loaded.why;
  const std::string suffix = unique_suffix();
  const std::string source_name = fmt::format("{}.{}.c", name, suffix);
  const std::string temporary = fmt::format("{}.{}.tmp", name, suffix);
  const std::string digest_temporary = fmt::format("{}.{}.sha256.tmp", name, suffix);
  const std::string log = fmt::format("{}.{}.log", name, suffix);
  auto remove_inside = [folder](const std::string& file) { ::unlinkat(folder, file.c_str(), 0); };
  if (!write_new_file(folder, source_name, source)) {
    why = fmt::format("cache directory {} is not writable ({})", folder_path.string(), system_error_text());
    remove_inside(source_name);
    return nullptr;
  }
  // an argument vector, no shell, absolute paths: the paths are data, never options
  std::vector<std::string> command = options.compiler;
  for (const std::string_view flag : compiler_flags) command.emplace_back(flag);
  command.insert(command.end(), {"-o", (folder_path / temporary).string(),
                                 (folder_path / source_name).string(), "-lm"});
  const int status =
      run_program_logged(command, (folder_path / log).string(), options.compile_time_limit_s);
  const std::string detail = first_line_inside(folder, log);
  remove_inside(source_name);
  remove_inside(log);
  const std::string compiler = describe_program(options.compiler);
  if (status == compiler_killed_at_limit) {
    remove_inside(temporary);
    throw BadInput("model", fmt::format("{} bytes of C", source.size()),
                   fmt::format("the C compiler '{}' ran past its limit of {} s on this model: "
                               "write its expressions with fewer or smaller terms",
                               compiler, options.compile_time_limit_s));
  }
  FileDescriptor object = open_inside(folder, temporary);
  if (status != 0 || !object || !trusted_file(object.get())) {
    why = status < 0 ? fmt::format("the C compiler '{}' could not be started or was killed", compiler)
          : status > 0 ? fmt::format("the C compiler '{}' failed (status {}{}{})", compiler, status,
                                     detail.empty() ? "" : ": ", detail)
                       : fmt::format("the C compiler '{}' wrote no object", compiler);
    remove_inside(temporary);
    return nullptr;
  }
  const std::optional<std::string> content = read_all(object.get());
  if (!content || !write_new_file(folder, digest_temporary, sha256_hex(*content) + "\n")) {
    why = fmt::format("cache directory {} is not writable", folder_path.string());
    remove_inside(temporary);
    remove_inside(digest_temporary);
    return nullptr;
  }
  // atomic renames: a concurrent run sees no object, an object without its
  // digest (and compiles anew) or both
  if (::renameat(folder, temporary.c_str(), folder, name.c_str()) != 0 ||
      ::renameat(folder, digest_temporary.c_str(), folder, (name + ".sha256").c_str()) != 0) {
    why = fmt::format("cannot move the compiled model into {} ({})", folder_path.string(),
                      system_error_text());
    remove_inside(temporary);
    remove_inside(digest_temporary);
    return nullptr;
  }
  return load_open_file(object, folder_path / name, loaded);
}

// Compiles and loads in a fresh private temporary folder, removed afterwards:
// the way round a cache folder that may not be used.
LoadedObject compile_without_cache(const std::string& name, const std::string& source,
                                   const CompileOptions& options, std::string note) {
  LoadedObject loaded;
  loaded.cache_note = std::move(note);
  std::error_code error;
  std::string pattern = (fs::temp_directory_path(error) / "impactlab-model-XXXXXX").string();
  if (error || ::mkdtemp(pattern.data()) == nullptr) {
    loaded.why = fmt::format("{}, and no private temporary folder could be made", loaded.cache_note);
    return loaded;
  }
  const fs::path folder_path(pattern);
  const FileDescriptor folder = open_private_folder(folder_path, loaded.why);
  try {
    if (folder) compile_into(folder.get(), folder_path, name, source, options, loaded);
  } catch (...) {
    fs::remove_all(folder_path, error);
    throw;
  }
  if (!loaded.handle)
    loaded.why = fmt::format("{}; temporary folder {}: {}", loaded.cache_note, folder_path.string(),
                             loaded.why);
  fs::remove_all(folder_path, error);
  return loaded;
}

// The user's home directory from the password database (empty where none).
std::string home_from_password_database() {
  std::array<char, 16384> buffer{};
  struct passwd entry {};
  struct passwd* found = nullptr;
  if (::getpwuid_r(::geteuid(), &entry, buffer.data(), buffer.size(), &found) != 0 || !found ||
      !found->pw_dir || found->pw_dir[0] != '/')
    return {};
  return found->pw_dir;
}

}  // namespace

CompileOptions compile_options_from_environment() {
  CompileOptions options;
  if (const char* compiler = std::getenv("IMPACTLAB_CC"); compiler) {
    std::vector<std::string> words = split_on_spaces(compiler);
    if (!words.empty()) options.compiler = std::move(words);
  }
  const std::string home = [] {
    const char* variable = std::getenv("HOME");
    return variable && *variable ? std::string(variable) : home_from_password_database();
  }();
  if (const char* cache = std::getenv("IMPACTLAB_CACHE_DIR"); cache && *cache) {
    options.cache_directory = cache;
  } else if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
    options.cache_directory = (fs::path(xdg) / "impactlab").string();
  } else if (!home.empty()) {
    options.cache_directory = (fs::path(home) / ".cache" / "impactlab").string();
  }
  return options;
}

LoadedObject load_or_compile(const std::string& source, const CompileOptions& options) {
  std::vector<std::string> command = options.compiler;
  for (const std::string_view flag : compiler_flags) command.emplace_back(flag);
  const std::string key = fmt::format("{}\n{}", source, describe_program(command));
  const std::string name = fmt::format("model-{}.so", sha256_hex(key).substr(0, 32));
  if (options.cache_directory.empty())
    return compile_without_cache(name, source, options,
                                 "no cache folder (set IMPACTLAB_CACHE_DIR or HOME): compiled "
                                 "without a cache");

  // absolute, so that no path given to the compiler begins with '-'
  std::error_code error;
  fs::path folder_path = fs::absolute(options.cache_directory, error).lexically_normal();
  if (folder_path.has_parent_path() && !folder_path.has_filename()) folder_path = folder_path.parent_path();
  std::string why;
  const FileDescriptor folder = open_private_folder(folder_path, why);
  if (!folder)
    return compile_without_cache(
        name, source, options,
        fmt::format("cache directory {} {}: compiled without the cache", folder_path.string(), why));

  LoadedObject loaded;
  loaded.path = (folder_path / name).string();
  load_verified(folder.get(), folder_path, name, loaded);
  if (loaded.handle || !loaded.why.empty()) {
    loaded.from_cache = loaded.handle != nullptr;
    return loaded;
  }
  compile_into(folder.get(), folder_path, name, source, options, loaded);
  if (!loaded.handle) loaded.path.clear();
  return loaded;
}

}  // namespace impactlab
