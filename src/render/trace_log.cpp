#include "render/trace_log.h"

#include <stdexcept>

namespace countershade {

void TraceLog::record_hit(size_t pixel, uint32_t sample, const std::optional<Hit>& hit) {
  Pixel& p = pixels_[pixel];
  if (sample != p.hits.size()) throw std::logic_error("TraceLog: samples recorded out of order");
  TracedHit traced;
  traced.first_answer = uint32_t(p.answers.size());
  if (hit) {
    traced.object = int32_t(hit->object);
    traced.triangle = hit->triangle;
    traced.b1 = float(hit->b1);
    traced.b2 = float(hit->b2);
  }
  p.hits.push_back(traced);
}

uint64_t TraceLog::projected_bytes(uint64_t planned) const {
  uint64_t samples = 0, answers = 0;
  for (const Pixel& p : pixels_) {
    samples += p.hits.size();
    answers += p.answers.size();
  }
  const double answers_per_sample = samples ? double(answers) / double(samples) : 0.0;
  return planned * sizeof(TracedHit) + uint64_t(double(planned) * answers_per_sample) +
         pixels_.size() * sizeof(Pixel);
}

void TraceLog::abandon() {
  abandoned_ = true;
  std::vector<Pixel>().swap(pixels_);
}

std::optional<Hit> TraceLog::hit(size_t pixel, uint32_t sample) const {
  const TracedHit& traced = pixels_[pixel].hits[sample];
  if (traced.object < 0) return std::nullopt;
  return Hit{unsigned(traced.object), traced.triangle, traced.b1, traced.b2, 0.0};
}

ShadowAnswers TraceLog::answers(size_t pixel, uint32_t sample) const {
  const Pixel& p = pixels_[pixel];
  const size_t end = sample + 1 < p.hits.size() ? p.hits[sample + 1].first_answer : p.answers.size();
  ShadowAnswers out;
  out.replay = p.answers.data() + p.hits[sample].first_answer;
  out.replay_end = p.answers.data() + end;
  return out;
}

}  // namespace countershade
