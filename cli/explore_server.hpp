// The HTTP plumbing of `impactlab explore`: a server on 127.0.0.1 that
// serves the page's files (web/, among the program's files) and the JSON API
// over api/explore_requests.hpp and api/explore_jobs.hpp. Every request must
// carry the token (the address's ?token=, or an `Authorization: token ...`
// header, as the page's own requests do), name the server itself as its Host
// (127.0.0.1:PORT or localhost:PORT: no DNS rebinding) and come from no
// other origin (Origin absent or the same).
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include <impactlab/api/explore_requests.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab::cli {

struct ExploreServerSettings {
  std::string scene_source;  // the scene as given: a built-in name or a path
  Scene scene;               // loaded
  int port = 0;              // 0: any free port
  std::string token;         // what every request must carry
  std::filesystem::path web_folder;  // the page's files
  ExploreLimits limits;
  int http_threads = 16;     // requests served at once
};

// Serves until the process ends; `on_listening(url)` runs once the port is
// bound (the url carries the port and the token). Throws BadInput (key
// `port`) where the port cannot be bound.
void serve_explorer(const ExploreServerSettings& settings,
                    const std::function<void(const std::string& url)>& on_listening);

// 32 hexadecimal digits from the system's random device.
std::string random_token();

}  // namespace impactlab::cli
