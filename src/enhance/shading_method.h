#pragma once
// What the methods that change shading share (`lla`, `exaggerated-shading`): the normal scales
// they read (σ_1 and S), and a prepared state that renders the scene again with a hook per λ.

#include <functional>
#include <memory>

#include "core/parameters.h"
#include "enhance/light_alignment.h"
#include "enhance/method.h"
#include "enhance/multiscale_normals.h"

namespace countershade {

inline constexpr int kMaxNormalScales = int(kMaxAlignmentScales);

// σ_1 (the finest smoothing width: world units in `surface` mode, pixels in `image` mode), the
// number of scales S, the mode, and image mode's depth tolerance.
struct NormalScales {
  double sigma = 0;
  int scales = 3;
  bool image = false;
  double depth_tolerance = 0.02;
};

// Reads `scales` (2 … 8, default 3), `mode` (surface or image) and `depth_tolerance` now, and σ_1
// as `sigma`; call check_normal_scales after bag.finish() so that an unknown key is reported first.
NormalScales read_normal_scales(const ParameterBag& bag, std::optional<double>& sigma);
void check_normal_scales(const ParameterBag& bag, NormalScales& scales,
                         const std::optional<double>& sigma);
WidthAxis normal_scales_axis();
std::vector<ParameterDoc> normal_scales_docs();

// `terminator_fade`, which every shading method takes: the cosine band over which its change fades
// out towards the original light's terminator (ShadingHook::terminator_band). 0, the default, is
// no fade, and the method shades the dark side where it does so (docs/methods.md).
double read_terminator_fade(const ParameterBag& bag);
ParameterDoc terminator_fade_doc();

// The normals' entries of a method's recorded parameters: scales, mode and the mode's figures.
nlohmann::json describe_normals(const NormalScales& scales, const NormalScaleField& normals);

// What every shading method asks of rendering: a scene (its renders with hooks come later).
RenderRequest shading_request();
// InputError naming `method` when the context has no scene to render again (an external image).
void require_scene(const PrepareContext& context, const std::string& method);

// The multi-scale normals of the context's view in the chosen mode; InputError naming `method`
// without a scene.
std::shared_ptr<const NormalScaleField> scene_normals(const PrepareContext& context,
                                                      const NormalScales& scales,
                                                      const std::string& method);

// Each λ rendered again with the hook `hook_for(λ)`; a null hook gives the view itself (λ = 0).
class HookedRender final : public PreparedEnhancement {
 public:
  using HookFor = std::function<std::shared_ptr<const ShadingHook>(double lambda)>;
  HookedRender(const PrepareContext& context, HookFor hook_for, nlohmann::json parameters)
      : view_(context.view),
        render_again_(context.render_again),
        hook_for_(std::move(hook_for)),
        parameters_(std::move(parameters)) {}

  Composed compose(double lambda) const override;
  nlohmann::json parameters() const override { return parameters_; }

 private:
  std::shared_ptr<const View> view_;
  std::function<std::shared_ptr<const View>(const RenderRequest&)> render_again_;
  HookFor hook_for_;
  nlohmann::json parameters_;
};

}  // namespace countershade
