// SPDX-License-Identifier: MIT
// Where terrasprite keeps what it can rebuild: one root for every cache
// (objects' representations and quality tables, COG max-height bounds), each
// in a folder of its own under it. Never next to a user's files.
#pragma once
#include <string>

namespace terrasprite {

/// $TERRASPRITE_CACHE when set and not empty, else $XDG_CACHE_HOME/terrasprite,
/// else $HOME/.cache/terrasprite, else <temp>/terrasprite-cache. The folder
/// may not exist yet (writers create what they need). `from_env`, when given,
/// is set to whether TERRASPRITE_CACHE chose it (the user asked for caching).
std::string cache_root(bool* from_env = nullptr);

}  // namespace terrasprite
