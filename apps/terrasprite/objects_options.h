// SPDX-License-Identifier: MIT
// `--objects default|FILE` for the commands that draw a flythrough (render,
// bench render); the loading is terrasprite/objects/attach_objects.h.
#pragma once
#include <CLI/CLI.hpp>

#include "terrasprite/objects/attach_objects.h"

namespace terrasprite::cli {

/// --objects, --models-dir, --objects-cache.
void add_objects_options(CLI::App& cmd, ObjectsOptions& o);

}  // namespace terrasprite::cli
