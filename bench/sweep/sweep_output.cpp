#include "bench/sweep/sweep_output.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <thread>
#include <type_traits>

#include "bench/common/bench_setup.h"
#include "bench/common/progress.h"
#include "bench/common/stats.h"
#include "bench/common/table.h"

namespace lgh::bench {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string fmt(double v, const char* format = "%.4g") {
  if (!std::isfinite(v)) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

void printScalingCase(const Case& c) {
  std::printf("\n%s: time and overdraw vs VPL count (alpha 1, S1, k 4), %d x %d\n", c.scene.name.c_str(),
              c.base.image.width, c.base.image.height);
  TextTable table({"input lights", "method", "tiles", "L", "grid lights", "fragments/px", "light pass ms", "frame ms"});
  for (const Measurement& m : c.measurements) {
    const bool lgh = m.lgh();
    table.addRow({formatCount(m.inputLights), m.method + (m.extrapolated ? " (extrapolated)" : ""),
                  lgh ? std::to_string(m.point.interleave) + "x" + std::to_string(m.point.interleave) : "-",
                  lgh ? std::to_string(m.lights.levels) : "-", lgh ? formatCount(gridLightsOf(m.lights)) : "-",
                  lgh ? formatMs(m.lights.rasterizedPerPixel) : "-",
                  formatMs(median(m.timeUnshadowedMs) - (std::isfinite(m.buildMs) ? m.buildMs : 0.0)),
                  formatMs(median(m.frameMs))});
  }
  table.print(stdout);
}

void printGridCase(const Case& c) {
  std::printf(
      "\n%s%s%s, %d x %d, %s VPLs (budget %s): %s input lights (%s VPLs, %s emitter samples, %s point lights), "
      "L = %d, clamp %.3g\n",
      c.scene.name.c_str(), c.scene.camera.empty() ? "" : " @ ", c.scene.camera.c_str(), c.base.image.width,
      c.base.image.height, shortCount(c.vplTarget).c_str(), formatCount(c.vplBudget).c_str(),
      formatCount(c.inputLights).c_str(), formatCount(c.vpls).c_str(), formatCount(c.emitterSamples).c_str(),
      formatCount(c.pointLights).c_str(), c.levels, c.clampDistance);
  const ReferenceInfo& r = c.reference;
  std::printf("reference: %s of %s pixels (fraction %.4g), %s rays, %s, %.1f M rays/s on %u threads%s; build %s ms\n",
              formatCount(r.pixels).c_str(), formatCount(r.imagePixels).c_str(), r.fraction,
              formatCount(size_t(r.rays)).c_str(), ProgressBar::formatSeconds(r.seconds).c_str(),
              double(r.rays) / std::max(r.seconds, 1e-9) / 1e6, r.threads, r.cached ? " (from the cache)" : "",
              formatSpread(spreadOf(c.buildMs)).c_str());
  TextTable table({"method", "settings", "frag/px", "time ms (shadowed)", "time ms (unshadowed)", "rmse unsh.",
                   "rmse shadowed", "psnr sh."});
  for (const Measurement& m : c.measurements) {
    std::string settings = m.gridPoint() ? settingsLabel(m.point) : "M = " + formatCount(m.subsetLights);
    if (m.extrapolated) settings += " (extrapolated)";
    table.addRow({m.method, settings, m.lgh() ? formatMs(m.lights.rasterizedPerPixel) : "-",
                  m.timeMs.empty() ? "-" : formatSpread(spreadOf(m.timeMs)),
                  m.timeUnshadowedMs.empty() ? "-" : formatSpread(spreadOf(m.timeUnshadowedMs)),
                  fmt(median(m.rmseUnshadowed)), fmt(median(m.rmseShadowed)), fmt(median(m.psnrShadowed), "%.1f")});
  }
  table.print(stdout);
}

// Writes path.tmp with write(stream), then renames it to path.
void writeAtomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
  const std::string temporary = path.string() + ".tmp";
  std::ofstream out(temporary);
  if (!out) throw std::runtime_error(path.string() + ": cannot open for writing");
  write(out);
  out.close();
  if (!out) throw std::runtime_error(path.string() + ": write failed");
  fs::rename(temporary, path);
}

// ---- CSV: one row per measurement, medians over the repeats ("" where a value does not apply).

constexpr const char* kCsvHeader =
    "scene,camera,width,height,vpl_target,vpl_budget,vpls,input_lights,method,series,alpha,start_level,interleave,"
    "shadow_samples,filter,subset_lights,levels,grid_lights,fragments_per_pixel,shaded_per_pixel,time_ms,time_ms_min,"
    "time_ms_max,time_unshadowed_ms,build_ms,light_pass_ms,interleave_ms,shadow_rays_ms,shadow_filter_ms,frame_ms,"
    "extrapolated,rmse_unshadowed,psnr_unshadowed,rmse_shadowed,psnr_shadowed,rmse_shadowed_min,rmse_shadowed_max,"
    "reference_pixels,others_cpu,image,frames,rmse_exact_ratio,rtslc_block,rtslc_cuts_ms,rtslc_sampling_ms,mae_"
    "shadowed,mae_shadowed_min,mae_shadowed_max";

std::string num(double v) {
  if (!std::isfinite(v)) return std::string();
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

// The LGH point's columns (alpha .. shaded_per_pixel); empty for the baselines but subset_lights; the
// lightcuts' samples n in shadow_samples and their m in interleave.
std::vector<std::string> pointCells(const Measurement& m) {
  const PointSpec& p = m.point;
  if (m.lightcuts())
    return {"", "", std::to_string(p.interleave), std::to_string(p.k), p.filter ? "on" : "off", "", "", "", "", ""};
  if (!m.lgh()) return {"", "", "", "", "", std::to_string(m.subsetLights), "", "", "", ""};
  return {num(p.alpha),
          std::to_string(p.startLevel),
          std::to_string(p.interleave),
          std::to_string(p.k),
          p.k > 0 ? (p.filter ? "on" : "off") : "",
          "",
          std::to_string(m.lights.levels),
          std::to_string(gridLightsOf(m.lights)),
          num(m.lights.rasterizedPerPixel),
          num(m.lights.shadedPerPixel)};
}

std::vector<std::string> csvCells(const Case& c, const Measurement& m) {
  const Spread t = spreadOf(m.timeMs), rs = spreadOf(m.rmseShadowed), ms = spreadOf(m.maeShadowed);
  const bool timed = !m.timeMs.empty(), shadowed = !m.rmseShadowed.empty();
  const bool interleaved = m.lgh() && m.point.interleave > 1;
  std::vector<std::string> cells = {c.scene.name,
                                    c.scene.camera,
                                    std::to_string(c.base.image.width),
                                    std::to_string(c.base.image.height),
                                    std::to_string(m.vplTarget),
                                    std::to_string(m.settings.inputLights.vpls),
                                    std::to_string(m.vpls),
                                    std::to_string(m.inputLights),
                                    m.method,
                                    m.series};
  for (std::string& cell : pointCells(m)) cells.push_back(std::move(cell));
  for (std::string cell :
       {timed ? num(t.median) : "",
        timed ? num(t.min) : "",
        timed ? num(t.max) : "",
        num(median(m.timeUnshadowedMs)),
        num(m.buildMs),
        num(m.passMedian(passes::kLightPass)),
        interleaved ? num(m.passMedian(passes::kInterleaveSplit) + m.passMedian(passes::kInterleaveResolve)) : "",
        num((m.passMs.count(passes::kShadowTargets) ? m.passMedian(passes::kShadowTargets) : 0.0) +
            m.passMedian(passes::kShadowRays)),
        num(m.passMedian(passes::kShadowFilter)),
        num(median(m.frameMs)),
        std::string(m.extrapolated ? "1" : "0"),
        num(median(m.rmseUnshadowed)),
        num(median(m.psnrUnshadowed)),
        num(rs.median),
        num(median(m.psnrShadowed)),
        shadowed ? num(rs.min) : "",
        shadowed ? num(rs.max) : "",
        c.scaling ? "" : std::to_string(c.reference.pixels),
        num(std::round(m.othersCpu * 100) / 100),
        m.image,
        m.gridPoint() ? std::to_string(m.point.frames) : "",
        num(median(m.rmseExactRatio)),
        m.lightcuts() ? std::to_string(m.point.block) : "",
        m.lightcuts() ? num(m.passMedian(passes::kLightcutCuts)) : "",
        m.lightcuts() ? num(m.passMedian(passes::kLightcutSampling)) : "",
        num(ms.median),
        shadowed ? num(ms.min) : "",
        shadowed ? num(ms.max) : ""})
    cells.push_back(std::move(cell));
  return cells;
}

// ---- JSON: everything, with every repeat and every render setting.

// Five significant digits (timings and errors carry no more), null for NaN: keeps the file small.
json significant(double x) {
  if (!std::isfinite(x)) return json(nullptr);
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.5g", x);
  return json(std::strtod(buffer, nullptr));
}

json significant(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(significant(x));
  return a;
}

json settingsJson(RenderSettings s) {
  json j;
  visitSettings(s, [&](auto& value, const SettingInfo& info) {
    if constexpr (std::is_enum_v<std::decay_t<decltype(value)>>)
      j[info.name] = choiceName(value, info.choices);
    else
      j[info.name] = value;
  });
  return j;
}

json definitionsJson() {
  return {{"time_ms",
           "shadowed estimate: LGH build + interleave split + light pass + resolve + shadow targets + shadow rays + "
           "filter; "
           "uniform_shadowed: compute brute force with one ray per subset light and pixel; brute_force_ratio and "
           "uniform_ratio: the rasterized brute-force light pass over all / about M lights (a fresh set: VPL budget "
           "and emitter samples scaled by M/N) with the frame's shadow rays and filter"},
          {"rtslc",
           "stochastic lightcuts (--indirect-method rtslc): time_ms = light tree build + cuts + sampling + "
           "irradiance filter; shadow_samples = its samples per pixel n, interleave = m, rtslc_block = B"},
          {"time_unshadowed_ms",
           "unshadowed estimate: LGH build + split + light pass + resolve; brute_force and uniform: "
           "the rasterized brute-force light pass (every light full-screen)"},
          {"rmse", "relative RMSE of luminance, sqrt(sum (a - r)^2 / sum r^2), over the reference's pixels"},
          {"rmse_exact_ratio",
           "LGH: the relative RMSE of its irradiance times the reference's own visibility ratio (shadowed / "
           "unshadowed luminance): the floor any shadow estimate composited on this irradiance can reach"},
          {"psnr", "10 log10(max r^2 / mean (a - r)^2) over the reference's pixels, luminance, dB"},
          {"mae", "relative mean absolute error of luminance, sum |a - r| / sum |r|: outliers do not dominate it"},
          {"compared",
           "irradiance before albedo: Aov::Irradiance (unshadowed) and Aov::Irradiance x Aov::Visibility (shadowed)"},
          {"others_cpu",
           "the largest share of the machine other processes took during a sample that was kept (a sample "
           "during which they took more than 25% is taken again once they are quiet, up to 3 times)"}};
}

json measurementJson(const Measurement& m, const json& baseSettings) {
  json jm;
  jm["method"] = m.method;
  jm["series"] = m.series;
  // Only what differs from the case's base settings (which are listed in full once).
  json settings = json::object();
  const json own = settingsJson(m.settings);
  for (const auto& [name, value] : own.items())
    if (baseSettings[name] != value) settings[name] = value;
  jm["settings"] = settings;
  if (!m.gridPoint()) jm["subset_lights"] = m.subsetLights;
  if (m.lightcuts()) jm["tree_build_ms"] = significant(m.buildMs);
  jm["vpl_target"] = m.vplTarget;
  jm["vpls"] = m.vpls;
  jm["extrapolated"] = m.extrapolated;
  jm["others_cpu"] = significant(m.othersCpu);
  if (m.lgh()) {
    jm["levels"] = m.lights.levels;
    jm["lights_per_level"] = m.lights.lightsPerLevel;
    jm["input_lights"] = m.lights.inputLights;
    jm["fragments_per_pixel"] = significant(m.lights.rasterizedPerPixel);
    jm["shaded_per_pixel"] = significant(m.lights.shadedPerPixel);
    jm["max_fragments"] = m.lights.maxRasterized;
    jm["build_ms"] = significant(m.buildMs);
  }
  json passes;
  for (const auto& [name, samples] : m.passMs) passes[name] = significant(samples);
  jm["pass_ms"] = passes;
  jm["time_ms"] = significant(m.timeMs);
  jm["time_unshadowed_ms"] = significant(m.timeUnshadowedMs);
  jm["frame_ms"] = significant(m.frameMs);
  jm["rmse_unshadowed"] = significant(m.rmseUnshadowed);
  jm["psnr_unshadowed"] = significant(m.psnrUnshadowed);
  jm["rmse_shadowed"] = significant(m.rmseShadowed);
  jm["psnr_shadowed"] = significant(m.psnrShadowed);
  jm["mae_shadowed"] = significant(m.maeShadowed);
  if (!m.rmseExactRatio.empty()) jm["rmse_exact_ratio"] = significant(m.rmseExactRatio);
  if (!m.image.empty()) jm["image"] = m.image;
  return jm;
}

json caseJson(const Case& c) {
  json jc;
  jc["scene"] = sourceRelative(c.scene.path);
  jc["name"] = c.scene.name;
  jc["camera"] = c.scene.camera;
  jc["series"] = c.scaling ? "scaling" : "grid";
  jc["base_settings"] = settingsJson(c.base);
  if (!c.scaling) {
    jc["vpl_target"] = c.vplTarget;
    jc["vpl_budget"] = c.vplBudget;
    jc["input_lights"] = c.inputLights;
    jc["vpls"] = c.vpls;
    jc["emitter_samples"] = c.emitterSamples;
    jc["point_lights"] = c.pointLights;
    jc["levels"] = c.levels;
    jc["clamp_distance"] = c.clampDistance;
    jc["build_ms"] = significant(c.buildMs);
    if (!c.treeBuildMs.empty()) jc["tree_build_ms"] = significant(c.treeBuildMs);
    const ReferenceInfo& r = c.reference;
    jc["reference"] = {{"pixels", r.pixels},
                       {"image_pixels", r.imagePixels},
                       {"fraction", r.fraction},
                       {"seconds", significant(r.seconds)},
                       {"rays", r.rays},
                       {"pixel_light_pairs", r.pairs},
                       {"threads", r.threads},
                       {"from_cache", r.cached},
                       {"cache_file", sourceRelative(r.cacheFile)}};
  }
  const json base = jc["base_settings"];
  for (const Measurement& m : c.measurements) jc["measurements"].push_back(measurementJson(m, base));
  return jc;
}

}  // namespace

void printCase(const Case& c) {
  if (c.scaling)
    printScalingCase(c);
  else
    printGridCase(c);
}

void writeSweepCsv(const fs::path& path, const std::vector<Case>& cases) {
  writeAtomically(path, [&](std::ostream& csv) {
    csv << kCsvHeader << "\n";
    for (const Case& c : cases)
      for (const Measurement& m : c.measurements) {
        const std::vector<std::string> cells = csvCells(c, m);
        for (size_t i = 0; i < cells.size(); ++i) csv << (i ? "," : "") << cells[i];
        csv << "\n";
      }
  });
}

void writeSweepJson(const fs::path& path, const std::vector<Case>& cases, const SweepRunInfo& info) {
  json root;
  root["generated"] = timestamp();
  root["device"] = info.device;
  root["hardware_threads"] = std::thread::hardware_concurrency();
  root["width"] = info.width;
  root["height"] = info.height;
  root["repeats"] = info.repeats;
  root["preset"] = info.preset;
  root["definitions"] = definitionsJson();
  for (const Case& c : cases) root["cases"].push_back(caseJson(c));
  root["failures"] = info.failures;
  root["samples_retaken"] = info.samplesRetaken;
  root["samples_contended"] = info.samplesContended;
  writeAtomically(path, [&](std::ostream& out) { out << root.dump() << "\n"; });
}

std::string timestamp() {
  const std::time_t now = std::time(nullptr);
  char buffer[64];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d %H:%M", std::localtime(&now));
  return buffer;
}

}  // namespace lgh::bench
