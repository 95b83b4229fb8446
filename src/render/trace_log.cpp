#include "render/trace_log.h"

#include <algorithm>
#include <stdexcept>

namespace countershade {

void TraceLog::reserve(size_t pixel, uint32_t samples, uint32_t hits) {
  Pixel& p = pixels_[pixel];
  p.hits.reserve(samples);
  if (!keeps_shading_) return;
  hits = std::min(hits, samples);
  p.records.reserve(hits);
  p.lights.reserve(size_t(hits) * light_samples_);
  p.backgrounds.reserve(samples - hits);
}

void TraceLog::record_hit(size_t pixel, uint32_t sample, const std::optional<Hit>& hit) {
  Pixel& p = pixels_[pixel];
  if (sample != p.hits.size()) throw std::logic_error("TraceLog: samples recorded out of order");
  TracedHit traced;
  traced.first_answer = uint32_t(p.answers.size());
  traced.hit = PackedHit::of(hit);
  p.hits.push_back(traced);
}

std::pair<ShadingRecord*, LightSampleRecord*> TraceLog::shading_to_record(size_t pixel) {
  if (!keeps_shading_) return {nullptr, nullptr};
  Pixel& p = pixels_[pixel];
  p.hits.back().shaded = uint32_t(p.records.size());
  p.records.emplace_back();
  p.lights.resize(p.lights.size() + light_samples_);
  return {&p.records.back(), p.lights.data() + p.lights.size() - light_samples_};
}

void TraceLog::record_background(size_t pixel, const glm::dvec3& radiance) {
  if (!keeps_shading_) return;
  Pixel& p = pixels_[pixel];
  p.hits.back().shaded = uint32_t(p.backgrounds.size());
  p.backgrounds.push_back(radiance);
}

uint64_t TraceLog::projected_bytes(uint64_t planned, bool with_shading) const {
  uint64_t samples = 0, answers = 0, shading = 0;
  for (const Pixel& p : pixels_) {
    samples += p.hits.size();
    answers += p.answers.size();
    shading += p.records.size() * sizeof(ShadingRecord) +
               p.lights.size() * sizeof(LightSampleRecord) +
               p.backgrounds.size() * sizeof(glm::dvec3);
  }
  const double answers_per_sample = samples ? double(answers) / double(samples) : 0.0;
  // Before any sample is seen, every sample counts as a hit.
  const double shading_per_sample =
      samples ? double(shading) / double(samples)
              : double(sizeof(ShadingRecord) + light_samples_ * sizeof(LightSampleRecord));
  const double per_sample =
      double(sizeof(TracedHit)) + answers_per_sample + (with_shading ? shading_per_sample : 0.0);
  return uint64_t(double(planned) * per_sample) + pixels_.size() * sizeof(Pixel);
}

void TraceLog::drop_shading() {
  keeps_shading_ = false;
  for (Pixel& p : pixels_) {
    std::vector<ShadingRecord>().swap(p.records);
    std::vector<LightSampleRecord>().swap(p.lights);
    std::vector<glm::dvec3>().swap(p.backgrounds);
  }
}

void TraceLog::abandon() {
  abandoned_ = true;
  keeps_shading_ = false;
  std::vector<Pixel>().swap(pixels_);
}

ShadowAnswers TraceLog::answers(size_t pixel, uint32_t sample) const {
  const Pixel& p = pixels_[pixel];
  const size_t end =
      sample + 1 < p.hits.size() ? p.hits[sample + 1].first_answer : p.answers.size();
  ShadowAnswers out;
  out.replay = p.answers.data() + p.hits[sample].first_answer;
  out.replay_end = p.answers.data() + end;
  return out;
}

}  // namespace countershade
