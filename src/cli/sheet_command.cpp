// `countershade sheet`: any images side by side with captions, in rows of a chosen length (the
// README's picture; comparisons a set's own contact sheets do not make).

#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "figures/contact_sheet.h"

namespace countershade::cli {
namespace {

struct SheetArgs {
  std::vector<std::string> images;  // FILE or FILE=CAPTION
  std::string output, title;
  int columns = 3, width = 320;
};

ContactCell cell_of(const std::string& word) {
  const size_t eq = word.find('=');
  ContactCell cell{word.substr(0, eq), eq == std::string::npos ? "" : word.substr(eq + 1)};
  std::error_code ec;
  if (!std::filesystem::is_regular_file(cell.file, ec))
    throw_input_error(cell.file.string(), "no such image");
  return cell;
}

void run(const SheetArgs& args) {
  check_output_file(args.output, {".png"}, "a PNG file");
  std::vector<std::vector<ContactCell>> rows;
  for (size_t k = 0; k < args.images.size(); ++k) {
    if (k % size_t(args.columns) == 0) rows.emplace_back();
    rows.back().push_back(cell_of(args.images[k]));
  }
  const size_t columns = rows.front().size();
  write_contact_sheet(args.output, args.title, std::vector<std::string>(rows.size()),
                      std::vector<std::string>(columns), rows, args.width);
  std::fprintf(stderr, "sheet: wrote %s (%zu images)\n", args.output.c_str(), args.images.size());
}

}  // namespace

void add_sheet_command(CLI::App& app) {
  auto args = std::make_shared<SheetArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sheet", "Put images side by side with captions, in rows (a comparison figure).");
  cmd->add_option("images", args->images, "Images as FILE or FILE=CAPTION, row by row")->required();
  cmd->add_option("-o,--output", args->output, "The sheet (PNG)")->required();
  cmd->add_option("--title", args->title, "A title above the images");
  cmd->add_option("--columns", args->columns, "Images per row")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--width", args->width,
                  "Thumbnail width in pixels (images are shrunk by a whole factor to fit)")
      ->check(CLI::Range(16, 4096))
      ->capture_default_str();
  cmd->callback([args] { run(*args); });
  cmd->footer(
      "\nExample:\n  countershade sheet plain.png=plain \"usm3d.png=usm3d, σ = 0.12, λ = 1\" -o "
      "compare.png --columns 2");
}

}  // namespace countershade::cli
