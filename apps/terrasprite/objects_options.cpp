// SPDX-License-Identifier: MIT
#include "objects_options.h"

namespace terrasprite::cli {

void add_objects_options(CLI::App& cmd, ObjectsOptions& o) {
  cmd.add_option("--objects", o.scene,
                 "objects on the terrain: 'default' (400 instances of 8 models from "
                 "--models-dir) or a scene file (JSON); GL modes only");
  cmd.add_option("--models-dir", o.models_dir, "where the default scene's models are")
      ->capture_default_str();
  cmd.add_option("--objects-cache", o.cache,
                 "where the objects' LOD chains and impostors are cached, or 'off' "
                 "(default: ~/.cache/terrasprite/objects)");
}

}  // namespace terrasprite::cli
