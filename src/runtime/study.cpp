#include "runtime/study.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "core/error.h"
#include "core/random.h"

// What a study is once loaded (load_study.cpp reads it from a set). These functions need no file,
// so the browser's WebAssembly build (web/engine) compiles them too.

namespace countershade::runtime {

double Study::lambda(int index) const {
  return std::round((lambda_min + double(index) * lambda_step) * 1e9) / 1e9;
}

int Stimulus::frame_at(double seconds) const {
  if (fps <= 0 || frames.size() == 1) return frames[0];
  return frames[size_t(std::floor(std::max(0.0, seconds) * fps)) % frames.size()];
}

int Study::max_width() const {
  int w = 0;
  for (size_t c = 0; c < conditions.size(); ++c) w = std::max(w, width(int(c)));
  return w;
}

int Study::max_height() const {
  int h = 0;
  for (size_t c = 0; c < conditions.size(); ++c) h = std::max(h, height(int(c)));
  return h;
}

bool Study::changes_with_lambda(int condition) const {
  const auto& stimuli = condition_images[size_t(condition)];
  const std::string& reference = image_of(stimuli[0]).sha256;
  return std::any_of(stimuli.begin() + 1, stimuli.end(),
                     [&](int s) { return image_of(s).sha256 != reference; });
}

void check_subject_id(const std::string& subject) {
  if (subject.empty()) throw_input_error("--subject", "empty subject id");
  if (subject.size() > 64) throw_input_error("--subject", "longer than 64 characters");
  for (char c : subject)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'))
      throw_input_error(
          "--subject",
          "'" + subject + "' may only use letters, digits, '-' and '_' (it becomes a file name)");
}

uint64_t session_seed(uint64_t study_seed, const std::string& subject, int session) {
  return hash_combine(hash_combine(study_seed, hash_string(subject)), uint64_t(session));
}

}  // namespace countershade::runtime
