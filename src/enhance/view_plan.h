#pragma once
// What a view is rendered for, and the short paths from a method's name to a prepared
// enhancement: a plan of method uses, the render of a scene for a plan (one render for every use,
// sampled to the noise budget at the plan's strongest λ), and prepare_method for tools and tests.

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "enhance/method.h"
#include "enhance/view.h"
#include "render/render_request.h"

namespace countershade {

// What a view is rendered for: every method that will enhance it, and the strongest λ they use.
struct ViewPlan {
  std::vector<MethodUse> uses;
  double max_abs_lambda = 0;
  RenderRequest request() const;  // the uses' requests merged
  // Adds a use of the named method (InputError for an unknown method or bad parameters).
  ViewPlan& add(const std::string& method, const nlohmann::json& parameters);
};

// Parses a JSON object of parameters for the named method (InputError for an unknown method or
// bad parameters).
MethodUse parse_method(const std::string& method, const nlohmann::json& parameters);

// Prepares the named method with these parameters on a view: the short path for tools and
// tests. A method with a surface stage must be one of the uses the view was rendered for.
std::unique_ptr<PreparedEnhancement> prepare_method(const std::string& method,
                                                    std::shared_ptr<const View> view,
                                                    const nlohmann::json& parameters,
                                                    int threads = 0);

// Applies the request's scene changes (mesh refinement) before the scene is rendered.
void apply_request(Scene& scene, const RenderRequest& request);

struct ViewOptions {
  int bits = 8;
  int threads = 0;
  std::function<void(double)> progress;
};

// Renders a scene for a plan and makes its view: one render for every use, with the fields their
// surface stages ask for, sampled to the noise budget at the plan's strongest λ.
std::shared_ptr<const View> render_view(std::shared_ptr<const Scene> scene, const ViewPlan& plan,
                                        const ViewOptions& options);
// The plain view (no methods).
std::shared_ptr<const View> render_view(std::shared_ptr<const Scene> scene,
                                        const ViewOptions& options = {});

// The plan of one method.
ViewPlan plan_for(const std::string& method, const nlohmann::json& parameters,
                  double max_abs_lambda);

}  // namespace countershade
