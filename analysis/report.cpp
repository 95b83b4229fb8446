#include "analysis/report.h"

#include <fstream>

#include "core/atomic_file.h"

namespace countershade::analysis {
namespace {

void write_text(const std::filesystem::path& path, const std::string& text) {
  write_atomically(path, [&](const std::filesystem::path& temp) {
    std::ofstream out(temp, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error(path.string() + ": cannot write");
  });
}

}  // namespace

void write_outputs(const std::vector<BlockResults>& results, const std::filesystem::path& dir, bool figures) {
  (void)figures;
  nlohmann::json json;
  if (results.size() == 1) {
    json = results[0].json;
  } else {
    json["methods"] = nlohmann::json::array();
    for (const auto& b : results) json["methods"].push_back(b.json);
  }
  write_text(dir / "results.json", json.dump(2) + "\n");
}

}  // namespace countershade::analysis
