#pragma once
// Every ray a RayTracer traces while a recorder is attached, kept per thread: the rays of one
// render, to be replayed through Embree alone (RayTracer::replay), so that the renderer's rays
// per second can be set against what Embree does with the same rays (bench/render_bench.cpp,
// BM_RayRatio; docs/performance.md, "Renderer").

#include <cstdint>
#include <memory>
#include <vector>

namespace countershade {

// A ray as Embree receives it.
struct RecordedRay {
  float origin[3], direction[3], tnear, tfar;
  bool closest;  // a closest-hit query (intersect); else an any-hit one (occluded)
};

class RayRecorder {
 public:
  RayRecorder();
  ~RayRecorder();
  RayRecorder(const RayRecorder&) = delete;
  RayRecorder& operator=(const RayRecorder&) = delete;

  // Safe from any number of threads at once: each appends to its own list.
  void add(const RecordedRay& ray);
  // Every ray recorded so far, thread by thread (each thread's in its order); empties the lists.
  std::vector<RecordedRay> take();

 private:
  struct Lists;
  std::unique_ptr<Lists> lists_;
};

}  // namespace countershade
