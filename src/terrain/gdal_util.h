// SPDX-License-Identifier: MIT
// GDAL set-up and error capture: GDAL's own messages become part of our
// one-line InputError instead of being printed.
#pragma once
#include <string>

namespace terrasprite::detail {

/// Registers GDAL's drivers once (thread-safe).
void ensure_gdal();

/// While alive, GDAL errors on this thread are collected, not printed.
class GdalErrorCapture {
 public:
  GdalErrorCapture();
  ~GdalErrorCapture();
  GdalErrorCapture(const GdalErrorCapture&) = delete;
  GdalErrorCapture& operator=(const GdalErrorCapture&) = delete;
  /// The last error GDAL reported, or "" when none.
  const std::string& last() const { return last_; }

 private:
  std::string last_;
};

}  // namespace terrasprite::detail
