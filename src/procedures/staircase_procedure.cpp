// The up/down staircase as a procedure: it steps in λ by StairHandler's rules (staircase.h), the
// study shows the grid's nearest λ, and the staircase steps on from the λ shown.

#include <cmath>

#include "formats/responses.h"
#include "procedures/procedure.h"
#include "procedures/staircase.h"

namespace countershade::procedures {
namespace {

using json = nlohmann::ordered_json;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

class StaircaseProcedure final : public Procedure {
 public:
  StaircaseProcedure(const StaircaseRules& rules, const Grid& grid)
      : staircase_(rules), grid_(grid) {}
  Intensity next() const override {
    const double requested = staircase_.next_intensity();
    return {requested, grid_.nearest(requested)};
  }
  void record(const Intensity& shown, bool correct) override {
    staircase_.add_response(correct, grid_.lambdas[shown.grid]);
  }
  bool finished() const override { return staircase_.finished(); }
  json state() const override {
    json j = {{"reversals", staircase_.reversal_intensities().size()},
              {"next_intensity", staircase_.next_intensity()}};
    if (!staircase_.reversal_intensities().empty()) j["estimate"] = staircase_.estimate();
    return j;
  }

 private:
  Staircase staircase_;
  const Grid& grid_;
};

class StaircaseSettings final : public ProcedureSettings {
 public:
  explicit StaircaseSettings(StaircaseRules rules) : rules_(std::move(rules)) {}

  std::unique_ptr<Procedure> start(const Grid& grid, uint64_t, const std::string&) const override {
    return std::make_unique<StaircaseProcedure>(rules_, grid);
  }

  Replay replay(const std::vector<bool>& responses, const std::string&) const override {
    Replay out;
    out.csv = csv_line({"trial", "intensity", "response", "reversal"});
    Staircase stair(rules_);
    size_t used = 0;
    while (!stair.finished() && used < responses.size()) {
      const double shown = stair.next_intensity();
      const bool reversal = stair.add_response(responses[used++]);
      out.csv += csv_line({std::to_string(used), exact_number(shown),
                           responses[used - 1] ? "1" : "0", reversal ? "1" : "0"});
    }
    out.summary = {{"type", "staircase"},
                   {"trials", used},
                   {"finished", stair.finished()},
                   {"reversals", stair.reversal_intensities().size()},
                   {"final_estimate", number_or_null(stair.estimate())},
                   {"final_estimate_geometric", number_or_null(stair.geometric_estimate())},
                   {"next_intensity", stair.next_intensity()},
                   {"responses_left", responses.size() - used}};
    return out;
  }

 private:
  StaircaseRules rules_;
};

class StaircaseType final : public ProcedureType {
 public:
  std::string name() const override { return "staircase"; }
  std::string summary() const override {
    return "An up/down staircase with PsychoPy StairHandler's rules, stepping in λ";
  }
  std::vector<ParameterDoc> parameter_docs() const override { return staircase_parameter_docs(); }
  std::shared_ptr<const ProcedureSettings> parse(const ParameterBag& bag) const override {
    StaircaseRules rules = read_staircase_rules(bag);
    bag.finish(name());
    return std::make_shared<StaircaseSettings>(std::move(rules));
  }
};

}  // namespace

std::unique_ptr<const ProcedureType> make_staircase_procedure() {
  return std::make_unique<StaircaseType>();
}

}  // namespace countershade::procedures
