// SPDX-License-Identifier: MIT
// terrasprite: the command-line tool. Sub-commands follow the pipeline:
// info (load terrain) -> render (fly a path) -> compare (score images) ->
// bench (whole-system figures) -> demo (all of it on the default terrain).

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>

#include "commands.h"
#include "terrasprite/error.h"

namespace {

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"terrasprite: fast terrain flythroughs measured against full-quality images"};
  app.require_subcommand(1);
  terrasprite::cli::add_info(app);
  terrasprite::cli::add_render(app);
  terrasprite::cli::add_compare(app);
  terrasprite::cli::add_bench(app);
  terrasprite::cli::add_demo(app);
#ifdef TS_HAVE_VIEWER
  terrasprite::cli::add_view(app);
#endif
  int rc = 0;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "terrasprite: {}\n", one_line(e.what()));
    rc = 2;
  } catch (const terrasprite::InputError& e) {
    fmt::print(stderr, "terrasprite: {}\n", one_line(e.what()));
    rc = 2;
  } catch (const terrasprite::DeviceError& e) {
    fmt::print(stderr, "terrasprite: {}\n", one_line(e.what()));
    rc = 3;
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "terrasprite: out of memory\n");
    rc = 2;
  }
  return rc;
}
