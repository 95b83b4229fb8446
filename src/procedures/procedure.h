#pragma once
// A forced-choice procedure as a plug-in (docs/forced-choice.md, "Procedures"), in the way an
// enhancement method is one: one file, one registration line, its parameters read through a
// ParameterBag. A procedure picks the λ a condition shows next and learns from each answer; like
// PsychoPy's StairHandler it knows no window, no file and no clock. The study runs one per
// condition, interleaved in a seeded order, and records what it shows.
//
// Three parts:
//   ProcedureType      the plug-in: its name (the block's "type"), its documentation, its parser;
//   ProcedureSettings  one block's values, checked: makes a condition's procedure, replays answers;
//   Procedure          one condition's running state.

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/parameters.h"

namespace countershade::procedures {

// The λ > 0 a set shows, with their grid indices, increasing.
struct Grid {
  std::vector<double> lambdas;
  std::vector<int> indices;
  // The grid point nearest λ (linear distance; the lower one on a tie).
  size_t nearest(double lambda) const;
  // The grid point of a listed λ; one off the grid is an InputError naming `where`.
  size_t point_of(double lambda, const std::string& where) const;
};

struct Intensity {
  double requested = 0;  // what the procedure asked for
  size_t grid = 0;       // the grid point shown
};

// One condition's procedure, in λ on the set's grid.
class Procedure {
 public:
  virtual ~Procedure() = default;
  // What to show next. Called only while !finished(); it waits for a choice made in the background.
  virtual Intensity next() const = 0;
  // Whether next() answers at once. A procedure that chooses in the background after each answer
  // (QUEST+ on a large grid) is not ready while it computes, so that the study can keep drawing
  // frames and show the trial when it is.
  virtual bool ready() const { return true; }
  // The answer to a trial shown at `shown` (which may differ from what next() asked for).
  virtual void record(const Intensity& shown, bool correct) = 0;
  // Whether the procedure's own rule ends the condition (the study's max_trials ends it too).
  virtual bool finished() const = 0;
  // The state after the last answer, for the session's record.
  virtual nlohmann::ordered_json state() const = 0;
};

// A procedure run on answers alone, with no stimuli and no grid (`countershade simulate
// --procedure`): one CSV row per trial, and a summary of the final state.
struct Replay {
  std::string csv;
  nlohmann::ordered_json summary;  // trials run, the final estimate, responses left over
};

class ProcedureSettings {
 public:
  virtual ~ProcedureSettings() = default;
  // A condition's procedure on its grid, seeded with the condition's own seed. Throws InputError
  // (naming `where`, the block) when the procedure cannot work on this grid.
  virtual std::unique_ptr<Procedure> start(const Grid& grid, uint64_t seed,
                                           const std::string& where) const = 0;
  // Adds what the session's record keeps beyond the block as written (e.g. a default the
  // procedure filled in).
  virtual void describe(nlohmann::ordered_json& record) const { (void)record; }
  // Runs the procedure on the answers, in its own units, until it finishes or they run out.
  // Throws InputError (naming `where`) for a procedure that needs a grid to run.
  virtual Replay replay(const std::vector<bool>& responses, const std::string& where) const = 0;
  // The procedure's own estimate from a condition's answered trials (λ shown, correct), for
  // `analyze`: a posterior's summary. None for a procedure that keeps no posterior to report;
  // InputError (naming the block's key) when it cannot be computed here, e.g. for lack of memory.
  virtual std::optional<nlohmann::ordered_json> estimate(
      const std::vector<std::pair<double, bool>>& trials) const {
    (void)trials;
    return std::nullopt;
  }
  // The memory a procedure started on `grid` would hold, in parts (none for a procedure whose
  // state is small). A session starts every condition's procedure at once, so it adds these up
  // before starting any (forced_choice::procedure_memory_problem).
  struct MemoryPart {
    std::string shared;  // not empty: procedures whose parts have this key share one copy
    double bytes = 0;
  };
  virtual std::vector<MemoryPart> memory(const Grid& grid) const {
    (void)grid;
    return {};
  }
};

// The WebAssembly engine's largest memory: its -sMAXIMUM_MEMORY (src/web_engine/CMakeLists.txt).
inline constexpr double kWebAssemblyMemoryBytes = 2.0 * 1024 * 1024 * 1024;
// The memory the procedures of one session may take: half of what this machine has, or half of
// the WebAssembly engine's in the browser, so that the rest of the program and the page keep room.
double procedure_memory_limit();

// Where an experiment gives a procedure: per condition, as a forced_choice block's "procedure"
// ({"type": NAME, …}), or as the whole adjust block (one plan of trials for the study).
enum class Study { forced_choice, adjustment };

class ProcedureType {
 public:
  virtual ~ProcedureType() = default;
  virtual std::string name() const = 0;  // the block's "type"
  virtual std::string summary() const = 0;
  virtual Study study() const { return Study::forced_choice; }
  virtual std::vector<ParameterDoc> parameter_docs() const = 0;
  // The one parser: reads every key of the block but "type", checks the values together, and
  // ends with bag.finish(name()), so that an unknown key is an InputError naming it.
  virtual std::shared_ptr<const ProcedureSettings> parse(const ParameterBag& bag) const = 0;
};

// The shortest text that reads back as exactly `v` (replay CSVs).
std::string exact_number(double v);

}  // namespace countershade::procedures
