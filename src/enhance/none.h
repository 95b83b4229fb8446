#pragma once
// The unenhanced stimulus: every λ gives the rendered image unchanged.

#include "enhance/method.h"

namespace countershade {

class NoEnhancement final : public EnhancementMethod {
 public:
  std::string name() const override { return "none"; }
  std::string summary() const override { return "the unenhanced rendering"; }
  void validate(const MethodOptions&) const override {}
  std::unique_ptr<PreparedEnhancement> prepare(const View& view, const MethodOptions&) const override;
};

}  // namespace countershade
