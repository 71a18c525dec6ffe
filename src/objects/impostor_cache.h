// SPDX-License-Identifier: MIT
// An impostor's textures to and from the representation cache: level 0 of
// each texture, read back once after capture, uploaded instead of capturing.
#pragma once
#include <epoxy/gl.h>

#include <initializer_list>
#include <string>

#include "terrasprite/objects/representation_cache.h"

namespace terrasprite::objects {

/// Level 0 of a texture whose storage exists: width x height x layers texels
/// of `bytes_per_texel`, transferred as (format, type).
struct TextureLevel {
  GLuint texture = 0;
  GLenum target = GL_TEXTURE_2D;  ///< GL_TEXTURE_2D or GL_TEXTURE_2D_ARRAY
  int width = 0, height = 0, layers = 1;
  GLenum format = GL_RGBA, type = GL_UNSIGNED_BYTE;
  int bytes_per_texel = 4;
  std::size_t bytes() const { return std::size_t(width) * height * layers * bytes_per_texel; }
};

/// Fills the textures from the entry `what` and returns true; false (the
/// textures untouched) when the cache is disabled, has no such entry of this
/// model (RepresentationCache::read: key, checksum), or the entry's size is
/// not the textures' size.
bool load_impostor(const RepresentationCache& cache, const std::string& what,
                   std::initializer_list<TextureLevel> textures);

/// Reads the textures back (waits for their capture) and stores them as
/// `what`; counts the build time since `build_start_ms` (ms_now()). Nothing
/// when the cache is disabled.
void store_impostor(const RepresentationCache& cache, const std::string& what,
                    std::initializer_list<TextureLevel> textures, double build_start_ms);

/// Monotonic milliseconds, for store_impostor's build time.
double ms_now();

}  // namespace terrasprite::objects
