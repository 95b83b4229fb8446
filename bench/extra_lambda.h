#pragma once
// What one extra λ of a method costs against the render it starts from: each iteration renders
// the scene's view for the method (as a stimulus set does: a method that renders again gets the
// render's ray log), prepares the method, then composes λ = 1 once, after one untimed round.
// Counters: render_s, compose_s and vs_render (compose over render, in the same run).

#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>
#include <string>

#include "enhance/method.h"
#include "enhance/view.h"
#include "enhance/view_plan.h"

namespace countershade {

inline void measure_extra_lambda(benchmark::State& state, const std::shared_ptr<const Scene>& scene,
                                 const std::string& method, const nlohmann::json& parameters) {
  auto seconds_since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  // One untimed round first: the process's first render pays one-time costs (thread pools, the
  // allocator's first pages) that would count against the render alone.
  const MethodUse use = parse_method(method, parameters);
  auto prepare = [&](const std::shared_ptr<const View>& view) {
    PrepareContext context = make_use_context(view, 0);
    context.compose_from_samples = true;
    return use.method->prepare(context, *use.parameters);
  };
  benchmark::DoNotOptimize(
      prepare(render_view(scene, plan_for(method, parameters, 1.0), {}))->compose(1.0));
  double render = 0, prepared_in = 0, compose = 0;
  for (auto _ : state) {
    auto t = std::chrono::steady_clock::now();
    const auto view = render_view(scene, plan_for(method, parameters, 1.0), {});
    render += seconds_since(t);
    t = std::chrono::steady_clock::now();
    const auto prepared = prepare(view);
    prepared_in += seconds_since(t);
    t = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(prepared->compose(1.0));
    compose += seconds_since(t);
  }
  state.counters["render_s"] = render / double(state.iterations());
  state.counters["prepare_s"] = prepared_in / double(state.iterations());
  state.counters["compose_s"] = compose / double(state.iterations());
  state.counters["vs_render"] = compose / render;
}

}  // namespace countershade
