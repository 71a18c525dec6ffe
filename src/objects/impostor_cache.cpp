// SPDX-License-Identifier: MIT
#include "objects/impostor_cache.h"

#include <fmt/format.h>

#include <chrono>
#include <cstring>

namespace terrasprite::objects {

namespace {
std::size_t total_bytes(std::initializer_list<TextureLevel> textures) {
  std::size_t n = 0;
  for (const TextureLevel& t : textures) n += t.bytes();
  return n;
}
}  // namespace

double ms_now() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

bool load_impostor(const RepresentationCache& cache, const std::string& what,
                   std::initializer_list<TextureLevel> textures) {
  if (!cache.enabled()) return false;
  const std::size_t total = total_bytes(textures);
  const std::optional<std::string> payload =
      cache.read(what, total, [total](std::string_view bytes) -> const char* {
        return bytes.size() == total ? nullptr : "not the size of this impostor's textures";
      });
  if (!payload) return false;
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
  const std::size_t total = total_bytes(textures);
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
