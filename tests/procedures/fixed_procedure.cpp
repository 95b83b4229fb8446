// A test-only procedure, added the way a lab would add its own: this one file and its
// registration line, nothing else. It shows one λ (on the set's grid) a given number of times and
// counts the right answers. The ProcedureExtension tests run it through a build of the program
// that includes this file (countershade_fixed_procedure).

#include "core/error.h"
#include "formats/responses.h"
#include "procedures/registry.h"

namespace countershade::procedures {
namespace {

class FixedProcedure final : public Procedure {
 public:
  FixedProcedure(size_t point, double lambda, int trials)
      : point_(point), lambda_(lambda), trials_(trials) {}
  Intensity next() const override { return {lambda_, point_}; }
  void record(const Intensity&, bool correct) override {
    ++shown_;
    correct_ += correct;
  }
  bool finished() const override { return shown_ >= trials_; }
  nlohmann::ordered_json state() const override {
    return {{"shown", shown_}, {"correct", correct_}};
  }

 private:
  size_t point_;
  double lambda_;
  int trials_, shown_ = 0, correct_ = 0;
};

class FixedSettings final : public ProcedureSettings {
 public:
  FixedSettings(double lambda, int trials) : lambda_(lambda), trials_(trials) {}
  std::unique_ptr<Procedure> start(const Grid& grid, uint64_t,
                                   const std::string& where) const override {
    return std::make_unique<FixedProcedure>(grid.point_of(lambda_, where + ".lambda"), lambda_,
                                            trials_);
  }
  Replay replay(const std::vector<bool>& responses, const std::string&) const override {
    Replay out{csv_line({"trial", "intensity", "response"}), {}};
    size_t used = 0;
    for (; used < responses.size() && int(used) < trials_; ++used)
      out.csv +=
          csv_line({std::to_string(used + 1), exact_number(lambda_), responses[used] ? "1" : "0"});
    out.summary = {
        {"type", "fixed"}, {"trials", used}, {"responses_left", responses.size() - used}};
    return out;
  }

 private:
  double lambda_;
  int trials_;
};

class FixedType final : public ProcedureType {
 public:
  std::string name() const override { return "fixed"; }
  std::string summary() const override { return "One λ, a given number of times (a test's)"; }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {{"lambda", "", "The λ shown, required"}, {"trials", "5", "Trials per condition"}};
  }
  std::shared_ptr<const ProcedureSettings> parse(const ParameterBag& bag) const override {
    const double lambda = bag.required_number("lambda");
    const int trials = int(bag.integer_in("trials", 5, 1, 1000));
    bag.finish(name());
    return std::make_shared<FixedSettings>(lambda, trials);
  }
};

static const ProcedureRegistration fixed_registration{std::make_unique<FixedType>()};

}  // namespace
}  // namespace countershade::procedures
