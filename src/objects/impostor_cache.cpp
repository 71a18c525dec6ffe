// SPDX-License-Identifier: MIT
#include "objects/impostor_cache.h"

#include <fmt/format.h>

#include <chrono>
#include <cstring>

namespace terrasprite::objects {

double ms_now() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

bool load_impostor(const RepresentationCache& cache, const std::string& what,
                   std::initializer_list<TextureLevel> textures) {
  if (!cache.enabled()) return false;
  std::optional<std::string> payload = cache.read(what);
  if (!payload) return false;
  std::size_t total = 0;
  for (const TextureLevel& t : textures) total += t.bytes();
  if (payload->size() != total) {
    fmt::print(stderr, "warning: ignoring the cache entry {}: {} bytes, expected {}\n",
               cache.file(what).string(), payload->size(), total);
    --cache.stats().hits;
    ++cache.stats().rejected;
    return false;
  }
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  const char* p = payload->data();
  for (const TextureLevel& t : textures) {
    if (t.target == GL_TEXTURE_2D_ARRAY)
      glTextureSubImage3D(t.texture, 0, 0, 0, 0, t.width, t.height, t.layers, t.format, t.type, p);
    else
      glTextureSubImage2D(t.texture, 0, 0, 0, t.width, t.height, t.format, t.type, p);
    p += t.bytes();
  }
  return true;
}

void store_impostor(const RepresentationCache& cache, const std::string& what,
                    std::initializer_list<TextureLevel> textures, double build_start_ms) {
  if (!cache.enabled()) return;
  std::size_t total = 0;
  for (const TextureLevel& t : textures) total += t.bytes();
  std::string payload(total, '\0');
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  char* p = payload.data();
  for (const TextureLevel& t : textures) {
    glGetTextureImage(t.texture, 0, t.format, t.type, GLsizei(t.bytes()), p);
    p += t.bytes();
  }
  cache.stats().build_ms += ms_now() - build_start_ms;
  ++cache.stats().misses;
  cache.write(what, payload);
}

}  // namespace terrasprite::objects
