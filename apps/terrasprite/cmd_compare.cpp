// SPDX-License-Identifier: MIT
// terrasprite compare: placeholder until the quality module lands (issue 3).
#include "commands.h"
#include "terrasprite/error.h"

namespace terrasprite::cli {

void add_compare(CLI::App& app) {
  auto* cmd = app.add_subcommand("compare", "quality metrics between two images (not built yet)");
  cmd->allow_extras();
  cmd->callback([] { throw InputError("compare: the image-quality module is not built yet"); });
}

}  // namespace terrasprite::cli
