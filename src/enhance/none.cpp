// The unenhanced stimulus: every λ gives the rendered image unchanged (a scene's reference).

#include "enhance/method.h"

namespace countershade {
namespace {

struct NoParameters final : MethodParameters {};

class Identity final : public PreparedEnhancement {
 public:
  explicit Identity(std::shared_ptr<const View> view) : view_(std::move(view)) {}
  Composed compose(double) const override { return {view_->display, 0}; }

 private:
  std::shared_ptr<const View> view_;
};

class NoEnhancement final : public EnhancementMethod {
 public:
  std::string name() const override { return "none"; }
  std::string summary() const override { return "the unenhanced rendering"; }
  MethodAxes axes() const override { return {"none (every λ gives the same image)", {}}; }
  std::vector<ParameterDoc> parameter_docs() const override { return {}; }
  bool enhances() const override { return false; }
  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    bag.finish(name());
    return std::make_shared<NoParameters>();
  }
  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters&) const override {
    return std::make_unique<Identity>(context.view);
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_none_method() {
  return std::make_unique<NoEnhancement>();
}

}  // namespace countershade
