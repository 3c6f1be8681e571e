#include "explore_server.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include <netinet/in.h>
#include <sys/socket.h>

#include <fmt/format.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include <impactlab/api/explore_jobs.hpp>
#include <impactlab/io/bad_input.hpp>

namespace impactlab::cli {

namespace {

using nlohmann::json;

// the page's files, read once at the start, those of its folders too (the
// plotting library, web/vendor/uplot/): only these names are served, so no
// request reaches another file
struct WebFile {
  std::string content;
  std::string mime;
};

std::string mime_of(const std::filesystem::path& path) {
  const std::string extension = path.extension().string();
  if (extension == ".html") return "text/html; charset=utf-8";
  if (extension == ".js") return "text/javascript; charset=utf-8";
  if (extension == ".css") return "text/css; charset=utf-8";
  if (extension == ".png") return "image/png";
  return "text/plain; charset=utf-8";
}

std::map<std::string, WebFile> read_web_files(const std::filesystem::path& folder) {
  std::map<std::string, WebFile> files;
  std::error_code error;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder, error)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    // named by its path under the folder: explore.js, vendor/uplot/uPlot.iife.min.js
    files[entry.path().lexically_relative(folder).generic_string()] = {text.str(),
                                                                       mime_of(entry.path())};
  }
  if (!files.contains("explore.html"))
    throw BadInput("explore", folder.string(),
                   "the page's files are missing (web/explore.html among the program's files)");
  return files;
}

// equal texts, compared in a time that does not depend on where they differ
bool same_secret(const std::string& given, const std::string& token) {
  if (given.size() != token.size()) return false;
  unsigned char difference = 0;
  for (std::size_t i = 0; i < token.size(); ++i)
    difference |= static_cast<unsigned char>(given[i] ^ token[i]);
  return difference == 0;
}

// JSON as it is: cpp-httplib compresses a body typed exactly
// "application/json" for a browser that accepts Brotli, at a cost of
// hundreds of milliseconds for a time series; with its charset named the
// type is the same to the browser and the body goes out uncompressed
void send_json(httplib::Response& response, int status, const json& body) {
  response.status = status;
  response.set_header("Cache-Control", "no-store");
  response.set_content(body.dump(), "application/json; charset=utf-8");
}

void send_error(httplib::Response& response, int status, const std::string& key,
                const std::string& value, const std::string& message) {
  send_json(response, status,
            {{"error", {{"key", key}, {"value", value}, {"message", message}}}});
}

json parse_body(const httplib::Request& request) {
  json body = json::parse(request.body, nullptr, false);
  if (body.is_discarded() || !body.is_object())
    throw BadInput("body", request.body.substr(0, 80), "expected a JSON object");
  return body;
}

const json& member(const json& body, const char* name) {
  static const json empty_object = json::object();
  return body.contains(name) ? body.at(name) : empty_object;
}

// a text member of the body, empty where it is absent or not a text
std::string text_member(const json& body, const char* name) {
  return body.contains(name) && body.at(name).is_string() ? body.at(name).get<std::string>() : "";
}

// Debian's cpp-httplib (0.11) listens with a backlog of 5 connections,
// compiled into its library: a burst of requests overflows it and the
// kernel resets some. Listening again on the same socket with a longer
// backlog widens the queue (Linux); the socket is the one bound to `port`.
void widen_listen_backlog(int port) {
  for (int descriptor = 0; descriptor < 1024; ++descriptor) {
    sockaddr_in address{};
    socklen_t length = sizeof address;
    int listening = 0;
    socklen_t flag_length = sizeof listening;
    if (::getsockname(descriptor, reinterpret_cast<sockaddr*>(&address), &length) != 0 ||
        address.sin_family != AF_INET || ntohs(address.sin_port) != port)
      continue;
    if (::getsockopt(descriptor, SOL_SOCKET, SO_ACCEPTCONN, &listening, &flag_length) == 0 &&
        listening != 0)
      ::listen(descriptor, SOMAXCONN);
  }
}

}  // namespace

std::string random_token() {
  std::random_device device;
  std::string token;
  for (int k = 0; k < 4; ++k) token += fmt::format("{:08x}", device());
  return token;
}

void serve_explorer(const ExploreServerSettings& settings,
                    const std::function<void(const std::string& url)>& on_listening) {
  const std::map<std::string, WebFile> web = read_web_files(settings.web_folder);
  const ExploreLimits& limits = settings.limits;
  ExploreJobs jobs(limits.max_live_jobs);

  httplib::Server server;
  const int http_threads = settings.http_threads;
  server.new_task_queue = [http_threads] { return new httplib::ThreadPool(http_threads); };
  server.set_payload_max_length(limits.max_body_bytes);
  server.set_read_timeout(5, 0);
  server.set_write_timeout(5, 0);
  // an idle kept-alive connection holds a worker: let it go soon
  server.set_keep_alive_timeout(1);
  // a response's header and body leave at once, not after the client's delayed ACK
  server.set_tcp_nodelay(true);
  // SO_REUSEADDR alone: cpp-httplib's default adds SO_REUSEPORT, with which a
  // second server (any program of the same user) could bind the same port
  // and take some of the page's requests
  server.set_socket_options([](int socket) {
    const int yes = 1;
    ::setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });

  int port = settings.port;
  if (port == 0) {
    port = server.bind_to_any_port("127.0.0.1");
  } else if (!server.bind_to_port("127.0.0.1", port)) {
    port = -1;
  }
  if (port <= 0)
    throw BadInput("port", std::to_string(settings.port), "cannot listen on 127.0.0.1 there");
  widen_listen_backlog(port);
  const std::vector<std::string> hosts = {fmt::format("127.0.0.1:{}", port),
                                          fmt::format("localhost:{}", port)};

  // every request: our own Host, no foreign Origin, the token
  server.set_pre_routing_handler([&](const httplib::Request& request,
                                     httplib::Response& response) {
    const std::string host = request.get_header_value("Host");
    if (std::find(hosts.begin(), hosts.end(), host) == hosts.end()) {
      send_error(response, 403, "Host", host, "not this server's address (127.0.0.1 or localhost)");
      return httplib::Server::HandlerResponse::Handled;
    }
    if (request.has_header("Origin") && request.get_header_value("Origin") != "http://" + host) {
      send_error(response, 403, "Origin", request.get_header_value("Origin"),
                 "requests from another origin are refused");
      return httplib::Server::HandlerResponse::Handled;
    }
    const std::string authorization = request.get_header_value("Authorization");
    const bool by_query = same_secret(request.get_param_value("token"), settings.token);
    const bool by_header = authorization.rfind("token ", 0) == 0 &&
                           same_secret(authorization.substr(6), settings.token);
    if (!by_query && !by_header) {
      send_error(response, 403, "token", "", "missing or wrong token: open the address the server printed");
      return httplib::Server::HandlerResponse::Handled;
    }
    response.set_header("X-Content-Type-Options", "nosniff");
    return httplib::Server::HandlerResponse::Unhandled;
  });

  auto serve_file = [&](const std::string& name, httplib::Response& response) {
    const auto found = web.find(name);
    if (found == web.end()) {
      send_error(response, 404, "path", name, "no such file of the page");
      return;
    }
    response.set_header("Cache-Control", "no-store");
    response.set_content(found->second.content, found->second.mime.c_str());
  };
  // the page names its own files with the token (its requests to the API
  // send it as a header): no cookie, so that it works framed in a notebook
  std::string page = web.at("explore.html").content;
  for (std::size_t at = page.find("{{token}}"); at != std::string::npos; at = page.find("{{token}}"))
    page.replace(at, 9, settings.token);
  server.Get("/", [&](const httplib::Request&, httplib::Response& response) {
    response.set_header("Cache-Control", "no-store");
    // the page runs its own script and style alone, and names no other site
    response.set_header("Content-Security-Policy",
                        "default-src 'self'; img-src 'self' data: blob:; object-src 'none'");
    response.set_header("Referrer-Policy", "no-referrer");
    response.set_content(page, "text/html; charset=utf-8");
  });
  // a name of one to three parts, none beginning with a dot; only the
  // names read above are found
  server.Get(R"(/web/([A-Za-z0-9_-][A-Za-z0-9_.-]*(?:/[A-Za-z0-9_-][A-Za-z0-9_.-]*){0,2}))",
             [&](const httplib::Request& request, httplib::Response& response) {
    serve_file(request.matches[1], response);
  });

  server.Get("/api/scene", [&](const httplib::Request&, httplib::Response& response) {
    json description = explore_scene_description(settings.scene);
    description["scene_source"] = settings.scene_source;
    description["limits"] = {{"max_periods", limits.max_periods},
                             {"max_samples", limits.max_samples},
                             {"max_section_points", limits.max_section_points},
                             {"max_columns", limits.max_columns},
                             {"max_column_points", limits.max_column_points}};
    send_json(response, 200, description);
  });

  // a view's job: validated here (the scene's own messages), run on its thread
  server.Post("/api/jobs", [&](const httplib::Request& request, httplib::Response& response) {
    try {
      const json body = parse_body(request);
      const std::string kind = text_member(body, "kind");
      const Scene scene = explore_scene(settings.scene, member(body, "values"), limits);
      const json& options = member(body, "options");
      ExploreJobs::Work work;
      if (kind == "trajectory") {
        work = [scene, view = trajectory_view(options, limits)](ExploreJobControl& control) {
          return run_trajectory(scene, view, {[&](double f) { control.progress(f); }, {}});
        };
      } else if (kind == "section") {
        work = [scene, view = section_view(options, limits)](ExploreJobControl& control) {
          return run_section(scene, view, {[&](double f) { control.progress(f); }, {}});
        };
      } else if (kind == "diagram") {
        work = [scene, view = diagram_view(options, scene, limits)](ExploreJobControl& control) {
          return run_diagram(scene, view,
                             {[&](double f) { control.progress(f); },
                              [&](const json& column) { control.add_item(column); }});
        };
      } else if (kind == "orbit") {
        work = [scene, view = orbit_view(options, scene, limits)](ExploreJobControl& control) {
          return run_orbit(scene, view, {[&](double f) { control.progress(f); }, {}});
        };
      } else {
        throw BadInput("kind", kind, "expected trajectory, section, diagram or orbit");
      }
      const json& sequence = member(body, "sequence");
      const std::uint64_t order = sequence.is_number_unsigned() ? sequence.get<std::uint64_t>() : 0;
      std::string client = text_member(body, "client");
      client.resize(std::min<std::size_t>(client.size(), 64));
      send_json(response, 202, {{"id", jobs.start(kind, std::move(work), order, client)}});
    } catch (const BadInput& bad) {
      send_error(response, 400, bad.key(), bad.value(), bad.what());
    } catch (const ExploreSuperseded& overtaken) {
      send_error(response, 409, "sequence", "", overtaken.what());
    } catch (const ExploreBusy& busy) {
      send_error(response, 503, "jobs", "", busy.what());
    }
  });

  server.Get(R"(/api/jobs/(\d{1,18}))", [&](const httplib::Request& request,
                                             httplib::Response& response) {
    const std::uint64_t id = std::stoull(request.matches[1]);
    std::size_t first_item = 0;
    long wait_ms = 0;
    try {
      if (request.has_param("from")) first_item = std::stoul(request.get_param_value("from"));
      if (request.has_param("wait")) wait_ms = std::stol(request.get_param_value("wait"));
    } catch (const std::exception&) {
      send_error(response, 400, "from", request.get_param_value("from"), "expected whole numbers");
      return;
    }
    // a poll waits at most a second, so that waiting polls cannot hold every worker long
    wait_ms = std::clamp(wait_ms, 0L, 1000L);
    const json state = jobs.poll(id, first_item, std::chrono::milliseconds(wait_ms));
    if (state.is_null()) {
      send_error(response, 404, "job", std::to_string(id), "no such job (or long finished)");
      return;
    }
    send_json(response, 200, state);
  });

  server.Post("/api/export", [&](const httplib::Request& request, httplib::Response& response) {
    try {
      const json body = parse_body(request);
      const Scene scene = explore_scene(settings.scene, member(body, "values"), limits);
      const ExploreExport exported =
          explore_export(text_member(body, "kind"), member(body, "options"),
                         settings.scene_source, settings.scene, scene, limits);
      json commands = json::array();
      for (const auto& words : exported.commands) commands.push_back(shell_command(words));
      send_json(response, 200,
                {{"scene_toml", exported.scene_toml},
                 {"commands", commands},
                 {"argv", exported.commands},
                 {"python", exported.python_calls}});
    } catch (const BadInput& bad) {
      send_error(response, 400, bad.key(), bad.value(), bad.what());
    }
  });

  server.set_exception_handler([](const httplib::Request&, httplib::Response& response,
                                  std::exception_ptr failure) {
    std::string message = "internal error";
    try {
      std::rethrow_exception(failure);
    } catch (const std::exception& error) {
      message = error.what();
    } catch (...) {
    }
    send_error(response, 500, "", "", message);
  });

  on_listening(fmt::format("http://127.0.0.1:{}/?token={}", port, settings.token));
  server.listen_after_bind();
}

}  // namespace impactlab::cli
