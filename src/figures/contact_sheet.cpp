#include "figures/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.h"
#include "core/number_format.h"
#include "core/text.h"
#include "stimuli/set_layout.h"

namespace countershade {
namespace {

// Box-filtered downscale by an integer factor, so thumbnails average instead of alias.
Image thumbnail(const Image& in, int width) {
  int factor = std::max(1, (in.width + width - 1) / width);
  Image out(in.width / factor, in.height / factor, 3);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 3; ++c) {
        float sum = 0;
        for (int dy = 0; dy < factor; ++dy)
          for (int dx = 0; dx < factor; ++dx)
            sum += in.at(x * factor + dx, y * factor + dy, std::min(c, in.channels - 1));
        out.at(x, y, c) = sum / float(factor * factor);
      }
  return out;
}

// Copies `thumb` into `sheet` with its top-left at (x0, y0), within a tw × th cell.
void place(Image& sheet, const Image& thumb, int x0, int y0, int tw, int th) {
  for (int y = 0; y < std::min(th, thumb.height); ++y)
    for (int x = 0; x < std::min(tw, thumb.width); ++x)
      for (int c = 0; c < 3; ++c) sheet.at(x0 + x, y0 + y, c) = thumb.at(x, y, c);
}

// The widest caption or column label, in pixels.
int widest_text(const std::vector<std::vector<ContactCell>>& cells,
                const std::vector<std::string>& column_labels) {
  int widest = 0;
  for (const auto& row : cells)
    for (const ContactCell& cell : row) widest = std::max(widest, text_width(cell.caption, 12));
  for (const auto& label : column_labels) widest = std::max(widest, text_width(label, 14));
  return widest;
}

}  // namespace

void write_contact_sheet(const std::filesystem::path& output, const std::string& title,
                         const std::vector<std::string>& row_labels,
                         const std::vector<std::string>& column_labels,
                         const std::vector<std::vector<ContactCell>>& cells, int thumbnail_width) {
  if (cells.empty() || cells[0].empty()) return;
  Image first = thumbnail(read_image(cells[0][0].file), thumbnail_width);
  int longest_row = 0;
  for (const auto& label : row_labels) longest_row = std::max(longest_row, text_width(label, 14));
  const int tw = first.width, th = first.height, gap = 8 + 16, top = 56;  // 16: the captions
  const int left =
      longest_row == 0 ? 10 : std::max(110, 24 + longest_row);  // no row labels: no column for them
  const int cols = int(column_labels.size()), rows = int(row_labels.size());
  const int pitch =
      gap + std::max(tw, widest_text(cells, column_labels));  // a caption never runs into the next
  const int width = std::max(left + cols * pitch, 20 + text_width(title, 18)),
            height = top + rows * (th + gap);
  Image sheet(width, height, 3, 0.5f);
  const float ink[3] = {1.0f, 1.0f, 1.0f};
  draw_text(sheet, 10, 24, title, 18, ink);
  for (int c = 0; c < cols; ++c)
    draw_text(sheet, left + c * pitch, top - 10, column_labels[size_t(c)], 14, ink);
  for (int r = 0; r < rows; ++r) {
    draw_text(sheet, 8, top + r * (th + gap) + th / 2, row_labels[size_t(r)], 14, ink);
    for (int c = 0; c < cols && size_t(c) < cells[size_t(r)].size();
         ++c) {  // a last row may be short
      const ContactCell& cell = cells[size_t(r)][size_t(c)];
      const int x0 = left + c * pitch, y0 = top + r * (th + gap);
      place(sheet, r == 0 && c == 0 ? first : thumbnail(read_image(cell.file), thumbnail_width), x0,
            y0, tw, th);
      if (!cell.caption.empty()) draw_text(sheet, x0, y0 + th + 14, cell.caption, 12, ink);
    }
  }
  write_image(output, sheet);
}

namespace {

// "noise 0.21 L*" from a manifest entry's noise estimate, and ", C 0.531" with its congruence
// score; "" without either.
std::string caption_of(const ManifestEntry& entry) {
  const auto noise = image_noise(entry);
  std::string caption = noise ? "noise " + format_value(round_to(noise->rms, 2)) + " L*" : "";
  if (entry.extra.contains("congruence"))
    caption += (caption.empty() ? "" : ", ") + std::string("C ") +
               format_value(round_to(entry.extra["congruence"].get<double>(), 3));
  return caption;
}

}  // namespace

namespace {

// `count` indices spread evenly over [0, n), the first and the last included.
std::vector<int> evenly_spaced(int n, int count) {
  count = std::min(count, n);
  std::vector<int> picks;
  for (int c = 0; c < count; ++c)
    picks.push_back(count == 1 ? 0 : int(std::lround(double(c) * (n - 1) / (count - 1))));
  return picks;
}

// The frames a sheet shows of a scene: four spread over a sequence; -1 for a still.
std::vector<int> sheet_frames(const ExperimentScene& scene) {
  if (!scene.frames) return {-1};
  std::vector<int> frames;
  for (int k : evenly_spaced(scene.frames->second - scene.frames->first + 1, 4))
    frames.push_back(scene.frames->first + k);
  return frames;
}

}  // namespace

void write_set_contact_sheets(const Experiment& e, const std::filesystem::path& dir,
                              const Manifest& manifest) {
  std::map<std::string, std::string> captions;  // file → caption
  for (const auto& s : manifest.stimuli) captions[s.file] = caption_of(s);
  const std::vector<int> picks = evenly_spaced(e.lambda.count(), e.contact_columns);
  std::filesystem::create_directories(dir / "contact-sheets");
  for (size_t s = 0; s < e.scenes.size(); ++s)
    for (size_t m = 0; m < e.methods.size(); ++m) {
      const std::vector<int> frames = sheet_frames(e.scenes[s]);
      const size_t sigmas = e.methods[m].sigmas.size();
      if (!e.methods[m].applies_to(e.scenes[s].name)) continue;
      if (picks.size() == 1 && sigmas == 1 && frames.size() == 1)
        continue;  // one image: nothing to compare
      std::vector<std::string> rows, cols;
      std::vector<std::vector<ContactCell>> cells;
      for (int p : picks) cols.push_back("λ = " + format_value(e.lambda.value(p)));
      for (size_t g = 0; g < sigmas; ++g)
        for (int f : frames) {
          const std::string sigma = "σ = " + format_value(e.methods[m].sigmas[g]);
          const std::string frame = "frame " + std::to_string(f);
          rows.push_back(f < 0 ? sigma : sigmas == 1 ? frame : sigma + ", " + frame);
          cells.emplace_back();
          for (int p : picks) {
            std::string rel = stimulus_path(e, {s, int(m), g, f}, p);
            const auto caption = captions.find(rel);
            if (caption == captions.end()) return;  // incomplete (a shard): no sheets
            cells.back().push_back({dir / rel, caption->second});
          }
        }
      write_contact_sheet(
          dir / "contact-sheets" / (e.scenes[s].name + "-" + e.methods[m].label + ".png"),
          e.scenes[s].name + " - " + e.methods[m].label, rows, cols, cells);
    }
}

}  // namespace countershade
