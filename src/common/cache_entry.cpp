// SPDX-License-Identifier: MIT
#include "terrasprite/common/cache_entry.h"

#include <fmt/format.h>
#include <zstd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <memory>

namespace terrasprite {
namespace {

constexpr char kEntryMagic[8] = {'T', 'S', 'C', 'A', 'C', 'H', 'E', '\n'};
constexpr std::size_t kFixedHeader = 8 + 4 + 4 + 8;  // magic, format, key size, payload size

template <class T>
void append_raw(std::string& out, T x) {
  out.append(reinterpret_cast<const char*>(&x), sizeof x);
}

// Reads a T from the front of `in` (false when too short).
template <class T>
bool take_raw(std::string_view& in, T& x) {
  if (in.size() < sizeof x) return false;
  std::memcpy(&x, in.data(), sizeof x);
  in.remove_prefix(sizeof x);
  return true;
}

/// Decompresses the one zstd frame `in`, which claims `size` bytes, into
/// `out`, growing it as data arrives: a size field claiming more than the
/// frame holds allocates no more than the frame yields. False when the frame
/// is corrupt (its checksum included), holds another size or has bytes after it.
bool decompress_frame(std::string_view in, std::uint64_t size, std::string& out) {
  constexpr std::uint64_t kFirstChunk = 1 << 20;
  const std::unique_ptr<ZSTD_DCtx, std::size_t (*)(ZSTD_DCtx*)> d(ZSTD_createDCtx(), ZSTD_freeDCtx);
  if (!d) return false;
  ZSTD_inBuffer src{in.data(), in.size(), 0};
  out.clear();
  std::size_t done = 0;
  for (;;) {
    if (done == out.size() && out.size() < size)
      out.resize(std::size_t(std::min<std::uint64_t>(
          size, std::max<std::uint64_t>(kFirstChunk, 2 * std::uint64_t(out.size())))));
    ZSTD_outBuffer dst{out.data(), out.size(), done};
    const std::size_t read_before = src.pos;
    const std::size_t ret = ZSTD_decompressStream(d.get(), &dst, &src);
    if (ZSTD_isError(ret)) return false;
    const bool progress = dst.pos != done || src.pos != read_before;
    done = dst.pos;
    if (ret == 0) return done == size && src.pos == src.size;
    if (!progress) return false;  // input used up, or more output than claimed
  }
}

/// Why the frame `frame` cannot hold `size` bytes with a checksum, or nullptr.
/// The checksum flag is bit 2 of the frame header descriptor, the byte after
/// the 4-byte magic number (RFC 8878, 3.1.1.1.1).
const char* frame_problem(std::string_view frame, std::uint64_t size) {
  const unsigned long long content = ZSTD_getFrameContentSize(frame.data(), frame.size());
  if (content == ZSTD_CONTENTSIZE_ERROR) return "truncated or not a zstd frame";
  if (content == ZSTD_CONTENTSIZE_UNKNOWN) return "no payload size";
  std::uint32_t magic = 0;
  std::memcpy(&magic, frame.data(), 4);
  if (magic != ZSTD_MAGICNUMBER) return "not a zstd frame";  // a skippable frame
  if ((std::uint8_t(frame[4]) & 0x04) == 0) return "a payload without a checksum";
  if (content != size) return "a payload size its data does not have";
  if (ZSTD_findFrameCompressedSize(frame.data(), frame.size()) != frame.size()) return "truncated";
  return nullptr;
}

}  // namespace

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h) {
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}

std::string encode_cache_entry(std::string_view key, std::string_view payload) {
  std::string out(kEntryMagic, sizeof kEntryMagic);
  append_raw(out, kCacheEntryFormat);
  append_raw(out, std::uint32_t(key.size()));
  out.append(key);
  append_raw(out, std::uint64_t(payload.size()));
  // Level 1: fast to write and to read back; an impostor atlas is mostly
  // empty texels and shrinks several times.
  const std::size_t header = out.size();
  out.resize(header + ZSTD_compressBound(payload.size()));
  const std::unique_ptr<ZSTD_CCtx, std::size_t (*)(ZSTD_CCtx*)> c(ZSTD_createCCtx(), ZSTD_freeCCtx);
  if (!c) return {};
  ZSTD_CCtx_setParameter(c.get(), ZSTD_c_compressionLevel, 1);
  ZSTD_CCtx_setParameter(c.get(), ZSTD_c_checksumFlag, 1);
  ZSTD_CCtx_setParameter(c.get(), ZSTD_c_contentSizeFlag, 1);
  const std::size_t n = ZSTD_compress2(c.get(), out.data() + header, out.size() - header,
                                       payload.data(), payload.size());
  if (ZSTD_isError(n)) return {};
  out.resize(header + n);
  return out;
}

CacheEntryRead decode_cache_entry(std::string_view bytes, std::string_view key,
                                  std::uint64_t max_payload) {
  CacheEntryRead r;
  std::string_view in = bytes;
  std::uint32_t format = 0, key_size = 0;
  std::uint64_t size = 0;
  if (in.size() < kFixedHeader || std::memcmp(in.data(), kEntryMagic, 8) != 0) {
    r.problem = "not a terrasprite cache entry";
    return r;
  }
  in.remove_prefix(8);
  take_raw(in, format);
  if (format != kCacheEntryFormat) {
    r.problem = "another entry format";
    return r;
  }
  take_raw(in, key_size);
  if (key_size > in.size()) {
    r.problem = "truncated";
    return r;
  }
  if (in.substr(0, key_size) != key) {
    r.problem = "written for other inputs (another model, file or options)";
    return r;
  }
  in.remove_prefix(key_size);
  if (!take_raw(in, size)) {
    r.problem = "truncated";
    return r;
  }
  if (size > max_payload) {
    r.problem =
        fmt::format("claims {} bytes, more than such an entry holds ({})", size, max_payload);
    return r;
  }
  if (const char* p = frame_problem(in, size)) {
    r.problem = p;
    return r;
  }
  std::string payload;
  if (!decompress_frame(in, size, payload)) {
    r.problem = "checksum mismatch or corrupt data";
    return r;
  }
  r.payload = std::move(payload);
  return r;
}

CacheEntryRead read_cache_entry(const std::filesystem::path& file, std::string_view key,
                                std::uint64_t max_payload) {
  namespace fs = std::filesystem;
  CacheEntryRead r;
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(file, ec))) return r;
  const std::uintmax_t bytes_on_disk = fs::file_size(file, ec);
  if (ec || !fs::is_regular_file(file, ec)) {
    r.problem = "not a regular file";
    return r;
  }
  // Every entry of this key and payload bound fits in this many bytes.
  const std::uint64_t largest =
      kFixedHeader + key.size() +
      ZSTD_compressBound(std::size_t(std::min<std::uint64_t>(max_payload, std::uint64_t(1) << 40)));
  if (bytes_on_disk > largest) {
    r.problem = fmt::format("{} bytes, more than such an entry holds", bytes_on_disk);
    return r;
  }
  std::string bytes(std::size_t(bytes_on_disk), '\0');
  std::ifstream f(file, std::ios::binary);
  if (!f || !f.read(bytes.data(), std::streamsize(bytes.size())) ||
      f.peek() != std::char_traits<char>::eof()) {
    r.problem = "unreadable, or changed while read";
    return r;
  }
  return decode_cache_entry(bytes, key, max_payload);
}

}  // namespace terrasprite
