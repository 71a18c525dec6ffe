// SPDX-License-Identifier: MIT
// Image loading through GDAL (every raster format, georeferencing kept) with
// stb as a fallback, and PNG writing through stb.
#include "terrasprite/terrain/image_io.h"

#include <fmt/format.h>
#include <gdal.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "terrain/gdal_util.h"
#include "terrasprite/common/error.h"
#include "terrasprite/common/image.h"

namespace terrasprite {
namespace {

// Images larger than this a side exceed GL's texture limit (16384 on llvmpipe
// and most GPUs) and several GB decoded: refused from the header, before decoding.
constexpr int kMaxImageSide = 16384;

std::string too_large(int w, int h) {
  return fmt::format(
      "image is {}x{}; more than {} pixels a side is not supported (downsample it, "
      "e.g. gdal_translate -outsize)",
      w, h, kMaxImageSide);
}

Image from_channels(const std::vector<std::uint16_t>& v, int w, int h, int n, bool sixteen) {
  Image img(w, h);
  const std::size_t count = static_cast<std::size_t>(w) * h;
  auto to8 = [&](std::uint16_t x) -> std::uint8_t {
    return sixteen ? static_cast<std::uint8_t>((x * 255u + 32767u) / 65535u)
                   : static_cast<std::uint8_t>(x);
  };
  for (std::size_t p = 0; p < count; ++p) {
    std::uint8_t* o = img.rgba.data() + p * 4;
    const std::uint16_t* s = v.data() + p * n;
    if (n == 1 || n == 2) {
      o[0] = o[1] = o[2] = to8(s[0]);
      o[3] = n == 2 ? to8(s[1]) : 255;
    } else {
      o[0] = to8(s[0]);
      o[1] = to8(s[1]);
      o[2] = to8(s[2]);
      o[3] = n >= 4 ? to8(s[3]) : 255;
    }
  }
  return img;
}

std::optional<Image> load_with_gdal(const std::string& path, std::string& error) {
  detail::GdalErrorCapture capture;
  GDALDatasetH ds = GDALOpen(path.c_str(), GA_ReadOnly);
  if (!ds) {
    error = capture.last();
    return std::nullopt;
  }
  const int w = GDALGetRasterXSize(ds), h = GDALGetRasterYSize(ds);
  const int bands = std::min(GDALGetRasterCount(ds), 4);
  if (w <= 0 || h <= 0 || bands <= 0) {
    GDALClose(ds);
    error = "no raster data";
    return std::nullopt;
  }
  if (w > kMaxImageSide || h > kMaxImageSide) {
    GDALClose(ds);
    throw InputError(fmt::format("{}: {}", path, too_large(w, h)));
  }
  bool sixteen = false;
  for (int b = 1; b <= bands; ++b) {
    GDALDataType t = GDALGetRasterDataType(GDALGetRasterBand(ds, b));
    if (t == GDT_UInt16 || t == GDT_Int16)
      sixteen = true;
    else if (t != GDT_Byte) {
      GDALClose(ds);
      error = fmt::format("unsupported sample type {} for an image (8- or 16-bit expected)",
                          GDALGetDataTypeName(t));
      return std::nullopt;
    }
  }
  std::vector<std::uint16_t> buf(static_cast<std::size_t>(w) * h * bands);
  CPLErr err = GDALDatasetRasterIO(ds, GF_Read, 0, 0, w, h, buf.data(), w, h, GDT_UInt16, bands,
                                   nullptr, bands * 2, static_cast<GSpacing>(w) * bands * 2, 2);
  if (err != CE_None) {
    error = capture.last().empty() ? "read failed" : capture.last();
    GDALClose(ds);
    return std::nullopt;
  }
  Image img = from_channels(buf, w, h, bands, sixteen);
  double gt[6];
  if (GDALGetGeoTransform(ds, gt) == CE_None) {
    GeoTransform g;
    std::copy(gt, gt + 6, g.gt);
    const char* wkt = GDALGetProjectionRef(ds);
    g.wkt = wkt ? wkt : "";
    img.geo = g;
  }
  GDALClose(ds);
  return img;
}

}  // namespace

Image load_image(const std::string& path) {
  std::error_code ec;
  // GDAL's virtual files (/vsimem/, /vsizip/...) are not on the filesystem.
  const bool gdal_virtual = path.rfind("/vsi", 0) == 0;
  if (!gdal_virtual && !std::filesystem::exists(path, ec))
    throw InputError(fmt::format("{}: no such file", path));
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("{}: is a directory, not an image", path));
  std::string gdal_error;
  if (auto img = load_with_gdal(path, gdal_error)) return std::move(*img);
  // stb reads a few things GDAL's build may lack (e.g. some PNG/TGA variants).
  int w = 0, h = 0, n = 0;
  if (stbi_info(path.c_str(), &w, &h, &n) && (w > kMaxImageSide || h > kMaxImageSide))
    throw InputError(fmt::format("{}: {}", path, too_large(w, h)));
  if (stbi_is_16_bit(path.c_str())) {
    stbi_us* p = stbi_load_16(path.c_str(), &w, &h, &n, 0);
    if (p) {
      std::vector<std::uint16_t> v(p, p + static_cast<std::size_t>(w) * h * n);
      stbi_image_free(p);
      return from_channels(v, w, h, n, true);
    }
  } else if (stbi_uc* p = stbi_load(path.c_str(), &w, &h, &n, 0)) {
    std::vector<std::uint16_t> v(p, p + static_cast<std::size_t>(w) * h * n);
    stbi_image_free(p);
    return from_channels(v, w, h, n, false);
  }
  if (gdal_error.empty())
    gdal_error = stbi_failure_reason() ? stbi_failure_reason() : "unknown format";
  // GDAL's messages can span lines; keep ours to one.
  std::replace(gdal_error.begin(), gdal_error.end(), '\n', ' ');
  throw InputError(fmt::format("{}: not a readable image ({})", path, gdal_error));
}

namespace {

void append_big_endian(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(char((v >> shift) & 0xff));
}

// A PNG tEXt chunk `keyword` = `text`.
std::string text_chunk(const std::string& keyword, const std::string& text) {
  const std::string body = "tEXt" + keyword + '\0' + text;
  std::string chunk;
  append_big_endian(chunk, std::uint32_t(body.size() - 4));
  chunk += body;
  append_big_endian(
      chunk, std::uint32_t(crc32(crc32(0, nullptr, 0), reinterpret_cast<const Bytef*>(body.data()),
                                 uInt(body.size()))));
  return chunk;
}

// The encoded PNG with its Software chunk after IHDR (the signature, 8 bytes,
// and IHDR, 25 bytes, come first in every PNG).
std::string png_bytes(const Image& image, const std::string& path) {
  std::string png;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
  };
  if (!stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.rgba.data(),
                              image.width * 4) ||
      png.size() < 33)
    throw InputError(fmt::format("{}: cannot encode the PNG", path));
  png.insert(33, text_chunk("Software", kPngSoftware));
  return png;
}

// Writes `bytes` to `path`, every write and the close checked.
void write_all(const std::string& path, const std::string& bytes) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw InputError(fmt::format("{}: cannot write PNG ({})", path, std::strerror(errno)));
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  const int write_errno = errno;
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed)
    throw InputError(fmt::format("{}: cannot write PNG ({})", path,
                                 std::strerror(!written ? write_errno : errno)));
}

}  // namespace

void save_png(const Image& image, const std::string& path) {
  write_all(path, png_bytes(image, path));
}

void save_png16(std::span<const std::uint16_t> grey, int width, int height,
                const std::string& path) {
  // stb writes 8-bit only; GDAL's PNG driver writes 16-bit through CreateCopy.
  detail::GdalErrorCapture capture;
  GDALDriverH mem = GDALGetDriverByName("MEM");
  GDALDriverH png = GDALGetDriverByName("PNG");
  if (!mem || !png) throw InputError(fmt::format("{}: GDAL has no PNG driver", path));
  GDALDatasetH ds = GDALCreate(mem, "", width, height, 1, GDT_UInt16, nullptr);
  CPLErr e = GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, width, height,
                          const_cast<std::uint16_t*>(grey.data()), width, height, GDT_UInt16, 0, 0);
  GDALDatasetH out = e == CE_None
                         ? GDALCreateCopy(png, path.c_str(), ds, FALSE, nullptr, nullptr, nullptr)
                         : nullptr;
  GDALClose(ds);
  if (!out) throw InputError(fmt::format("{}: cannot write 16-bit PNG ({})", path, capture.last()));
  GDALClose(out);
  // GDAL leaves an .aux.xml beside PNGs it writes when metadata is present.
  std::error_code ec;
  std::filesystem::remove(path + ".aux.xml", ec);
}

}  // namespace terrasprite
