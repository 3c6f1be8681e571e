// `impactlab explore [SCENE] [--port P]`: serves the explorer's page on
// 127.0.0.1 (cli/explore_server.hpp) and prints its address with a random
// token, Jupyter-style; serves until interrupted (Ctrl-C, SIGTERM).
#include <iostream>
#include <memory>

#include <impactlab/api/scene_loading.hpp>
#include "command.hpp"
#include "commands.hpp"
#include "explore_server.hpp"
#include "program_files.hpp"
#include "table_options.hpp"

namespace impactlab::cli {

namespace {

struct ExploreOptions {
  std::string scene;
  int port = 0;
};

int run_explore(const ExploreOptions& options) {
  ExploreServerSettings settings;
  settings.scene_source = options.scene;
  settings.scene = load_scene(options.scene);
  settings.port = options.port;
  settings.token = random_token();
  settings.web_folder = program_file("web");
  serve_explorer(settings, [](const std::string& url) {
    std::cout << "impactlab explore: serving on 127.0.0.1; open\n    " << url
              << "\n(Ctrl-C stops it)" << std::endl;
  });
  return exit_done;
}

}  // namespace

Command add_explore_command(CLI::App& app) {
  auto* command = add_subcommand(
      app, "explore",
      "serve an interactive page on 127.0.0.1 (time series, section, orbit diagram, periodic "
      "orbits) and print its address with a token");
  auto options = std::make_shared<ExploreOptions>();
  TableOptions table(*command, "explore");
  table.add("scene", options->scene);
  table.add("port", options->port);
  return {command,
          [options](const std::vector<std::string>&) { return run_explore(*options); },
          "explore"};
}

}  // namespace impactlab::cli
