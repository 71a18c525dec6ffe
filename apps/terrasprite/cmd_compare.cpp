// SPDX-License-Identifier: MIT
// terrasprite compare: score a test image against a reference (PSNR, SSIM,
// MS-SSIM, FLIP), optionally writing difference images. Reads as: load both,
// check sizes, run the metrics asked for, write images, report.
#include <fmt/format.h>

#include <cmath>
#include <sstream>

#include "cli_common.h"
#include "commands.h"
#include "terrasprite/terrain/image_io.h"
#include "terrasprite/common/error.h"
#include "terrasprite/quality/quality.h"
#include "terrasprite/report/json_writer.h"

namespace terrasprite::cli {

namespace {

struct CompareArgs {
  std::string reference, test;
  std::string metrics = "psnr,ssim,msssim,flip";
  bool metrics_given = false;
  std::string ssim_mode = "wang";
  double ppd = 67.02;
  double diff_scale = 4.0;
  std::string diff, flip_map, json;
};

struct Wanted {
  bool psnr = false, ssim = false, msssim = false, flip = false;
};

Wanted parse_metrics(const std::string& text) {
  Wanted w;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item == "psnr")
      w.psnr = true;
    else if (item == "ssim")
      w.ssim = true;
    else if (item == "msssim")
      w.msssim = true;
    else if (item == "flip")
      w.flip = true;
    else
      throw InputError(
          fmt::format("--metrics {}: unknown metric '{}' (psnr, ssim, msssim, flip)", text, item));
  }
  if (!(w.psnr || w.ssim || w.msssim || w.flip)) throw InputError("--metrics: empty list");
  return w;
}

// A single-file PNG output: written beside the target, renamed into place.
void save_png_output(const Image& image, const std::string& path, const OutputPolicy& policy) {
  write_output_file(path, policy, [&](const std::string& tmp) { save_png(image, tmp); });
}

// Infinite PSNR (identical images) is written as the string "inf": JSON has no infinity.
nlohmann::json db(double v) {
  return std::isinf(v) ? nlohmann::json("inf") : nlohmann::json(v);
}
std::string db_text(double v) {
  return std::isinf(v) ? std::string("inf") : fmt::format("{:.3f} dB", v);
}

void run(const CompareArgs& o, const OutputPolicy& policy) {
  const Wanted want = parse_metrics(o.metrics);
  check_outputs(policy, "", {o.json, o.diff, o.flip_map});
  if ((want.flip || !o.flip_map.empty()) && !(std::isfinite(o.ppd) && o.ppd > 0 && o.ppd <= 1000))
    throw InputError(fmt::format("--ppd {}: pixels per degree must be in (0, 1000]", o.ppd));
  const Image ref = load_image(o.reference);
  const Image test = load_image(o.test);
  if (ref.width != test.width || ref.height != test.height)
    throw InputError(
        fmt::format("compare: {} is {}x{} but {} is {}x{}: images must have the same size",
                    o.reference, ref.width, ref.height, o.test, test.width, test.height));
  const ImageView a = ref.view(), b = test.view();

  nlohmann::json j = {
      {"reference", o.reference}, {"test", o.test}, {"size", {ref.width, ref.height}}};
  std::string table = fmt::format("{:<12} {}\n{:<12} {}\n{:<12} {} x {}\n", "reference",
                                  o.reference, "test", o.test, "size", ref.width, ref.height);
  if (want.psnr) {
    const auto p = quality::psnr(a, b);
    j["psnr_rgb"] = db(p.rgb);
    j["psnr_luma"] = db(p.luma);
    table += fmt::format("{:<12} {}\n{:<12} {}\n", "psnr_rgb", db_text(p.rgb), "psnr_luma",
                         db_text(p.luma));
  }
  if (want.ssim) {
    quality::SsimOptions so;
    so.mode = o.ssim_mode == "ffmpeg" ? quality::SsimMode::kFfmpeg : quality::SsimMode::kWang;
    const auto s = quality::ssim(a, b, so);
    j["ssim"] = s.ssim;
    j["ssim_channels"] = s.channels;
    j["ssim_mode"] = o.ssim_mode;
    table += fmt::format("{:<12} {:.6f}  (R {:.6f}  G {:.6f}  B {:.6f}, {} mode)\n", "ssim", s.ssim,
                         s.channels[0], s.channels[1], s.channels[2], o.ssim_mode);
  }
  if (want.msssim) {
    try {
      const double m = quality::msssim(a, b);
      j["msssim"] = m;
      table += fmt::format("{:<12} {:.6f}\n", "msssim", m);
    } catch (const InputError& e) {
      // Asked for explicitly: a bad input. Part of the default set: skip it
      // on a small image rather than refuse the other metrics.
      if (o.metrics_given) throw;
      fmt::print(stderr, "terrasprite: compare: msssim skipped: {}\n", e.what());
      j["msssim"] = nullptr;
      table += fmt::format("{:<12} skipped (image too small)\n", "msssim");
    }
  }
  if (want.flip || !o.flip_map.empty()) {
    quality::FlipOptions fo;
    fo.ppd = o.ppd;
    fo.want_map = !o.flip_map.empty();
    const auto f = quality::flip(a, b, fo);
    j["flip_mean"] = f.mean;
    j["flip_median"] = f.median;
    j["ppd"] = o.ppd;
    table += fmt::format("{:<12} {:.6f}  (median {:.6f}, {} pixels per degree)\n", "flip_mean",
                         f.mean, f.median, o.ppd);
    if (fo.want_map)
      save_png_output(quality::flip_image(f.map, ref.width, ref.height), o.flip_map, policy);
  }
  if (!o.diff.empty())
    save_png_output(quality::difference_image(a, b, o.diff_scale), o.diff, policy);
  if (!o.json.empty()) {
    report::write_json(j, o.json, policy);
  } else {
    fmt::print("{}", table);
  }
}

}  // namespace

void add_compare(CLI::App& app, const OutputPolicy& policy) {
  auto* cmd = app.add_subcommand(
      "compare", "quality metrics of TEST against REFERENCE: PSNR, SSIM, MS-SSIM, FLIP");
  auto o = std::make_shared<CompareArgs>();
  cmd->add_option("reference", o->reference,
                  "reference image (8/16-bit grey, RGB or RGBA; alpha ignored)")
      ->required();
  cmd->add_option("test", o->test, "test image, same size")->required();
  auto* metrics = cmd->add_option("--metrics", o->metrics,
                                  "comma-separated: psnr,ssim,msssim,flip (default: all)");
  cmd->add_option("--ssim-mode", o->ssim_mode,
                  "wang (Gaussian, on luma) or ffmpeg (ffmpeg's ssim filter)")
      ->check(CLI::IsMember({"wang", "ffmpeg"}));
  cmd->add_option("--ppd", o->ppd,
                  "FLIP pixels per degree (default 67.02: 0.7 m wide 4K display at 0.7 m)");
  cmd->add_option("--diff", o->diff, "write |reference - test| * scale as PNG");
  cmd->add_option("--diff-scale", o->diff_scale, "scale of the difference image (default 4)");
  cmd->add_option("--flip-map", o->flip_map,
                  "write the FLIP error map (magma) as PNG (computes FLIP)");
  cmd->add_option("--json", o->json, "write the metrics as JSON instead of the table");
  cmd->callback([o, metrics, &policy] {
    o->metrics_given = metrics->count() > 0;
    run(*o, policy);
  });
}

}  // namespace terrasprite::cli
