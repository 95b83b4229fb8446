#include "render/pixel_pass.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "core/color.h"
#include "core/parallel.h"
#include "core/random.h"
#include "render/camera.h"
#include "render/camera_samples.h"
#include "render/ray_differentials.h"
#include "render/record_replay.h"
#include "render/surface_sums.h"

namespace countershade {
namespace {

// Running sums per pixel and replicate: radiance, coverage, fields, and the radiance of each
// surface apart (render/surface_sums.h).
struct Sums {
  Sums(size_t n, size_t fields) : count(n, 0), surfaces(n) {
    for (int r = 0; r < 2; ++r) {
      for (auto& c : rgb[r]) c.assign(n, 0.0);
      hits[r].assign(n, 0.0);
      field[r].assign(fields, std::vector<double>(n, 0.0));
    }
  }
  std::vector<double> rgb[2][3], hits[2];
  std::vector<std::vector<double>> field[2];  // [replicate][field][pixel]
  std::vector<uint32_t> count;
  SurfaceSums surfaces;
  double samples(int r, size_t p) const {
    return double(r == 0 ? (count[p] + 1) / 2 : count[p] / 2);
  }
};

class PixelSampler {
 public:
  PixelSampler(const PixelPassInput& in, Sums& sums, TraceLog* record, const GBuffer& gbuffer,
               SampleObserver* observer = nullptr)
      : in_(in),
        sums_(sums),
        record_(record),
        gbuffer_(gbuffer),
        observer_(observer),
        rays_(in.scene.camera),
        width_(in.scene.camera.width),
        fixed_spp_(in.scene.settings.spp.value_or(0)) {}

  // Takes samples [count, target) of a pixel.
  void sample(size_t pixel, uint32_t target, RayCounts& rays, std::vector<glm::dvec2>& lhs) {
    const RenderSettings& settings = in_.scene.settings;
    if (settings.sampling == SamplingMode::independent)
      latin_hypercube(settings.seed, pixel, fixed_spp_, lhs);
    if (record_) record_->reserve(pixel, target, expected_hits(pixel, target));
    uint32_t s = sums_.count[pixel];
    if (traces_packets(s, target))
      for (; s < target; s += RayTracer::kPacket)
        packet_of_samples(pixel, s, std::min<uint32_t>(RayTracer::kPacket, target - s), rays, lhs);
    for (; s < target; ++s) one_sample(pixel, s, rays, lhs);
    sums_.count[pixel] = target;
    if (observer_) observer_->pixel_done(pixel, target);
  }

 private:
  // A camera sample: its random numbers (past the position in the pixel) and its ray.
  struct CameraSample {
    Sampler sampler;
    glm::dvec2 offset;
    Ray ray;
  };
  CameraSample camera_sample(size_t pixel, uint32_t s, const std::vector<glm::dvec2>& lhs) const {
    const RenderSettings& settings = in_.scene.settings;
    Sampler sampler(settings.sampling, settings.seed, kDomainPixel, pixel, s);
    const glm::dvec2 offset = sample_position(settings, sampler, lhs, s);
    const int x = int(pixel % size_t(width_)), y = int(pixel / size_t(width_));
    return {sampler, offset, rays_.ray(x + offset.x, y + offset.y)};
  }

  // Whether a pixel's samples [s, target) have their camera rays traced here as packets: all of a
  // fixed count's samples at once, as trace_camera_samples groups them (the same hits), where no
  // hits were traced ahead and none are read back.
  bool traces_packets(uint32_t s, uint32_t target) const {
    return in_.camera_packets && !in_.camera_hits && !in_.replay && s == 0 && fixed_spp_ > 0 &&
           target == uint32_t(fixed_spp_);
  }

  // Samples [first, first + n) of a pixel, their camera rays traced together.
  void packet_of_samples(size_t pixel, uint32_t first, uint32_t n, RayCounts& counts,
                         const std::vector<glm::dvec2>& lhs) {
    std::optional<CameraSample> samples[RayTracer::kPacket];
    glm::dvec3 origins[RayTracer::kPacket] = {}, directions[RayTracer::kPacket] = {};
    std::optional<Hit> hits[RayTracer::kPacket];
    for (uint32_t k = 0; k < n; ++k) {
      samples[k].emplace(camera_sample(pixel, first + k, lhs));
      origins[k] = samples[k]->ray.origin;
      directions[k] = samples[k]->ray.direction;
    }
    in_.tracer.intersect_packet(int(n), origins, directions, hits);
    if (!record_ && !observer_) return shade_together(pixel, first, n, samples, hits, counts);
    for (uint32_t k = 0; k < n; ++k) {
      ++counts.primary;
      ShadowAnswers answers;
      if (record_) {
        record_->record_hit(pixel, first + k, hits[k]);
        answers.record = record_->answers_to_record(pixel);
      }
      shade(pixel, first + k, *samples[k], hits[k], counts, answers);
    }
  }

  // A packet's samples on the plain path (nothing recorded or observed): their surfaces shaded
  // together (Shader::radiance_many), then every sample added to the sums in order.
  void shade_together(size_t pixel, uint32_t first, uint32_t n,
                      std::optional<CameraSample> (&samples)[RayTracer::kPacket],
                      const std::optional<Hit> (&hits)[RayTracer::kPacket], RayCounts& counts) {
    SurfacePoint points[RayTracer::kPacket];
    Shader::PointToShade to_shade[RayTracer::kPacket];
    glm::dvec3 shaded[RayTracer::kPacket];
    size_t m = 0;
    for (uint32_t k = 0; k < n; ++k)
      if (hits[k]) {
        points[m] = hit_point(pixel, *samples[k], *hits[k]);
        to_shade[m] = {&points[m], -samples[k]->ray.direction, &samples[k]->sampler};
        ++m;
      }
    in_.shader.radiance_many(std::span(to_shade, m), counts, shaded);
    counts.primary += n;
    for (uint32_t k = 0, j = 0; k < n; ++k) {
      if (!hits[k]) {
        accumulate(pixel, first + k, in_.shader.background(samples[k]->ray.direction), nullptr);
        continue;
      }
      const SampleHit hit = seen_along(points[j], samples[k]->ray.direction);
      accumulate(pixel, first + k, shaded[j], &hit);
      ++j;
    }
  }

  // A camera ray's hit on `point` for the sums: seen from behind where the ray runs along the
  // geometric normal.
  static SampleHit seen_along(const SurfacePoint& point, const glm::dvec3& direction) {
    return {point, glm::dot(point.geometric_normal, direction) > 0};
  }

  // The surface point a camera sample hit, with its UV footprint where a texture needs one.
  SurfacePoint hit_point(size_t pixel, const CameraSample& sample, const Hit& hit) const {
    SurfacePoint sp = surface_point(in_.scene, hit.object, hit.triangle, hit.b1, hit.b2);
    if (in_.shader.textured(hit.object)) {  // the footprint picks the texture's mip level
      const int x = int(pixel % size_t(width_)), y = int(pixel / size_t(width_));
      const glm::dvec2 offset = sample.offset;
      set_uv_differentials(in_.scene, rays_.ray(x + offset.x + 1, y + offset.y),
                           rays_.ray(x + offset.x, y + offset.y + 1), sp);
    }
    return sp;
  }

  void one_sample(size_t pixel, uint32_t s, RayCounts& counts, const std::vector<glm::dvec2>& lhs) {
    if (in_.replay && in_.replay->has_shading(pixel, s)) return replay_shading(pixel, s);
    CameraSample sample = camera_sample(pixel, s, lhs);
    ShadowAnswers answers;
    const auto hit = camera_hit(pixel, s, sample.ray, counts, answers);
    shade(pixel, s, sample, hit, counts, answers);
  }

  // One sample with its camera ray's hit: the background, or the surface's shading.
  void shade(size_t pixel, uint32_t s, CameraSample& sample, const std::optional<Hit>& hit,
             RayCounts& counts, ShadowAnswers& answers) {
    const Ray& ray = sample.ray;
    if (!hit) {
      const glm::dvec3 radiance = in_.shader.background(ray.direction);
      if (answers.record) record_->record_background(pixel, radiance);
      return accumulate(pixel, s, radiance, nullptr);
    }
    const SurfacePoint sp = hit_point(pixel, sample, *hit);
    const SampleHit sample_hit = seen_along(sp, ray.direction);
    auto [record, lights] = answers.record ? record_->shading_to_record(pixel)
                                           : std::pair<ShadingRecord*, LightSampleRecord*>{};
    Sampler& sampler = sample.sampler;
    if (!record && !observer_)
      return accumulate(
          pixel, s,
          in_.shader.radiance(sp, -ray.direction, true, sampler, counts, tracing_answers(answers)),
          &sample_hit);
    thread_local ShadingRecord observed;  // an observed sample's shading, where the log keeps none
    thread_local std::vector<LightSampleRecord> observed_lights;
    if (!record) {
      observed_lights.resize(in_.shader.light_samples());
      std::tie(record, lights) = std::pair{&observed, observed_lights.data()};
    }
    in_.shader.gather(sp, -ray.direction, true, sampler, counts, tracing_answers(answers), *record,
                      lights);
    accumulate(pixel, s, in_.shader.evaluate(sp, *record, lights, record->albedo), &sample_hit);
    if (observer_) observer_->surface(pixel, in_.shader, sp, *record, lights);
  }

  // How many of a pixel's first `target` samples will likely hit a surface: as many as so far, in
  // proportion, or all of them where its centre does (the log's records are reserved for them).
  uint32_t expected_hits(size_t pixel, uint32_t target) const {
    const uint32_t count = sums_.count[pixel];
    if (count == 0) return gbuffer_.object[pixel] >= 0 ? target : 0;
    const double hits = sums_.hits[0][pixel] + sums_.hits[1][pixel];
    return uint32_t(std::ceil(double(target) * hits / double(count)));
  }

  // A sample whose shading the replayed log kept: evaluated again with this render's hooks.
  void replay_shading(size_t pixel, uint32_t s) {
    const ReplayedSample replayed = replay_sample(in_.scene, in_.shader, *in_.replay, pixel, s);
    if (!replayed.point) return accumulate(pixel, s, replayed.radiance, nullptr);
    const SampleHit sample_hit{*replayed.point, replayed.back};
    accumulate(pixel, s, replayed.radiance, &sample_hit);
    if (observer_)
      observer_->surface(pixel, in_.shader, *replayed.point, in_.replay->shading(pixel, s),
                         in_.replay->light_samples(pixel, s));
  }

  // Adds one sample's radiance (and, for a hit, its fields) to the pixel's sums.
  void accumulate(size_t pixel, uint32_t s, const glm::dvec3& radiance, const SampleHit* hit) {
    const int r = Sampler::replicate(s);
    if (hit) {
      auto& fields = sums_.field[r];
      for (size_t f = 0; f < fields.size(); ++f)
        fields[f][pixel] += in_.request.fields[f]->value(*hit);
    }
    for (int c = 0; c < 3; ++c) sums_.rgb[r][c][pixel] += radiance[c];
    if (hit) sums_.hits[r][pixel] += 1.0;
    const uint32_t surface =
        hit ? SurfaceSums::surface_of(hit->point.object, hit->back) : SurfaceSums::kBackground;
    sums_.surfaces.add(r, pixel, surface, radiance);
  }

  // The camera ray's hit: read back from the replayed log where it holds the sample (with its
  // shadow answers), else traced (or read from the samples traced ahead) and recorded when the
  // render keeps a log.
  std::optional<Hit> camera_hit(size_t pixel, uint32_t s, const Ray& ray, RayCounts& counts,
                                ShadowAnswers& answers) const {
    if (in_.replay && in_.replay->has(pixel, s)) {
      answers = in_.replay->answers(pixel, s);
      return in_.replay->hit(pixel, s);
    }
    ++counts.primary;
    auto hit = in_.camera_hits && s < in_.camera_hits->spp()
                   ? in_.camera_hits->hit(pixel, s)
                   : in_.tracer.intersect(ray.origin, ray.direction);
    if (record_) {
      record_->record_hit(pixel, s, hit);
      answers.record = record_->answers_to_record(pixel);
    }
    return hit;
  }

  // The answers the shader records or replays; none on the plain path, which then asks only the
  // shadow rays it uses.
  static ShadowAnswers* tracing_answers(ShadowAnswers& answers) {
    return answers.record || answers.replay ? &answers : nullptr;
  }

  const PixelPassInput& in_;
  Sums& sums_;
  TraceLog* record_;  // null: nothing recorded
  const GBuffer& gbuffer_;
  SampleObserver* observer_;  // null: nobody watches
  CameraRays rays_;
  int width_;
  int fixed_spp_;
};

// Per pixel, the products of the replicates' differences: (ΔL)²/4 estimates Var(L), ΔL·Δc/4
// Cov(L, c) and (Δc)²/4 Var(c), for every requested change c.
struct ReplicateSpread {
  std::vector<double> LL;
  std::vector<std::vector<double>> LC, CC;  // [change][pixel]
};

// The products of one pixel's replicate differences into `out` (pixel p).
void pixel_spread(const Sums& sums, const PixelRequest& request, const Exposure& exposure, size_t p,
                  std::vector<double>* fields, ReplicateSpread& out) {
  PixelMeans means[2];
  for (int r = 0; r < 2; ++r) {
    const double k = sums.samples(r, p);
    const glm::dvec3 mean(sums.rgb[r][0][p] / k, sums.rgb[r][1][p] / k, sums.rgb[r][2][p] / k);
    for (size_t f = 0; f < fields[r].size(); ++f) fields[r][f] = sums.field[r][f][p] / k;
    const SurfaceSums::Luminance y = sums.surfaces.weighted_luminance(r, p, exposure);
    means[r] = {cielab_lightness(display_luminance(mean, exposure)),
                (y.surfaces + y.background) / k, y.surfaces / k, sums.hits[r][p] / k,
                fields[r].data()};
  }
  const double dL = means[0].lightness - means[1].lightness;
  out.LL[p] = 0.25 * dL * dL;
  for (size_t c = 0; c < request.changes.size(); ++c) {
    const PixelRequest::Change& change = request.changes[c];
    double value[2];
    for (int r = 0; r < 2; ++r) {
      PixelMeans own = means[r];
      own.fields = fields[r].data() + change.first_field;
      value[r] = change.change->value(own);
    }
    const double dc = value[0] - value[1];
    out.LC[c][p] = 0.25 * dL * dc;
    out.CC[c][p] = 0.25 * dc * dc;
  }
}

ReplicateSpread replicate_spread(const Sums& sums, const PixelRequest& request,
                                 const Exposure& exposure, int threads) {
  const size_t n = sums.count.size(), changes = request.changes.size();
  ReplicateSpread out{std::vector<double>(n, 0.0),
                      std::vector<std::vector<double>>(changes, std::vector<double>(n, 0.0)),
                      std::vector<std::vector<double>>(changes, std::vector<double>(n, 0.0))};
  parallel_ranges(
      n, threads,
      [&](size_t begin, size_t end) {
        std::vector<double> fields[2] = {std::vector<double>(request.fields.size()),
                                         std::vector<double>(request.fields.size())};
        for (size_t p = begin; p < end; ++p)
          if (sums.count[p] >= 2) pixel_spread(sums, request, exposure, p, fields, out);
      },
      4096);
  return out;
}

// A 3×3 mean, clamped at the borders.
std::vector<double> mean3x3(const std::vector<double>& in, int width, int height, int threads) {
  std::vector<double> out(in.size());
  parallel_ranges(
      size_t(height), threads,
      [&](size_t begin, size_t end) {
        for (int y = int(begin); y < int(end); ++y)
          for (int x = 0; x < width; ++x) {
            double acc = 0;
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) {
                const int xx = std::clamp(x + dx, 0, width - 1),
                          yy = std::clamp(y + dy, 0, height - 1);
                acc += in[size_t(yy) * width + xx];
              }
            out[size_t(y) * width + x] = acc / 9.0;
          }
      },
      16);
  return out;
}

// The largest variance of a pixel's stimuli: of L itself and of L + λ·c for every change at the
// strongest ±λ.
std::vector<double> largest_variance(const ReplicateSpread& pooled, double lambda) {
  std::vector<double> out = pooled.LL;
  for (size_t c = 0; c < pooled.LC.size(); ++c)
    for (size_t p = 0; p < out.size(); ++p)
      out[p] = std::max(out[p], pooled.LL[p] + 2.0 * lambda * std::abs(pooled.LC[c][p]) +
                                    lambda * lambda * pooled.CC[c][p]);
  return out;
}

class AdaptiveSampling {
 public:
  AdaptiveSampling(const PixelPassInput& in, RenderResult& result)
      : in_(in),
        result_(result),
        width_(in.scene.camera.width),
        height_(in.scene.camera.height),
        sums_(size_t(width_) * height_, in.request.fields.size()),
        order_(tile_order(width_, height_)) {}

  void run() {
    const RenderSettings& settings = in_.scene.settings;
    const auto start = std::chrono::steady_clock::now();
    const uint32_t first = uint32_t(settings.spp.value_or(settings.noise.min_spp));
    std::vector<uint32_t> target(sums_.count.size(), first);
    std::vector<uint32_t> active = order_;
    while (!active.empty()) {
      const auto round_start = std::chrono::steady_clock::now();
      sample_round(active, target);
      ++result_.sampling.rounds;
      if (settings.spp && !in_.estimate_noise) break;  // a fixed count without its noise
      estimate();
      if (settings.spp) break;  // a fixed count: one round
      active = unconverged(active, target);
      const double elapsed = seconds_since(start), last = seconds_since(round_start);
      if (!active.empty() && settings.noise.time_limit_s > 0 &&
          elapsed + 2 * last > settings.noise.time_limit_s) {
        result_.sampling.stopped_by = "time_limit";
        break;
      }
    }
    result_.sampling.seconds = seconds_since(start);
    result_.sampling.budget_met = settings.spp || result_.sampling.stopped_by.empty();
    finish();
  }

 private:
  static double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  }
  Exposure exposure() const { return in_.scene.display.exposure(); }

  void sample_round(const std::vector<uint32_t>& active, const std::vector<uint32_t>& target) {
    keep_log_within_limit(target);
    PixelSampler sampler(in_, sums_, in_.record && !in_.record->abandoned() ? in_.record : nullptr,
                         result_.gbuffer);
    std::mutex mutex;
    std::atomic<size_t> done{0};
    const int round = result_.sampling.rounds;
    parallel_ranges(
        active.size(), in_.threads,
        [&](size_t begin, size_t end) {
          RayCounts counts;
          std::vector<glm::dvec2> lhs;
          for (size_t i = begin; i < end; ++i)
            sampler.sample(active[i], target[active[i]], counts, lhs);
          std::lock_guard<std::mutex> lock(mutex);
          result_.rays += counts;
          done += end - begin;
          if (in_.progress) in_.progress(progress(round, double(done) / double(active.size())));
        },
        64);
  }

  // Gives the log's shading records up before a round that would take the log past half its
  // memory limit (recording them costs time too: a render that would drop them later should not
  // record them at all), then the whole log (the render goes on without it) before a round that
  // would take it past its limit. The decisions depend only on the sample counts, like the image.
  void keep_log_within_limit(const std::vector<uint32_t>& target) {
    TraceLog* log = in_.record;
    if (!log || log->abandoned()) return;
    uint64_t planned = 0;
    for (uint32_t t : target) planned += t;
    if (log->keeps_shading() && log->projected_bytes(planned, true) > log->byte_limit() / 2)
      log->drop_shading();
    if (log->projected_bytes(planned, false) > log->byte_limit()) log->abandon();
  }

  // A rough share of the work done: the first round is most of it when few pixels need more.
  double progress(int round, double within) const {
    const int rounds =
        1 +
        int(std::log2(double(in_.scene.settings.noise.max_spp) / in_.scene.settings.noise.min_spp));
    return std::min(1.0,
                    (round + within) / double(in_.scene.settings.spp ? 1 : std::max(1, rounds)));
  }

  // The 3×3 means are the estimates (nine replicate pairs). A further 3×3 mean of the stimuli's
  // largest variance decides: an estimate from one pixel's two replicates is too rough to stop on
  // (it stops pixels that were merely lucky and wastes samples on unlucky ones).
  void estimate() {
    const int threads = in_.threads;
    ReplicateSpread spread = replicate_spread(sums_, in_.request, exposure(), threads);
    pooled_.LL = mean3x3(spread.LL, width_, height_, threads);
    pooled_.LC.resize(spread.LC.size());
    pooled_.CC.resize(spread.CC.size());
    for (size_t c = 0; c < spread.LC.size(); ++c) {
      pooled_.LC[c] = mean3x3(spread.LC[c], width_, height_, threads);
      pooled_.CC[c] = mean3x3(spread.CC[c], width_, height_, threads);
    }
    decision_ =
        mean3x3(largest_variance(pooled_, in_.request.max_abs_lambda), width_, height_, threads);
  }

  // The active pixels that still miss their threshold, with their next sample counts.
  std::vector<uint32_t> unconverged(const std::vector<uint32_t>& active,
                                    std::vector<uint32_t>& target) {
    const NoiseBudget& budget = in_.scene.settings.noise;
    const double threshold = stopping_threshold(active);
    std::vector<uint32_t> next;
    for (uint32_t p : active) {
      if (std::sqrt(decision_[p]) <= threshold) continue;
      if (sums_.count[p] >= uint32_t(budget.max_spp)) {
        result_.sampling.stopped_by = "max_spp";
        continue;
      }
      target[p] = next_count(sums_.count[p], decision_[p] / (threshold * threshold));
      next.push_back(p);
    }
    return next;
  }

  // The L* standard error at which an active pixel stops. Over pixels, the target itself. Over the
  // image, the largest threshold t at which the image's mean variance, the stopped pixels at their
  // estimates and the active ones at min(estimate, t²), stays within kImageMargin² of the target's,
  // and t at most the p99 bound over 2.576 (a normal error's 99th percentile of |e|): the pixels
  // whose noise costs most samples (soft shadows, dark surfaces) carry more of it, where flat ones
  // already sit below the target at min_spp.
  double stopping_threshold(const std::vector<uint32_t>& active) const {
    const NoiseBudget& budget = in_.scene.settings.noise;
    const double target = in_.request.share * budget.target;
    if (budget.allocation == NoiseAllocation::pixel) return target;
    // The estimates are rough: a tenth of the RMS in hand (the ritschel2008 scenes then measure
    // 0.38 to 0.45 L* with two seeds, tests/stimuli/noise_budget_test).
    constexpr double kImageMargin = 0.9;
    std::vector<uint8_t> is_active(decision_.size(), 0);
    for (uint32_t p : active) is_active[p] = 1;
    double stopped = 0;
    std::vector<double> open;
    open.reserve(active.size());
    for (size_t p = 0; p < decision_.size(); ++p) {
      if (is_active[p])
        open.push_back(decision_[p]);
      else
        stopped += decision_[p];
    }
    const auto within = [&](double t2) {
      double sum = stopped;
      for (double v : open) sum += std::min(v, t2);
      return sum <= double(decision_.size()) * std::pow(kImageMargin * target, 2);
    };
    double lo = target * target, hi = std::pow(in_.request.share * budget.p99 / 2.576, 2);
    if (hi <= lo || !within(lo)) return target;
    if (within(hi)) return std::sqrt(hi);
    for (int step = 0; step < 40; ++step) {
      const double mid = 0.5 * (lo + hi);
      (within(mid) ? lo : hi) = mid;
    }
    return std::sqrt(lo);
  }

  // The count at which a pixel whose variance is `excess` × its target's should meet it (the
  // variance falls as 1/count), with a 10 % margin, an even count (two replicates), at least a
  // quarter more and at most four times the samples so far (the estimate is rough).
  uint32_t next_count(uint32_t count, double excess) const {
    const double wanted = std::clamp(1.1 * excess, 1.25, 4.0) * count;
    const uint32_t even = 2 * uint32_t(std::ceil(0.5 * wanted));
    return std::min<uint32_t>(even, uint32_t(in_.scene.settings.noise.max_spp));
  }

  void finish() {
    const size_t n = sums_.count.size();
    result_.radiance = Image(width_, height_, 3, Image::Uninitialized{});
    result_.fields.assign(in_.request.fields.size(), std::vector<float>(n));
    result_.luminance.resize(n);
    result_.surface_luminance.resize(n);
    result_.coverage.resize(n);
    result_.noise.resize(n);
    result_.spp = sums_.count;
    for (size_t p = 0; p < n; ++p) {
      const double k = double(sums_.count[p]);
      auto both = [&](const std::vector<double>* v) { return float((v[0][p] + v[1][p]) / k); };
      for (int c = 0; c < 3; ++c)
        result_.radiance.pixels[3 * p + c] = float((sums_.rgb[0][c][p] + sums_.rgb[1][c][p]) / k);
      for (size_t f = 0; f < result_.fields.size(); ++f)
        result_.fields[f][p] = float((sums_.field[0][f][p] + sums_.field[1][f][p]) / k);
      const SurfaceSums::Luminance y = sums_.surfaces.weighted_luminance(-1, p, exposure());
      result_.luminance[p] = float((y.surfaces + y.background) / k);
      result_.surface_luminance[p] = float(y.surfaces / k);
      result_.coverage[p] = both(sums_.hits);
      result_.noise[p] = pooled_.LL.empty() ? 0.0f : float(std::sqrt(pooled_.LL[p]));
    }
    result_.change_noise.resize(pooled_.LC.size());
    for (size_t c = 0; c < pooled_.LC.size(); ++c) {
      result_.change_noise[c].covariance.assign(pooled_.LC[c].begin(), pooled_.LC[c].end());
      result_.change_noise[c].variance.assign(pooled_.CC[c].begin(), pooled_.CC[c].end());
    }
    auto [lo, hi] = std::minmax_element(sums_.count.begin(), sums_.count.end());
    double total = 0;
    for (uint32_t c : sums_.count) total += c;
    result_.sampling.pixels = {*lo, *hi, total / double(n)};
  }

  const PixelPassInput& in_;
  RenderResult& result_;
  int width_, height_;
  Sums sums_;
  std::vector<uint32_t> order_;
  ReplicateSpread pooled_;
  std::vector<double> decision_;
};

}  // namespace

void pixel_pass(const PixelPassInput& input, RenderResult& result) {
  AdaptiveSampling(input, result).run();
}

void observe_samples(const Scene& scene, const RayTracer& tracer,
                     const std::vector<uint32_t>& counts, const TraceLog* replay,
                     SampleObserver& observer, int threads) {
  const int width = scene.camera.width, height = scene.camera.height;
  if (counts.size() != size_t(width) * size_t(height))
    throw std::logic_error("observe_samples: one count per pixel");
  if (replay && replay->pixel_count() != counts.size()) replay = nullptr;
  const Shader shader(scene, tracer);
  const PixelRequest request;
  const PixelPassInput in{scene, tracer, shader, request, threads, {}, nullptr, replay, false};
  Sums sums(counts.size(), 0);
  const GBuffer none;  // expected_hits reads it only while a log records
  PixelSampler sampler(in, sums, nullptr, none, &observer);
  const std::vector<uint32_t> order = tile_order(width, height);
  parallel_ranges(
      order.size(), threads,
      [&](size_t begin, size_t end) {
        RayCounts rays;
        std::vector<glm::dvec2> lhs;
        for (size_t i = begin; i < end; ++i) sampler.sample(order[i], counts[order[i]], rays, lhs);
      },
      64);
}

}  // namespace countershade
