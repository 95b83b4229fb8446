// A method that only a test knows: every λ gives the view unchanged. It is added to the program
// by this one file and its one registration line below, and nothing else (see
// method_extension_test.cpp, which runs it through render, stimuli and adjust).

#include <memory>

#include "core/error.h"
#include "enhance/registry.h"

namespace countershade {
namespace {

struct IdentityParameters final : MethodParameters {
  double width = 1;
};

class Unchanged final : public PreparedEnhancement {
 public:
  explicit Unchanged(std::shared_ptr<const View> view) : view_(std::move(view)) {}
  Composed compose(double) const override { return {view_->display, 0}; }

 private:
  std::shared_ptr<const View> view_;
};

class IdentityMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "identity"; }
  std::string summary() const override { return "a test method: the view unchanged at every λ"; }
  MethodAxes axes() const override {
    return {"none", {{"width", "arbitrary units", "recorded, unused"}}};
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {{"width", "1", "recorded, unused"}};
  }
  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<IdentityParameters>();
    p->width = bag.number("width", 1.0);
    bag.finish(name());
    if (!(p->width > 0)) bag.fail("width", "must be positive");
    return p;
  }
  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters&) const override {
    return std::make_unique<Unchanged>(context.view);
  }
};

}  // namespace

static const MethodRegistration identity_registration{std::make_unique<IdentityMethod>()};

}  // namespace countershade
