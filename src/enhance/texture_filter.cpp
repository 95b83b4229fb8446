// Texture-space filtering (Semmo & Döllner 2015): an image filter (unsharp masking, bilateral
// abstraction, difference-of-Gaussians lines) applied to the rendered image (`post`), to a
// texture before its pyramid is built (`texture`), or to every level of the pyramid (`mip`).
// The filters and their λ are in enhance/lightness_filters.h; the pyramids in
// enhance/filtered_pyramid.h.

#include <map>

#include "core/error.h"
#include "enhance/filtered_pyramid.h"
#include "enhance/lightness.h"
#include "enhance/method.h"
#include "enhance/shading_method.h"

namespace countershade {
namespace {

enum class FilterMode { post, texture, mip };

struct TextureFilterParameters final : MethodParameters {
  FilterMode mode = FilterMode::mip;
  LightnessFilter filter;
  std::vector<double> level_strengths;  // mip only
};

std::string mode_name(FilterMode mode) {
  return mode == FilterMode::post ? "post" : (mode == FilterMode::texture ? "texture" : "mip");
}

// The textures of a render at one λ: each of the scene's textures replaced by its filtered pyramid.
class PyramidHook final : public TextureHook {
 public:
  void add(const Texture* plain, Texture filtered) { textures_.emplace(plain, std::move(filtered)); }
  const Texture* texture(unsigned, const Material& material) const override {
    const auto found = textures_.find(material.texture.get());
    return found == textures_.end() ? nullptr : &found->second;
  }

 private:
  std::map<const Texture*, Texture> textures_;
};

class FilteredTextures final : public PreparedEnhancement {
 public:
  FilteredTextures(const PrepareContext& context, std::vector<FilteredPyramid> pyramids, nlohmann::json parameters)
      : view_(context.view), render_again_(context.render_again), pyramids_(std::move(pyramids)),
        parameters_(std::move(parameters)) {}

  Composed compose(double lambda) const override {
    if (lambda == 0) return {view_->display, 0};
    auto hook = std::make_shared<PyramidHook>();
    for (const FilteredPyramid& p : pyramids_) hook->add(p.plain.get(), p.at(lambda));
    RenderRequest request;
    request.scene = true;
    request.texture_hook = std::move(hook);
    return {render_again_(request)->display, 0};
  }
  nlohmann::json parameters() const override { return parameters_; }

 private:
  std::shared_ptr<const View> view_;
  std::function<std::shared_ptr<const View>(const RenderRequest&)> render_again_;
  std::vector<FilteredPyramid> pyramids_;
  nlohmann::json parameters_;
};

// Every distinct texture of the scene's materials.
std::vector<std::shared_ptr<const Texture>> scene_textures(const Scene& scene) {
  std::vector<std::shared_ptr<const Texture>> out;
  for (const Object& o : scene.objects)
    if (o.material.texture && std::find(out.begin(), out.end(), o.material.texture) == out.end())
      out.push_back(o.material.texture);
  return out;
}

class TextureFilterMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "texture-filter"; }
  std::string summary() const override {
    return "an image filter in screen space (post), on the texture (texture) or on every mip level (mip)";
  }
  MethodAxes axes() const override {
    return {"the filter's strength: unsharp's gain, bilateral's blend towards the abstraction, dog's line strength",
            {{"sigma", "texels (pixels with mode post)", "the filter's spatial σ (dog: the finer of σ and 1.6σ)"}}};
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {{"sigma", "2", "spatial σ: texels of each level (mip), of the texture (texture), pixels (post)"},
            {"mode", "mip", "post: the rendered image; texture: the texture, then its pyramid; mip: every level"},
            {"filter", "unsharp", "unsharp (L* detail), bilateral (abstraction), dog (edge lines)"},
            {"sigma_r", "10", "bilateral: the range σ in L*"},
            {"tau", "1", "dog: how far below 0 the DoG must fall before a line starts, in L*"},
            {"phi", "0.5", "dog: the steepness of a line's soft edge, per L*"},
            {"level_strengths", "all 1", "mip: a strength multiplier per level, finest first (the last repeats)"}};
  }
  std::string label(const MethodParameters& parameters) const override {
    const auto& p = parameters_as<TextureFilterParameters>(parameters);
    return name() + "-" + mode_name(p.mode) + "-" + filter_name(p.filter.kind);
  }

  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<TextureFilterParameters>();
    const std::string mode = bag.choice("mode", "mip", {"post", "texture", "mip"});
    p->mode = mode == "post" ? FilterMode::post : (mode == "texture" ? FilterMode::texture : FilterMode::mip);
    p->filter = read_lightness_filter(bag);
    if (bag.has("level_strengths") && p->mode != FilterMode::mip) bag.fail("level_strengths", "applies to mode mip only");
    p->level_strengths = bag.numbers("level_strengths", {});
    for (double s : p->level_strengths)
      if (!(s >= 0 && s <= 100)) bag.fail("level_strengths", "every multiplier must lie in [0, 100]");
    bag.finish(name());
    return p;
  }

  RenderRequest request(const MethodParameters& parameters) const override {
    RenderRequest r;
    r.scene = parameters_as<TextureFilterParameters>(parameters).mode != FilterMode::post;
    r.renders_again = r.scene;  // every λ renders with its filtered textures
    return r;
  }

  std::shared_ptr<const ChangePerLambda> change_per_lambda(const MethodParameters& parameters) const override {
    const auto& p = parameters_as<TextureFilterParameters>(parameters);
    if (p.mode != FilterMode::post || p.filter.kind != FilterKind::unsharp) return nullptr;
    return std::make_shared<LightnessTimes>(1.0);  // as usm2d: the detail carries the pixel's noise
  }

  void check_scene(const Scene& scene, const MethodParameters& parameters) const override {
    const auto& p = parameters_as<TextureFilterParameters>(parameters);
    if (p.mode != FilterMode::post && scene_textures(scene).empty())
      throw InputError(name() + " in mode " + mode_name(p.mode) + " filters textures, and no object of " +
                       scene.file.string() + " has one (mode post filters the image)");
  }

  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    const auto& p = parameters_as<TextureFilterParameters>(parameters);
    if (p.mode == FilterMode::post) return prepare_post(context, p);
    return prepare_textures(context, p);
  }

 private:
  nlohmann::json describe(const TextureFilterParameters& p) const {
    nlohmann::json out{{"mode", mode_name(p.mode)}, {"filter", filter_name(p.filter.kind)}, {"sigma", p.filter.sigma}};
    if (p.filter.kind == FilterKind::bilateral) out["sigma_r"] = p.filter.sigma_r;
    if (p.filter.kind == FilterKind::dog) out.update({{"tau", p.filter.tau}, {"phi", p.filter.phi}});
    if (!p.level_strengths.empty()) out["level_strengths"] = p.level_strengths;
    return out;
  }

  std::unique_ptr<PreparedEnhancement> prepare_post(const PrepareContext& context, const TextureFilterParameters& p) const {
    const View& view = *context.view;
    const std::vector<float> detail =
        lightness_detail(view_lightness(view), view.width(), view.height(), p.filter, Borders::clamp, context.threads);
    LightnessChange change;
    change.amount.assign(detail.begin(), detail.end());
    return std::make_unique<LightnessPrepared>(context.view, std::move(change), describe(p),
                                               std::vector<std::pair<std::string, Image>>{}, context.threads,
                                               plain_noise(context));
  }

  std::unique_ptr<PreparedEnhancement> prepare_textures(const PrepareContext& context,
                                                        const TextureFilterParameters& p) const {
    require_scene(context, name());
    check_scene(*context.view->scene, p);
    const auto textures = scene_textures(*context.view->scene);
    const TextureMode mode = p.mode == FilterMode::mip ? TextureMode::mip : TextureMode::texture;
    std::vector<FilteredPyramid> pyramids;
    for (const auto& t : textures)
      pyramids.push_back(filter_pyramid(t, mode, p.filter, p.level_strengths, pyramid_cache_folder(), context.threads));
    nlohmann::json parameters = describe(p);
    parameters["textures"] = textures.size();
    return std::make_unique<FilteredTextures>(context, std::move(pyramids), std::move(parameters));
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_texture_filter_method() { return std::make_unique<TextureFilterMethod>(); }

}  // namespace countershade
