// Texture-space filtering (Semmo & Döllner 2015): an image filter (unsharp masking, bilateral
// abstraction, difference-of-Gaussians lines) applied to the rendered image (`post`), to a
// texture before its pyramid is built (`texture`), or to every level of the pyramid (`mip`).
// The filters and their λ are in enhance/lightness_filters.h; the pyramids in
// enhance/filtered_pyramid.h.

#include <map>
#include <optional>

#include "core/error.h"
#include "core/parallel.h"
#include "enhance/filtered_pyramid.h"
#include "enhance/lightness.h"
#include "enhance/method.h"
#include "enhance/shading_method.h"
#include "enhance/texel_weights.h"
#include "render/shading.h"

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
  void add(const Texture* plain, Texture filtered) {
    textures_.emplace(plain, std::move(filtered));
  }
  const Texture* texture(unsigned, const Material& material) const override {
    const auto found = textures_.find(material.texture.get());
    return found == textures_.end() ? nullptr : &found->second;
  }

 private:
  std::map<const Texture*, Texture> textures_;
};

// Per sample, the change of L* per unit λ that the filtered texture makes to the light it
// reflects, over that light's L* + 16 (FilteredPyramid::relative_detail), looked up with the
// sample's footprint; 0 on objects without a filtered texture.
class RelativeDetailField final : public SampleField {
 public:
  RelativeDetailField(const Scene& scene, const std::vector<FilteredPyramid>& pyramids) {
    std::vector<const Texture*> plain;
    for (const FilteredPyramid& p : pyramids) {
      details_.push_back(p.relative_detail());
      plain.push_back(p.plain.get());
    }
    detail_of_ = texture_of_objects(scene, plain);
    for (const Object& o : scene.objects) repeat_.push_back(o.material.texture_repeat);
  }
  double value(const SampleHit& hit) const override {
    const SurfacePoint& p = hit.point;
    const int k = detail_of_[p.object];
    if (k < 0) return 0.0;
    const double r = repeat_[p.object];
    return details_[size_t(k)].sample(p.uv * r, p.duv_dx * r, p.duv_dy * r).x;
  }

 private:
  std::vector<Texture> details_;
  std::vector<int> detail_of_;  // per object: its texture's pyramid, or -1
  std::vector<double> repeat_;
};

// A pixel's change of L* per unit λ: the samples' relative change times the pixel's L* + 16.
class TexelDetailChange final : public ChangePerLambda {
 public:
  double value(const PixelMeans& means) const override {
    return means.fields[0] * (means.lightness + 16.0);
  }
};

// The filtered pyramids of a view's textures (made before its pixels are sampled, so that the
// sampling knows the change they make) and the field of that change.
class FilteredTextureStage final : public SurfaceStage {
 public:
  FilteredTextureStage(const Scene& scene,
                       std::shared_ptr<const std::vector<FilteredPyramid>> pyramids)
      : pyramids_(std::move(pyramids)),
        field_(std::make_shared<RelativeDetailField>(scene, *pyramids_)) {}
  SampleFields fields() const override { return {field_}; }
  const std::shared_ptr<const std::vector<FilteredPyramid>>& pyramids() const { return pyramids_; }

 private:
  std::shared_ptr<const std::vector<FilteredPyramid>> pyramids_;
  std::shared_ptr<const RelativeDetailField> field_;
};

class FilteredTextures final : public PreparedEnhancement {
 public:
  FilteredTextures(const PrepareContext& context,
                   std::shared_ptr<const std::vector<FilteredPyramid>> pyramids,
                   std::shared_ptr<const TexelWeights> weights, nlohmann::json parameters,
                   bool unsharp)
      : view_(context.view),
        render_again_(context.render_again),
        threads_(context.threads),
        pyramids_(std::move(pyramids)),
        weights_(std::move(weights)),
        parameters_(std::move(parameters)),
        noise_(plain_noise(context)),
        unsharp_(unsharp) {}

  Composed compose(double lambda) const override {
    if (lambda == 0) return {view_->display, 0};
    if (weights_) return {from_weights(lambda), 0};
    auto hook = std::make_shared<PyramidHook>();
    for (const FilteredPyramid& p : *pyramids_) hook->add(p.plain.get(), p.at(lambda));
    RenderRequest request;
    request.scene = true;
    request.texture_hook = std::move(hook);
    return {render_again_(request)->display, 0};
  }
  nlohmann::json parameters() const override { return parameters_; }
  NoiseModel noise(double lambda) const override { return noise_(lambda); }
  // The texture's unsharp masking at λ = −1 is its low-pass G*L in L*: the view rendered with it
  // is the low-pass of the texture as rendered.
  std::vector<float> mask() const override {
    if (!unsharp_) return {};
    const Image low_pass = compose(-1.0).display;
    const LabPixels lab = display_to_lab(low_pass, view_->encoding);
    std::vector<float> m(lab.size());
    for (size_t i = 0; i < m.size(); ++i) m[i] = float(lab[i].L);
    return m;
  }

 private:
  // The view's radiance with every texel its samples read changed to its value at λ.
  Image from_weights(double lambda) const {
    const std::vector<FilteredPyramid>& pyramids = *pyramids_;
    std::vector<std::optional<Texture>> whole(
        pyramids.size());  // texture mode: every level changes
    for (size_t k = 0; k < pyramids.size(); ++k)
      if (pyramids[k].mode == TextureMode::texture) whole[k] = pyramids[k].at(lambda);
    const auto& texels = weights_->texels();
    std::vector<glm::dvec3> change(texels.size());
    parallel_ranges(
        texels.size(), threads_,
        [&](size_t begin, size_t end) {
          for (size_t i = begin; i < end; ++i) {
            const TexelWeights::Texel& t = texels[i];
            const FilteredPyramid& p = pyramids[t.texture];
            const glm::vec3 at = whole[t.texture]
                                     ? whole[t.texture]->levels()[t.level].texels[t.index]
                                     : p.mip_texel_at(lambda, t.level, t.index);
            change[i] = glm::dvec3(at) - glm::dvec3(p.plain->levels()[t.level].texels[t.index]);
          }
        },
        4096);
    RenderResult result;
    result.radiance = weights_->radiance_with(view_->render.radiance, change, threads_);
    return make_view(view_->scene, view_->tracer, std::move(result), view_->bits, false)->display;
  }

  std::shared_ptr<const View> view_;
  std::function<std::shared_ptr<const View>(const RenderRequest&)> render_again_;
  int threads_;
  std::shared_ptr<const std::vector<FilteredPyramid>> pyramids_;
  std::shared_ptr<const TexelWeights> weights_;  // null: every λ renders again
  nlohmann::json parameters_;
  NoiseFunction noise_;
  bool unsharp_;  // the filter is unsharp masking: it has a mask
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
    return "an image filter in screen space (post), on the texture (texture) or on every mip level "
           "(mip)";
  }
  MethodAxes axes() const override {
    return {
        "the filter's strength: unsharp's gain, bilateral's blend towards the abstraction, dog's "
        "line strength",
        {{"sigma", "texels (pixels with mode post)",
          "the filter's spatial σ (dog: the finer of σ and 1.6σ)"}}};
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {{"sigma", "2",
             "spatial σ: texels of each level (mip), of the texture (texture), pixels (post)"},
            {"mode", "mip",
             "post: the rendered image; texture: the texture, then its pyramid; mip: every level"},
            {"filter", "unsharp", "unsharp (L* detail), bilateral (abstraction), dog (edge lines)"},
            {"sigma_r", "10", "bilateral: the range σ in L*"},
            {"tau", "1", "dog: how far below 0 the DoG must fall before a line starts, in L*"},
            {"phi", "0.5", "dog: the steepness of a line's soft edge, per L*"},
            {"level_strengths", "all 1",
             "mip: a strength multiplier per level, finest first (the last repeats)"}};
  }
  std::string label(const MethodParameters& parameters) const override {
    const auto& p = parameters_as<TextureFilterParameters>(parameters);
    return name() + "-" + mode_name(p.mode) + "-" + filter_name(p.filter.kind);
  }

  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<TextureFilterParameters>();
    const std::string mode = bag.choice("mode", "mip", {"post", "texture", "mip"});
    p->mode = mode == "post" ? FilterMode::post
                             : (mode == "texture" ? FilterMode::texture : FilterMode::mip);
    p->filter = read_lightness_filter(bag);
    if (bag.has("level_strengths") && p->mode != FilterMode::mip)
      bag.fail("level_strengths", "applies to mode mip only");
    p->level_strengths = bag.numbers("level_strengths", {});
    for (double s : p->level_strengths)
      if (!(s >= 0 && s <= 100))
        bag.fail("level_strengths", "every multiplier must lie in [0, 100]");
    bag.finish(name());
    return p;
  }

  RenderRequest request(const MethodParameters& parameters) const override {
    RenderRequest r;
    r.scene = parameters_as<TextureFilterParameters>(parameters).mode != FilterMode::post;
    r.renders_again = r.scene;  // `render` renders its λ with the filtered textures; a set takes
                                // the samples again
    return r;
  }

  std::shared_ptr<const ChangePerLambda> change_per_lambda(
      const MethodParameters& parameters) const override {
    const auto& p = parameters_as<TextureFilterParameters>(parameters);
    if (p.mode != FilterMode::post) return std::make_shared<TexelDetailChange>();
    if (p.filter.kind != FilterKind::unsharp) return nullptr;
    return std::make_shared<LightnessTimes>(1.0);  // as usm2d: the detail carries the pixel's noise
  }

  std::shared_ptr<const SurfaceStage> surface_stage(
      const SurfaceContext& context, const MethodParameters& parameters) const override {
    const auto& p = parameters_as<TextureFilterParameters>(parameters);
    if (p.mode == FilterMode::post) return nullptr;
    check_scene(context.scene, p);
    return std::make_shared<FilteredTextureStage>(
        context.scene, filter_textures(context.scene, p, context.threads));
  }

  void check_scene(const Scene& scene, const MethodParameters& parameters) const override {
    const auto& p = parameters_as<TextureFilterParameters>(parameters);
    if (p.mode != FilterMode::post && scene_textures(scene).empty())
      throw InputError(name() + " in mode " + mode_name(p.mode) +
                       " filters textures, and no object of " + scene.file.string() +
                       " has one (mode post filters the image)");
  }

  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    const auto& p = parameters_as<TextureFilterParameters>(parameters);
    if (p.mode == FilterMode::post) return prepare_post(context, p);
    return prepare_textures(context, p);
  }

 private:
  static std::shared_ptr<const std::vector<FilteredPyramid>> filter_textures(
      const Scene& scene, const TextureFilterParameters& p, int threads) {
    const TextureMode mode = p.mode == FilterMode::mip ? TextureMode::mip : TextureMode::texture;
    auto pyramids = std::make_shared<std::vector<FilteredPyramid>>();
    for (const auto& t : scene_textures(scene))
      pyramids->push_back(
          filter_pyramid(t, mode, p.filter, p.level_strengths, pyramid_cache_folder(), threads));
    return pyramids;
  }

  nlohmann::json describe(const TextureFilterParameters& p) const {
    nlohmann::json out{{"mode", mode_name(p.mode)},
                       {"filter", filter_name(p.filter.kind)},
                       {"sigma", p.filter.sigma}};
    if (p.filter.kind == FilterKind::bilateral) out["sigma_r"] = p.filter.sigma_r;
    if (p.filter.kind == FilterKind::dog)
      out.update({{"tau", p.filter.tau}, {"phi", p.filter.phi}});
    if (!p.level_strengths.empty()) out["level_strengths"] = p.level_strengths;
    return out;
  }

  std::unique_ptr<PreparedEnhancement> prepare_post(const PrepareContext& context,
                                                    const TextureFilterParameters& p) const {
    const View& view = *context.view;
    const std::vector<float> detail =
        lightness_detail(view_signal_lightness(view), view.width(), view.height(), p.filter,
                         Borders::clamp, context.threads);
    LightnessChange change;
    change.amount.assign(detail.begin(), detail.end());
    auto prepared = std::make_unique<LightnessPrepared>(
        context.view, std::move(change), describe(p), std::vector<std::pair<std::string, Image>>{},
        context.threads, plain_noise(context));
    if (p.filter.kind == FilterKind::unsharp)  // the detail is S − G*S, so M = S − detail
      prepared->set_mask([view = context.view, detail] {
        const std::span<const float> S = view_signal_lightness(*view);
        std::vector<float> m(S.size());
        for (size_t i = 0; i < m.size(); ++i) m[i] = S[i] - detail[i];
        return m;
      });
    return prepared;
  }

  std::unique_ptr<PreparedEnhancement> prepare_textures(const PrepareContext& context,
                                                        const TextureFilterParameters& p) const {
    require_scene(context, name());
    check_scene(*context.view->scene, p);
    const auto textures = scene_textures(*context.view->scene);
    const auto* stage = dynamic_cast<const FilteredTextureStage*>(context.stage.get());
    auto pyramids =
        stage ? stage->pyramids() : filter_textures(*context.view->scene, p, context.threads);
    nlohmann::json parameters = describe(p);
    parameters["textures"] = textures.size();
    std::shared_ptr<const TexelWeights> weights;
    if (context.compose_from_samples) {
      std::vector<const Texture*> plain;
      for (const auto& t : textures) plain.push_back(t.get());
      const View& view = *context.view;
      weights = view.memo.get<TexelWeights>(
          "texel-weights", [&] { return TexelWeights::of_view(view, plain, context.threads); });
    }
    return std::make_unique<FilteredTextures>(context, std::move(pyramids), std::move(weights),
                                              std::move(parameters),
                                              p.filter.kind == FilterKind::unsharp);
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_texture_filter_method() {
  return std::make_unique<TextureFilterMethod>();
}

}  // namespace countershade
