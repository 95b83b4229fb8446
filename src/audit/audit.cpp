#include "audit/audit.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <sstream>

#include "audit/delta_e_cache.h"
#include "core/code_quantizer.h"
#include "core/color.h"
#include "core/display.h"
#include "core/error.h"
#include "core/image.h"
#include "core/lightness_kernels.h"
#include "core/number_format.h"
#include "core/random.h"
#include "enhance/lightness.h"
#include "formats/manifest.h"

namespace countershade {
namespace {

// A decoded stimulus: code values and CIELAB per pixel.
struct Decoded {
  int width = 0, height = 0, bits = 8;
  std::vector<uint16_t> codes;  // 3 per pixel
  LabPixels lab;
  // A 16-bit reference rounded to 8 bits, and its CIELAB: what every stimulus of its scene is
  // composed on to measure the quantisation loss (made once per reference).
  Image at_8_bits;
  LabPixels lab_at_8_bits;
};

// The display encoding a reference entry records ("srgb", "gamma 2.2", or a measured table with its
// rows in `display_lut`); a table without its rows (a set made before they were recorded) is
// decoded as sRGB, noted in the report.
DisplayEncoding encoding_of(const ManifestEntry& reference, std::vector<std::string>& notes) {
  const auto it = reference.extra.find("display_encoding");
  const std::string text =
      it != reference.extra.end() && it->is_string() ? it->get<std::string>() : "srgb";
  if (text.rfind("gamma ", 0) == 0) return DisplayEncoding::gamma(std::stod(text.substr(6)));
  const auto lut = reference.extra.find("display_lut");
  if (lut != reference.extra.end()) {
    try {
      return DisplayEncoding::lut(lut->at("codes").get<std::vector<double>>(),
                                  lut->at("luminances").get<std::vector<double>>());
    } catch (const std::exception& e) {
      throw_input_error(reference.file + ": display_lut", e.what());
    }
  }
  if (text != "srgb")
    notes.push_back(reference.scene + ": display encoding '" + text +
                    "' is not stored in the manifest; L* decoded as sRGB");
  return DisplayEncoding::srgb();
}

Decoded decode(const std::filesystem::path& file, const DisplayEncoding& encoding) {
  Decoded d;
  Image image = read_image(file, &d.bits);
  if (image.channels != 3) throw_input_error(file.string(), "expected an RGB image");
  d.width = image.width;
  d.height = image.height;
  d.codes.resize(image.pixels.size());
  // Code values, and back to code / levels exactly as the generator holds them (the readers'
  // float conversion may differ in the last bit, which would miss the decoding table).
  const float levels = float((1u << d.bits) - 1u);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    d.codes[i] = uint16_t(quantize(image.pixels[i], d.bits));
    image.pixels[i] = float(d.codes[i]) / levels;
  }
  d.lab = display_to_lab(image, encoding, d.bits);
  return d;
}

// `range`: a calibrated display's black and white (cd/m²), for the mean luminance.
void lightness_statistics(const Decoded& d, const std::optional<std::pair<double, double>>& range,
                          StimulusAudit& out) {
  double sum = 0, squares = 0;
  for (const Lab& lab : d.lab) sum += lab.L;
  const double n = double(d.lab.size()), mean = sum / n;
  for (const Lab& lab : d.lab) squares += (lab.L - mean) * (lab.L - mean);
  out.mean_lightness = mean;
  out.rms_contrast = std::sqrt(squares / n);
  if (!range) return;  // the relative luminance only where a calibration gives it a scale
  double relative = 0;
  for (const Lab& lab : d.lab) relative += lab_to_xyz(lab).y;
  out.mean_luminance_cd_m2 = range->first + (relative / n) * (range->second - range->first);
}

// A calibrated display's luminance range, as the scene's reference entry records it.
std::optional<std::pair<double, double>> luminance_range(const ManifestEntry& reference) {
  const auto it = reference.extra.find("luminance_cd_m2");
  if (it == reference.extra.end()) return std::nullopt;
  try {
    return std::make_pair(it->at("black").get<double>(), it->at("white").get<double>());
  } catch (const std::exception&) {
    throw_input_error(reference.file + ": luminance_cd_m2",
                      "expected {\"black\": number, \"white\": number}");
  }
}

// The 99th percentile (R's type 7 without interpolation: the value at ⌊0.99·(n − 1)⌋) of values
// that are 0 except at `nonzero`.
double percentile99(std::vector<float> nonzero, size_t n) {
  const size_t k = size_t(0.99 * double(n - 1)), zeros = n - nonzero.size();
  if (k < zeros) return 0.0;
  auto at = nonzero.begin() + long(k - zeros);
  std::nth_element(nonzero.begin(), at, nonzero.end());
  return *at;
}

// ΔE2000, changed and clipped pixels against the reference.
void compare_with_reference(const Decoded& d, const Decoded& reference, StimulusAudit& out) {
  const size_t n = d.lab.size();
  const uint16_t top = uint16_t((1u << d.bits) - 1u);
  std::vector<float> differences;
  double sum = 0;
  size_t changed = 0, clipped = 0;
  DeltaECache delta_e;
  for (size_t p = 0; p < n; ++p) {
    const uint16_t *c = &d.codes[3 * p], *r = &reference.codes[3 * p];
    if (c[0] == r[0] && c[1] == r[1] && c[2] == r[2]) continue;
    ++changed;
    clipped += clipped_by_enhancement(c, r, top);
    const uint64_t pair_hash =
        mix64(code_triple_key(c[0], c[1], c[2]) ^ mix64(code_triple_key(r[0], r[1], r[2])));
    const float e = float(delta_e(reference.lab[p], d.lab[p], pair_hash));
    differences.push_back(e);
    sum += e;
  }
  out.changed_fraction = double(changed) / double(n);
  out.clipped_fraction = double(clipped) / double(n);
  out.delta_e_mean = sum / double(n);
  out.delta_e_p99 = percentile99(std::move(differences), n);
}

// A 16-bit image's codes rounded to 8 bits, as values in [0,1].
Image rounded_to_8_bits(const Decoded& d) {
  Image image(d.width, d.height, 3, Image::Uninitialized{});
  for (size_t i = 0; i < d.codes.size(); ++i)
    image.pixels[i] = float(std::lround(d.codes[i] * 255.0 / 65535.0)) / 255.0f;
  return image;
}

// The share of a 16-bit stimulus's ideal change that an 8-bit set of the same render loses
// (StimulusAudit::quantisation_loss). That set holds the reference rounded to 8 bits and composes
// each stimulus on it, as the generator does: the reference's L* plus the change Δ, with hue and
// chroma kept, rounded to 8-bit codes. Δ is the 16-bit set's own, L*₁₆ − L*₁₆(reference).
std::optional<double> quantisation_loss(const Decoded& d, const Decoded& reference,
                                        const DisplayEncoding& encoding) {
  if (d.bits != 16) return std::nullopt;
  const Image& base = reference.at_8_bits;
  const LabPixels& base_lab = reference.lab_at_8_bits;
  const size_t n = base_lab.size();
  std::vector<double> delta(n);
  for (size_t p = 0; p < n; ++p) delta[p] = d.lab[p].L - reference.lab[p].L;
  Image composed(d.width, d.height, 3, Image::Uninitialized{});
  const LightnessComposer composer(CodeQuantizer::shared(encoding, 8), 8);
  for (size_t first = 0; first < n; first += 64) {
    const size_t count = std::min<size_t>(64, n - first);
    composer.compose(base_lab.data() + first, base.pixels.data() + 3 * first, delta.data() + first,
                     count, composed.pixels.data() + 3 * first);
  }
  const LabPixels lab = display_to_lab(composed, encoding, 8);
  double ideal = 0, error = 0;
  for (size_t p = 0; p < n; ++p) {
    const double rounded = lab[p].L - base_lab[p].L;
    ideal += delta[p] * delta[p];
    error += (rounded - delta[p]) * (rounded - delta[p]);
  }
  if (!(ideal > 0)) return std::nullopt;
  return std::sqrt(error / ideal);
}

// Every measure of one stimulus (or reference) against its reference.
void measure(const Decoded& d, const Decoded& reference,
             const std::optional<std::pair<double, double>>& range, const DisplayEncoding& encoding,
             StimulusAudit& s) {
  lightness_statistics(d, range, s);
  compare_with_reference(d, reference, s);
  if (!s.reference) s.quantisation_loss = quantisation_loss(d, reference, encoding);
}

// A note per condition whose change 8 bits would lose more than kQuantisationWarning of, naming
// the λ range where they would.
void add_quantisation_notes(AuditReport& report) {
  for (const AuditCondition& c : audit_conditions(report)) {
    std::optional<double> first, last;
    double worst = 0;
    for (const StimulusAudit* s : c.stimuli) {
      if (!s->quantisation_loss || *s->quantisation_loss <= kQuantisationWarning) continue;
      if (!first) first = s->lambda;
      last = s->lambda;
      worst = std::max(worst, *s->quantisation_loss);
    }
    if (!first) continue;
    std::ostringstream note;
    note << c.scene << " " << c.name << ": at 8 bits more than " << 100 * kQuantisationWarning
         << " % of the change would be lost at lambda " << format_value(*first)
         << (*last != *first ? " to " + format_value(*last) : std::string()) << " (up to "
         << std::lround(100 * worst)
         << " %); show these stimuli at 16 bits with dithering or on a 10-bit display";
    report.notes.push_back(note.str());
  }
}

// The render an entry belongs to: its scene and, in a sequence, its frame.
std::pair<std::string, int> shot_of(const ManifestEntry& e) {
  return {e.scene, e.frame ? e.frame->index : -1};
}

// Each stimulus's mean L* drift from its own reference.
void set_drifts(AuditReport& report) {
  std::map<std::pair<std::string, int>, double> reference_mean;
  for (const auto& s : report.stimuli)
    if (s.reference) reference_mean[{s.scene, s.frame}] = s.mean_lightness;
  for (auto& s : report.stimuli) s.drift = s.mean_lightness - reference_mean.at({s.scene, s.frame});
}

// Every reference image, decoded, by (scene, frame); and each scene's display encoding.
std::map<std::pair<std::string, int>, Decoded> decoded_references(
    const Manifest& manifest, const std::filesystem::path& dir,
    std::map<std::string, DisplayEncoding>& encodings, std::vector<std::string>& notes) {
  std::map<std::pair<std::string, int>, Decoded> references;
  for (const auto& e : manifest.stimuli)
    if (e.is_reference()) {
      encodings.emplace(e.scene, encoding_of(e, notes));
      Decoded d = decode(resolve_in_set(dir, e.file), encodings.at(e.scene));
      if (d.bits == 16) {
        d.at_8_bits = rounded_to_8_bits(d);
        d.lab_at_8_bits = display_to_lab(d.at_8_bits, encodings.at(e.scene), 8);
      }
      references.emplace(shot_of(e), std::move(d));
    }
  return references;
}

StimulusAudit describe(const ManifestEntry& e) {
  StimulusAudit s;
  s.file = e.file;
  s.sha256 = e.sha256;
  s.scene = e.scene;
  s.reference = e.is_reference();
  s.lambda = e.lambda;
  s.sigma = e.sigma.value_or(0.0);
  if (e.frame) s.frame = e.frame->index;
  if (!s.reference) s.condition = e.condition_method() + " sigma " + format_value(s.sigma);
  if (const auto noise = image_noise(e)) {
    s.noise_rms = noise->rms;
    s.noise_p99 = noise->p99;
    if (noise->budget) s.noise_met = noise->budget->met;
  }
  return s;
}

}  // namespace

size_t AuditReport::failed() const {
  return size_t(
      std::count_if(checks.begin(), checks.end(), [](const AuditCheck& c) { return !c.passed; }));
}

std::string AuditReport::summary() const {
  std::ostringstream s;
  s << stimuli.size() << " images, " << checks.size() << " checks, " << failed() << " failed";
  // How many of each kind, in the order the checks are made, when more than one kind failed.
  std::vector<std::pair<std::string, size_t>> kinds;
  for (const auto& c : checks) {
    if (c.passed) continue;
    auto it =
        std::find_if(kinds.begin(), kinds.end(), [&](const auto& k) { return k.first == c.check; });
    if (it == kinds.end())
      kinds.emplace_back(c.check, 1);
    else
      ++it->second;
  }
  for (size_t k = 0; kinds.size() > 1 && k < kinds.size(); ++k)
    s << (k == 0 ? " (" : ", ") << kinds[k].second << " " << kinds[k].first
      << (k + 1 == kinds.size() ? ")" : "");
  size_t shown = 0;
  for (const auto& c : checks)
    if (!c.passed && shown++ < 3)
      s << (shown == 1 ? ": " : "; ") << c.scene << " " << c.condition << " " << c.detail;
  if (failed() > 3) s << "; ...";
  return s.str();
}

AuditReport audit_stimulus_set(const std::filesystem::path& manifest_path,
                               const AuditOptions& options) {
  const Manifest manifest = read_verified_manifest(manifest_path);
  const std::filesystem::path dir = manifest_path.parent_path();
  AuditReport report;
  report.manifest = manifest_path;
  report.set_name = manifest.experiment_name;
  if (manifest.experiment.contains("audit"))
    report.limits = read_audit_limits(
        JsonObject(manifest.experiment["audit"], manifest_path.string(), "experiment.audit"));
  std::map<std::string, DisplayEncoding> encodings;
  const auto references = decoded_references(manifest, dir, encodings, report.notes);
  std::map<std::string, std::optional<std::pair<double, double>>>
      ranges;  // per scene, a calibrated display's
  for (const auto& e : manifest.stimuli)
    if (e.is_reference()) ranges[e.scene] = luminance_range(e);
  report.stimuli.resize(manifest.stimuli.size());
  std::atomic<size_t> done{0};
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(size_t(0), manifest.stimuli.size(), [&](size_t i) {
      const ManifestEntry& e = manifest.stimuli[i];
      StimulusAudit s = describe(e);
      const auto reference = references.find(shot_of(e));
      if (reference == references.end())
        throw_input_error(manifest_path.string(),
                          "scene " + e.scene + " has no reference image" +
                              (e.frame ? " for frame " + std::to_string(e.frame->index) : ""));
      Decoded own;
      if (!e.is_reference()) own = decode(resolve_in_set(dir, e.file), encodings.at(e.scene));
      const Decoded& d = e.is_reference() ? reference->second : own;
      if (d.width != reference->second.width || d.height != reference->second.height ||
          d.bits != reference->second.bits)
        throw_input_error(e.file, "differs in size or bit depth from its scene's reference");
      measure(d, reference->second, ranges.at(e.scene), encodings.at(e.scene), s);
      report.stimuli[i] = std::move(s);
      if (options.progress) options.progress(double(++done) / double(manifest.stimuli.size()));
    });
  });
  set_drifts(report);
  add_quantisation_notes(report);
  add_audit_checks(report, manifest);
  return report;
}

}  // namespace countershade
