// SPDX-License-Identifier: MIT
#include "terrain/gdal_util.h"

#include <cpl_error.h>
#include <gdal.h>

#include <mutex>

namespace terrasprite::detail {

void ensure_gdal() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    // Never let GDAL print on its own; captured handlers forward what matters.
    CPLSetErrorHandler(CPLQuietErrorHandler);
  });
}

static void CPL_STDCALL capture_handler(CPLErr cls, CPLErrorNum, const char* msg) {
  if (cls < CE_Failure) return;
  auto* self = static_cast<std::string*>(CPLGetErrorHandlerUserData());
  if (self && msg) *self = msg;
}

GdalErrorCapture::GdalErrorCapture() {
  ensure_gdal();
  CPLPushErrorHandlerEx(capture_handler, &last_);
}

GdalErrorCapture::~GdalErrorCapture() {
  CPLPopErrorHandler();
}

}  // namespace terrasprite::detail
