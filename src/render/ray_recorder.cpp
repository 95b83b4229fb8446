#include "render/ray_recorder.h"

#include <tbb/enumerable_thread_specific.h>

namespace countershade {

struct RayRecorder::Lists {
  tbb::enumerable_thread_specific<std::vector<RecordedRay>> per_thread;
};

RayRecorder::RayRecorder() : lists_(std::make_unique<Lists>()) {}
RayRecorder::~RayRecorder() = default;

void RayRecorder::add(const RecordedRay& ray) { lists_->per_thread.local().push_back(ray); }

std::vector<RecordedRay> RayRecorder::take() {
  std::vector<RecordedRay> all;
  for (std::vector<RecordedRay>& list : lists_->per_thread) {
    all.insert(all.end(), list.begin(), list.end());
    list.clear();
  }
  return all;
}

}  // namespace countershade
