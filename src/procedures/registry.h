#pragma once
// The forced-choice procedures by name: the built-in ones (listed in registry.cpp) and any a
// program adds, as enhance/registry.h does for methods.

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "procedures/procedure.h"

namespace countershade::procedures {

// nullptr when no procedure has that name.
const ProcedureType* find_procedure(const std::string& name);
// The procedure of that name; InputError (naming `where`) listing the known ones when there is
// none.
const ProcedureType& procedure_named(const std::string& name, const std::string& where);
std::vector<std::string> procedure_names();

// Adds a procedure (a test's, a lab's own); its name must be new. The registration line of a
// procedure outside this library is one static ProcedureRegistration.
void register_procedure(std::unique_ptr<const ProcedureType> procedure);
struct ProcedureRegistration {
  explicit ProcedureRegistration(std::unique_ptr<const ProcedureType> procedure) {
    register_procedure(std::move(procedure));
  }
};

// A parsed procedure block: its type's name and its settings.
struct ProcedureBlock {
  std::string type;
  std::shared_ptr<const ProcedureSettings> settings;
};

// Reads a procedure block ({"type": …, its parameters}); `file` and `path` name it in messages.
ProcedureBlock read_procedure_block(const nlohmann::json& block, const std::string& file,
                                    const std::string& path);
// A procedure file of its own (`simulate --procedure`).
ProcedureBlock read_procedure_file(const std::filesystem::path& path);

}  // namespace countershade::procedures
