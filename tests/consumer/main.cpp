// Uses the installed library: synthesise a tiny terrain and print its range.
#include <cstdio>

#include "terrasprite/terrain/synth.h"

int main() {
  terrasprite::SynthOptions o;
  o.size = 33;
  terrasprite::Heightfield h = terrasprite::synthesize_terrain(o);
  std::printf("consumer: %dx%d synthetic terrain, heights %.1f..%.1f m\n", h.width, h.height,
              h.min_height(), h.max_height());
  return h.width == 33 && h.max_height() > h.min_height() ? 0 : 1;
}
