#include "enhance/view_plan.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "enhance/registry.h"
#include "render/renderer.h"

namespace countershade {

MethodUse parse_method(const std::string& method, const nlohmann::json& parameters) {
  MethodUse use;
  use.method = &method_named(method, "method");
  use.parameters = use.method->parse(ParameterBag::from_json(parameters, method, "parameters"));
  use.parameters_json = parameters;
  return use;
}

std::unique_ptr<PreparedEnhancement> prepare_method(const std::string& method,
                                                    std::shared_ptr<const View> view,
                                                    const nlohmann::json& parameters, int threads) {
  const MethodUse use = parse_method(method, parameters);
  for (size_t u = 0; u < view->uses.size(); ++u)
    if (view->uses[u].method == use.method && view->uses[u].parameters_json == parameters)
      return use.method->prepare(make_use_context(view, u, threads), *view->uses[u].parameters);
  return use.method->prepare(make_context(view, threads), *use.parameters);  // no stage
}

void apply_request(Scene& scene, const RenderRequest& request) {
  if (request.refine_edge_length) refine_scene(scene, *request.refine_edge_length);
}

RenderRequest ViewPlan::request() const {
  RenderRequest merged;
  for (const auto& use : uses)
    merged.merge(use.method->request(*use.parameters), use.method->name());
  return merged;
}

ViewPlan& ViewPlan::add(const std::string& method, const nlohmann::json& parameters) {
  uses.push_back(parse_method(method, parameters));
  return *this;
}

ViewPlan plan_for(const std::string& method, const nlohmann::json& parameters,
                  double max_abs_lambda) {
  ViewPlan plan;
  plan.max_abs_lambda = max_abs_lambda;
  return plan.add(method, parameters);
}

namespace {

// The share of the noise budget left to the pixels' own noise: all of it, unless a method builds
// on the per-vertex signal, whose noise takes the rest.
constexpr double kPixelShareWithVertices = 0.9;

// Per object, the strictest need of the plan's uses. The vertex signal takes the part of the
// budget that the pixels leave.
std::vector<VertexNeed> vertex_needs(const Scene& scene, const ViewPlan& plan) {
  const double allowed = std::sqrt(1.0 - kPixelShareWithVertices * kPixelShareWithVertices) *
                         scene.settings.noise.target;
  std::vector<std::optional<VertexNeed>> strictest(scene.objects.size());
  for (const auto& use : plan.uses) {
    const auto own = use.method->vertex_needs(scene, *use.parameters, plan.max_abs_lambda, allowed);
    for (size_t o = 0; o < std::min(own.size(), strictest.size()); ++o) {
      if (!strictest[o]) strictest[o] = own[o];
      strictest[o]->noise = std::min(strictest[o]->noise, own[o].noise);
      strictest[o]->rings = std::max(strictest[o]->rings, own[o].rings);
      const int a = strictest[o]->support, b = own[o].support;
      strictest[o]->support = a < 0 || b < 0 ? -1 : std::max(a, b);
    }
  }
  std::vector<VertexNeed> needs;  // the budget's target where no method says otherwise
  for (const auto& need : strictest)
    needs.push_back(need.value_or(VertexNeed{scene.settings.noise.target, 1}));
  return needs;
}

// The stages of every use and the fields and changes they give the pixel pass.
struct Stages {
  std::vector<std::shared_ptr<const SurfaceStage>> stages;
  std::vector<std::vector<size_t>> fields;
  std::vector<int> changes;

  PixelRequest build(const Scene& scene, const ViewPlan& plan, const RenderResult& so_far,
                     int threads) {
    PixelRequest request;
    request.share = plan.request().vertex_radiance ? kPixelShareWithVertices : 1.0;
    request.max_abs_lambda = plan.max_abs_lambda;
    stages.assign(plan.uses.size(), nullptr);
    fields.assign(plan.uses.size(), {});
    changes.assign(plan.uses.size(), -1);
    for (size_t u = 0; u < plan.uses.size(); ++u) {
      const MethodUse& use = plan.uses[u];
      const size_t first = request.fields.size();
      stages[u] = use.method->surface_stage({scene, so_far, threads}, *use.parameters);
      if (stages[u])
        for (auto& field : stages[u]->fields()) {
          fields[u].push_back(request.fields.size());
          request.fields.push_back(std::move(field));
        }
      if (auto change = use.method->change_per_lambda(*use.parameters)) {
        changes[u] = int(request.changes.size());
        request.changes.push_back({std::move(change), first});
      }
    }
    return request;
  }
};

}  // namespace

std::shared_ptr<const View> render_view(std::shared_ptr<const Scene> scene, const ViewPlan& plan,
                                        const ViewOptions& options) {
  const RenderRequest request = plan.request();
  auto tracer = std::make_shared<const RayTracer>(*scene);
  RenderOptions ro;
  ro.threads = options.threads;
  ro.vertex_radiance = request.vertex_radiance;
  ro.ring_samples = request.ring_samples;
  ro.vertex_needs = vertex_needs(*scene, plan);
  ro.shading_hook = request.shading_hook;
  ro.texture_hook = request.texture_hook;
  ro.record_trace = request.renders_again;
  ro.progress = options.progress;
  Stages stages;
  ro.before_pixels = [&](const RenderResult& so_far) {
    return stages.build(*scene, plan, so_far, options.threads);
  };
  RenderResult result = render(*scene, *tracer, ro);
  auto view = std::const_pointer_cast<View>(
      make_view(std::move(scene), std::move(tracer), std::move(result), options.bits));
  view->uses = plan.uses;
  view->stages = std::move(stages.stages);
  view->stage_fields = std::move(stages.fields);
  view->change_noise = std::move(stages.changes);
  return view;
}

std::shared_ptr<const View> render_view(std::shared_ptr<const Scene> scene,
                                        const ViewOptions& options) {
  return render_view(std::move(scene), ViewPlan{}, options);
}

}  // namespace countershade
