// SPDX-License-Identifier: MIT
// terrasprite: the command-line tool. Sub-commands follow the pipeline:
// info (load terrain) -> render (fly a path) -> compare (score images) ->
// bench (whole-system figures) -> demo (all of it on the default terrain).

#include <fmt/format.h>
#include <malloc.h>

#include <CLI/CLI.hpp>
#include <algorithm>

#include "cli_common.h"
#include "commands.h"
#include "terrasprite/common/error.h"
#include "terrasprite/output/interrupt_cleanup.h"

namespace {

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

// Renderers that allocate a frame per draw (the GL ones' read-back, the
// reference ray caster) hand glibc blocks of megabytes, which it would map
// afresh (mmap) and return to the system after each frame, page-faulting every
// buffer again. Keep blocks up to 32 MB (glibc's ceiling for this setting) on
// the heap and up to 128 MB of freed heap. Figures:
// docs/results/2026-11-30-render-heap-trim.md.
void keep_frame_buffers_resident() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 128 << 20);
}

}  // namespace

int main(int argc, char** argv) {
  keep_frame_buffers_resident();             // before the first allocation of a frame
  terrasprite::install_interrupt_cleanup();  // before any thread starts
  CLI::App app{"terrasprite: fast terrain flythroughs measured against full-quality images"};
  app.require_subcommand(1);
  // Accepted after any sub-command too (fallthrough): it governs every output it writes.
  app.fallthrough();
  terrasprite::OutputPolicy policy;  // outlives the parse, whose callbacks read it
  app.add_flag("--overwrite", policy.overwrite,
               "replace existing outputs that terrasprite did not write (never a directory "
               "holding the working directory, a device or a link)");
  terrasprite::cli::add_info(app, policy);
  terrasprite::cli::add_render(app, policy);
  terrasprite::cli::add_compare(app, policy);
  terrasprite::cli::add_tile(app, policy);
  terrasprite::cli::add_objects(app, policy);
  terrasprite::cli::add_bench(app, policy);
  terrasprite::cli::add_demo(app, policy);
#ifdef TS_HAVE_VIEWER
  terrasprite::cli::add_view(app, policy);
#endif
  terrasprite::cli::require_finite_numbers(app);
  int rc = 0;
  std::string error;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    error = e.what();
    rc = 2;
  } catch (const terrasprite::InputError& e) {
    error = terrasprite::cli::with_option_names(e.what());
    rc = 2;
  } catch (const terrasprite::DeviceError& e) {
    error = e.what();
    rc = 3;
  } catch (const std::bad_alloc&) {
    error = "out of memory";
    rc = 2;
  } catch (const std::exception& e) {
    // A bug, not a user error: still one line, never an abort.
    error = std::string("internal error: ") + e.what();
    rc = 1;
  }
  // A failure caused by an interrupt's clean-up is not the story: the interrupt is.
  terrasprite::hold_if_interrupted();
  if (rc != 0) fmt::print(stderr, "terrasprite: {}\n", one_line(error));
  return rc;
}
