// SPDX-License-Identifier: MIT
// Fuzz target: the cache entry reader (decode_cache_entry, every cache's
// format) under a fixed key, and the LOD chain deserializer on what it
// yields and on the raw input (a payload that passed its checksum is still
// checked). Any bytes must end in a miss or a value, never a crash, an
// exception or an allocation of what a header claims.
#include <cstdint>
#include <string_view>

#include "terrasprite/common/cache_entry.h"
#include "terrasprite/objects/representation_cache.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The key the committed seeds in corpus/cache/ were written with.
  constexpr std::string_view kKey = "terrasprite fuzz entry";
  const terrasprite::CacheEntryRead r = terrasprite::decode_cache_entry(bytes, kKey, 1 << 24);
  if (r.payload) (void)terrasprite::deserialize_lod_chain(*r.payload, 4);
  (void)terrasprite::deserialize_lod_chain(bytes, 4);
  return 0;
}
