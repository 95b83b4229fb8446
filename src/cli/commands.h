#pragma once
// One registration function per subcommand; main.cpp calls them all.

#include <CLI/CLI.hpp>

namespace countershade::cli {

void add_render_command(CLI::App& app);
void add_mesh_usm_command(CLI::App& app);
void add_image_usm_command(CLI::App& app);
void add_analyze_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_stimuli_command(CLI::App& app);
void add_adjust_command(CLI::App& app);
void add_methods_command(CLI::App& app);

}  // namespace countershade::cli
