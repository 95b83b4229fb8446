// Local light alignment (Mestres et al. 2021): per shading point, the light direction is rotated
// from the coarsest scale of the normal field to the finest, so that every feature gets a lit and
// an unlit side (enhance/light_alignment.h). Diffuse shading is guided by the multi-scale normals,
// specular shading by the reflected view vectors. Where a point faces the original light its
// visibility is that light's; on the light's dark side the point is lit by max(0, n_1·l_1) where
// the aligned direction l_1 is open (docs/methods.md, "Shape depiction"). The normals come in
// `surface` or `image` mode (enhance/normal_field.h).
// λ scales the per-scale strengths: s_i = clamp(λ·profile_i, 0, 1).

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "core/error.h"
#include "enhance/light_alignment.h"
#include "enhance/method.h"
#include "enhance/multiscale_normals.h"
#include "enhance/shading_method.h"
#include "render/shading.h"

namespace countershade {
namespace {

struct LlaParameters final : MethodParameters {
  NormalScales normals;         // σ_1 and S
  double gamma = 3;             // W_γ
  double terminator_fade = 0;   // ShadingHook::terminator_band
  std::vector<double> profile;  // ŝ_1 … ŝ_{S−1}
};

// Shades every light sample with the light aligned per point: the diffuse term towards the
// multi-scale normals, the specular term towards the reflected view vectors.
class AlignmentHook final : public ShadingHook {
 public:
  AlignmentHook(std::shared_ptr<const NormalScaleField> normals, std::vector<double> strengths,
                double gamma, double band)
      : normals_(std::move(normals)),
        strengths_(std::move(strengths)),
        weight_(gamma),
        band_(band) {}

  // The diffuse term's direction, l_1: on the dark side a point is lit where l_1 is open.
  bool shades_dark_side() const override { return true; }
  std::optional<glm::dvec3> dark_side_direction(const ShadingInputs& s,
                                                const glm::dvec3& wi) const override {
    glm::dvec3 n[kMaxNormalScales];
    normals_->at_shading_point(s, n);
    return align_light(wi, {n, size_t(normals_->scales())}, strengths_, weight_);
  }
  double terminator_band() const override { return band_; }

  // The same directions, aligned in blocks of vector lanes.
  void dark_side_directions(std::span<const HookSample> samples,
                            std::optional<glm::dvec3>* out) const override {
    thread_local AlignmentBlock block;
    for (size_t first = 0; first < samples.size(); first += kAlignmentBlock) {
      const auto part = samples.subspan(first, std::min(kAlignmentBlock, samples.size() - first));
      align_diffuse(part, block);
      for (size_t j = 0; j < part.size(); ++j) out[first + j] = aligned(block, j);
    }
  }

  glm::dvec3 reflect(const ShadingInputs& s, const glm::dvec3& wi,
                     const glm::dvec3& incident) const override {
    glm::dvec3 n[kMaxNormalScales], r[kMaxNormalScales];
    const size_t scales = size_t(normals_->scales());
    normals_->at_shading_point(s, n);
    const glm::dvec3 diffuse =
        reflect_diffuse(s, align_light(wi, {n, scales}, strengths_, weight_), incident);
    // A material without a specular lobe reflects none at any direction: skip its alignment
    // (adding the zero keeps the sum's bits those of the full expression).
    if (s.material.specular == SpecularModel::none) return diffuse + glm::dvec3(0.0);
    for (size_t k = 0; k < scales; ++k) r[k] = reflected(n[k], s.wo);
    return diffuse +
           reflect_specular(s, align_light(wi, {r, scales}, strengths_, weight_), incident);
  }

  // The same, a block of light samples aligned at once in vector lanes (align_light_block).
  void reflect_many(std::span<const HookSample> samples, glm::dvec3* out) const override {
    thread_local AlignmentBlock block;
    for (size_t first = 0; first < samples.size(); first += kAlignmentBlock)
      reflect_block(samples.subspan(first, std::min(kAlignmentBlock, samples.size() - first)),
                    block, out + first);
  }

 private:
  static glm::dvec3 reflected(const glm::dvec3& n, const glm::dvec3& wo) {
    return 2 * glm::dot(n, wo) * n - wo;
  }
  static glm::dvec3 aligned(const AlignmentBlock& block, size_t j) {
    return {block.aligned[0][j], block.aligned[1][j], block.aligned[2][j]};
  }

  // The samples' lights aligned to their normals (block.aligned), the normals left in
  // block.vectors; whether any sample's material has a specular lobe.
  bool align_diffuse(std::span<const HookSample> samples, AlignmentBlock& block) const {
    const size_t scales = size_t(normals_->scales());
    bool specular = false;
    for (size_t j = 0; j < samples.size(); ++j) {
      glm::dvec3 n[kMaxNormalScales];
      normals_->at_shading_point(*samples[j].inputs, n);
      for (int c = 0; c < 3; ++c) {
        block.light[c][j] = samples[j].wi[c];
        for (size_t k = 0; k < scales; ++k) block.vectors[k][c][j] = n[k][c];
      }
      specular |= samples[j].inputs->material.specular != SpecularModel::none;
    }
    align_light_block(block, samples.size(), scales, strengths_, weight_.damping());
    return specular;
  }

  // Diffuse: the light aligned to the normals; then, if any sample's material has a specular
  // lobe, specular: the light aligned to the reflected view vectors, as reflect() does per sample.
  void reflect_block(std::span<const HookSample> samples, AlignmentBlock& block,
                     glm::dvec3* out) const {
    const size_t scales = size_t(normals_->scales());
    const bool specular = align_diffuse(samples, block);
    for (size_t j = 0; j < samples.size(); ++j)
      out[j] = reflect_diffuse(*samples[j].inputs, aligned(block, j), samples[j].incident);
    if (!specular) {
      for (size_t j = 0; j < samples.size(); ++j) out[j] += glm::dvec3(0.0);
      return;
    }
    for (size_t j = 0; j < samples.size(); ++j)
      for (size_t k = 0; k < scales; ++k) {
        const glm::dvec3 r =
            reflected({block.vectors[k][0][j], block.vectors[k][1][j], block.vectors[k][2][j]},
                      samples[j].inputs->wo);
        for (int c = 0; c < 3; ++c) block.vectors[k][c][j] = r[c];
      }
    align_light_block(block, samples.size(), scales, strengths_, weight_.damping());
    for (size_t j = 0; j < samples.size(); ++j) {
      const ShadingInputs& s = *samples[j].inputs;
      out[j] += s.material.specular == SpecularModel::none
                    ? glm::dvec3(0.0)
                    : reflect_specular(s, aligned(block, j), samples[j].incident);
    }
  }

  std::shared_ptr<const NormalScaleField> normals_;
  std::vector<double> strengths_;
  AlignmentWeight weight_;
  double band_;
};

class LlaMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "lla"; }
  std::string summary() const override {
    return "local light alignment: the light turned per point to reveal shape (shading)";
  }
  MethodAxes axes() const override {
    return {"per-scale strength s_i = clamp(λ·profile_i, 0, 1)", {normal_scales_axis()}};
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    std::vector<ParameterDoc> docs = normal_scales_docs();
    docs.push_back(
        {"gamma", "3", "γ of the weight W_γ: larger values sharpen the lit/unlit transitions"});
    docs.push_back({"profile", "all 1", "S − 1 strengths in [0, 1], finest first, scaled by λ"});
    docs.push_back(terminator_fade_doc());
    return docs;
  }

  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<LlaParameters>();
    std::optional<double> sigma;
    p->normals = read_normal_scales(bag, sigma);
    const int scales = p->normals.scales;
    p->gamma = bag.number_in("gamma", 3.0, 0.0, 50.0);
    p->profile = bag.numbers("profile", std::vector<double>(size_t(scales - 1), 1.0));
    p->terminator_fade = read_terminator_fade(bag);
    bag.finish(name());
    check_normal_scales(bag, p->normals, sigma);
    if (p->profile.size() != size_t(scales - 1))
      bag.fail("profile",
               "needs " + std::to_string(scales - 1) + " values (one per rotation, finest first)");
    for (double s : p->profile)
      if (!(s >= 0 && s <= 1)) bag.fail("profile", "values must be in [0, 1]");
    return p;
  }

  RenderRequest request(const MethodParameters&) const override { return shading_request(); }

  // Every λ is a render with the aligned light; with all strengths 0 it is the view itself.
  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    const auto& p = parameters_as<LlaParameters>(parameters);
    auto normals = scene_normals(context, p.normals, name());
    auto hook_for = [p, normals](double lambda) -> std::shared_ptr<const ShadingHook> {
      std::vector<double> strengths;
      for (double s : p.profile) strengths.push_back(std::clamp(lambda * s, 0.0, 1.0));
      if (std::all_of(strengths.begin(), strengths.end(), [](double s) { return s <= 0; }))
        return nullptr;
      return std::make_shared<AlignmentHook>(normals, std::move(strengths), p.gamma,
                                             p.terminator_fade);
    };
    nlohmann::json recorded = describe_normals(p.normals, *normals);
    recorded["gamma"] = p.gamma;
    recorded["profile"] = p.profile;
    recorded["terminator_fade"] = p.terminator_fade;
    return std::make_unique<HookedRender>(context, hook_for, recorded);
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_lla_method() { return std::make_unique<LlaMethod>(); }

}  // namespace countershade
