// SPDX-License-Identifier: MIT
// One file format for every cache entry (objects' representations and
// quality tables, COG max-height bounds): the entry records the full key it
// was built for and a checksum of its payload, so an entry of another model,
// file or option set, a truncated or a damaged one is a miss, never a hit.
//
//   "TSCACHE\n"                 8 bytes of magic
//   u32 kCacheEntryFormat       this layout's version
//   u32 key size, key bytes     what the entry depends on (at most kMaxCacheKey bytes)
//   u64 payload size            what the frame decodes to
//   one zstd frame              level 1, recording the payload size and its
//                               content checksum (XXH64, verified by libzstd)
//
// Integers are little-endian. Readers compare the key byte for byte before
// decoding anything, refuse a payload size above what the caller can use
// before allocating it, and grow the payload only as the frame yields data.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace terrasprite {

inline constexpr std::uint32_t kCacheEntryFormat = 1;
inline constexpr std::size_t kMaxCacheKey = 1 << 16;

/// 64-bit FNV-1a of `bytes`, continuing from `h`: the content digest that
/// cache keys carry.
std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = 1469598103934665603ull);

/// The entry of `payload` under `key` (at most kMaxCacheKey bytes). Empty when
/// zstd fails (out of memory).
std::string encode_cache_entry(std::string_view key, std::string_view payload);

/// What a lookup found.
struct CacheEntryRead {
  std::optional<std::string> payload;  ///< the intact payload of the right key
  /// Empty with no payload: no entry there. Else why the entry is unusable
  /// ("written for other inputs", "truncated", ...): one phrase for a note.
  std::string problem;
};

/// The payload of `bytes` when it is an entry of exactly `key` whose payload
/// is at most `max_payload` bytes, complete and matches its checksum.
/// Never throws on any bytes; allocates at most what the frame decodes to.
CacheEntryRead decode_cache_entry(std::string_view bytes, std::string_view key,
                                  std::uint64_t max_payload);

/// decode_cache_entry of the file `file`; a missing file is an empty result,
/// one larger than an entry of `key` holding `max_payload` bytes can be is
/// refused unread. Never throws.
CacheEntryRead read_cache_entry(const std::filesystem::path& file, std::string_view key,
                                std::uint64_t max_payload);

}  // namespace terrasprite
