#include "enhance/none.h"

namespace countershade {
namespace {

class Identity final : public PreparedEnhancement {
 public:
  explicit Identity(const View& view) : view_(view) {}
  Composed compose(double) const override { return {view_.display, 0}; }

 private:
  const View& view_;
};

}  // namespace

std::unique_ptr<PreparedEnhancement> NoEnhancement::prepare(const View& view, const MethodOptions&) const {
  return std::make_unique<Identity>(view);
}

}  // namespace countershade
