// Constant stimuli: each listed λ (which must be on the set's grid) shown a number of times, in an
// order shuffled from the condition's own seed.

#include <algorithm>

#include "core/error.h"
#include "core/random.h"
#include "procedures/procedure.h"

namespace countershade::procedures {
namespace {

class ConstantStimuli final : public Procedure {
 public:
  ConstantStimuli(const Grid& grid, std::vector<size_t> order)
      : grid_(grid), order_(std::move(order)) {}
  Intensity next() const override {
    const size_t point = order_[shown_];
    return {grid_.lambdas[point], point};
  }
  void record(const Intensity&, bool) override { ++shown_; }
  bool finished() const override { return shown_ >= order_.size(); }
  nlohmann::ordered_json state() const override { return nlohmann::ordered_json::object(); }

 private:
  const Grid& grid_;
  std::vector<size_t> order_;  // grid points in the order shown
  size_t shown_ = 0;
};

class ConstantSettings final : public ProcedureSettings {
 public:
  ConstantSettings(std::vector<double> lambdas, int repetitions)
      : lambdas_(std::move(lambdas)), repetitions_(repetitions) {}

  std::unique_ptr<Procedure> start(const Grid& grid, uint64_t seed,
                                   const std::string& where) const override {
    std::vector<size_t> order;
    for (double lambda : lambdas_) {
      const size_t point = grid.point_of(lambda, where + ".lambdas");
      for (int r = 0; r < repetitions_; ++r) order.push_back(point);
    }
    SampleStream random(seed, 211, 0, 0);  // Fisher–Yates from the condition's own stream
    for (size_t i = order.size(); i > 1; --i)
      std::swap(order[i - 1], order[std::min(size_t(random.next() * double(i)), i - 1)]);
    return std::make_unique<ConstantStimuli>(grid, std::move(order));
  }

  Replay replay(const std::vector<bool>&, const std::string& where) const override {
    throw_input_error(where, "constant stimuli show the set's λ grid; there is nothing to replay");
  }

 private:
  std::vector<double> lambdas_;
  int repetitions_;
};

class ConstantType final : public ProcedureType {
 public:
  std::string name() const override { return "constant"; }
  std::string summary() const override {
    return "Constant stimuli: every listed λ a fixed number of times, in a seeded order";
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {{"lambdas", "", "The λ shown, each on the set's grid and above 0, required"},
            {"repetitions", "20", "Trials per λ"}};
  }
  std::shared_ptr<const ProcedureSettings> parse(const ParameterBag& bag) const override {
    const std::vector<double> lambdas = bag.required_numbers("lambdas");
    if (lambdas.empty()) bag.fail("lambdas", "must list at least one λ");
    for (double l : lambdas)
      if (!(l > 0)) bag.fail("lambdas", "every λ must be above 0");
    const int repetitions = int(bag.integer_in("repetitions", 20, 1, 10000));
    bag.finish(name());
    return std::make_shared<ConstantSettings>(lambdas, repetitions);
  }
};

}  // namespace

std::unique_ptr<const ProcedureType> make_constant_procedure() {
  return std::make_unique<ConstantType>();
}

}  // namespace countershade::procedures
