#include "procedures/registry.h"

#include "core/error.h"
#include "core/json_reader.h"
#include "core/named_registry.h"

namespace countershade::procedures {

// The built-in procedures, one line each. Every procedure file defines its factory.
#define COUNTERSHADE_BUILTIN_PROCEDURES(X) \
  X(adjustment)                            \
  X(constant)                              \
  X(staircase)                             \
  X(quest)                                 \
  X(questplus)

#define COUNTERSHADE_DECLARE_PROCEDURE(id) \
  std::unique_ptr<const ProcedureType> make_##id##_procedure();
COUNTERSHADE_BUILTIN_PROCEDURES(COUNTERSHADE_DECLARE_PROCEDURE)

namespace {

NamedRegistry<ProcedureType>& registry() {
  // Never destroyed: registrations may run during static destruction.
  static auto* r = [] {
    std::vector<std::unique_ptr<const ProcedureType>> builtins;
#define COUNTERSHADE_ADD_PROCEDURE(id) builtins.push_back(make_##id##_procedure());
    COUNTERSHADE_BUILTIN_PROCEDURES(COUNTERSHADE_ADD_PROCEDURE)
    return new NamedRegistry<ProcedureType>(std::move(builtins));
  }();
  return *r;
}

}  // namespace

void register_procedure(std::unique_ptr<const ProcedureType> procedure) {
  registry().add(std::move(procedure), "procedure");
}

const ProcedureType* find_procedure(const std::string& name) { return registry().find(name); }

std::vector<std::string> procedure_names() { return registry().names(); }

const ProcedureType& procedure_named(const std::string& name, const std::string& where) {
  if (const ProcedureType* p = find_procedure(name)) return *p;
  std::string list;
  for (const auto& n : procedure_names()) list += (list.empty() ? "" : ", ") + n;
  throw_input_error(where, "unknown value '" + name + "' (expected one of: " + list + ")");
}

ProcedureBlock read_procedure_block(const nlohmann::json& block, const std::string& file,
                                    const std::string& path) {
  const JsonObject object(block, file, path);
  const std::string type = object.string("type");  // required: an absent type is named as such
  const ProcedureType& procedure = procedure_named(type, file + ": " + object.key_path("type"));
  if (procedure.study() != Study::forced_choice)
    throw_input_error(
        file + ": " + object.key_path("type"),
        "'" + type + "' is given as the experiment's adjust block, not as a procedure");
  return {type, procedure.parse(ParameterBag::from_json(block, file, path, {"type"}))};
}

ProcedureBlock read_procedure_file(const std::filesystem::path& path) {
  const nlohmann::json root = parse_json_file(path);
  if (!root.is_object()) throw_input_error(path.string(), "expected a JSON object");
  return read_procedure_block(root, path.string(), "");
}

}  // namespace countershade::procedures
