#pragma once
// The adjustment app's window: GLFW, OpenGL 3.3 core and Dear ImGui. It shows two stimuli at
// exactly 1:1 pixel scale (nearest-neighbour textures at integer positions, RGBA8 textures into
// a non-sRGB framebuffer, so no filtering, resampling or gamma change) on a uniform grey surround,
// with the question text above and the progress below. It knows nothing about the procedure.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "runtime/fine_levels.h"
#include "runtime/key_script.h"
#include "runtime/study.h"

struct GLFWwindow;
struct GLFWmonitor;

namespace countershade::runtime {

class DeepStimulusRenderer;

struct DisplayOptions {
  bool fullscreen = false;
  int monitor = 0;
  int stimulus_width = 0, stimulus_height = 0;  // the largest stimulus of the study
  int columns = 2;  // stimuli side by side (3 or 4 for a spatial forced choice among as many)
  int gap_px = 48;
  int surround = 128;
  double font_px = 22;
  std::string title = "countershade adjust";
  // The session's clock counts frames: each frame is exactly one refresh period after the last,
  // and pace() does not wait. For scripted runs (tests, recordings), whose logic then does not
  // depend on how busy the machine is.
  bool frame_clock = false;
  // The set's pixels per degree at its viewing distance: the monitor must give the same within 2 %.
  // Its width in mm comes from GLFW (the monitor's EDID) unless `monitor_width_mm` is given.
  std::optional<double> pixels_per_degree, distance_mm, monitor_width_mm;
  // 16-bit stimuli reach the screen through a 10-bit framebuffer (used only after a read-back
  // confirms it) or a seeded dither to 8 bits (runtime/fine_levels.h).
  int stimulus_bits = 8;
  OutputPathChoice output_path;
  uint32_t dither_seed = 0;
};

// The display a study needs: its largest stimulus, its surround, gap and font, and the set's
// pixels per degree; the window's title names `app` and the set.
DisplayOptions study_display(const Study& study, const std::string& app);

// A key or window event from GLFW, with its time on glfwGetTime()'s clock.
struct WindowEvent {
  enum class Kind { press, release, focus_lost, focus_gained, close };
  Kind kind = Kind::press;
  Key key = Key::enter;
  double time_s = 0;
};

// What one frame shows.
struct FrameContent {
  unsigned left_texture = 0, right_texture = 0;  // 0: no images
  bool centred = false;  // one image (left_texture) in the middle, as a temporal interval shows it
  std::vector<unsigned> row;  // several images side by side, left to right (instead of left/right)
  int image_width = 0, image_height = 0;
  std::string header;    // top line, e.g. "Trial 3 of 24"
  std::string question;  // the question text above the images
  std::string hint;      // the key reminder below the images
  std::string message;   // a centred text block over the surround (instructions, pause, end)
  double progress = -1;  // a progress bar (0..1) under the message; < 0 for none
};

// Where the stimuli of the last frame were drawn, in framebuffer pixels from the top-left.
struct StimulusLayout {
  int left_x = 0, right_x = 0, y = 0, width = 0, height = 0;
  std::vector<int> xs;  // every image's left edge, left to right
  bool fits = true;
};

class Presenter {
 public:
  // The minimum framebuffer size that shows two stimuli of this size at 1:1 with the texts.
  static void required_size(const DisplayOptions& options, int* width, int* height);

  // Opens the window. Throws InputError when the screen cannot show both stimuli at 1:1 (saying
  // why), std::runtime_error when there is no display or no OpenGL 3.3.
  explicit Presenter(const DisplayOptions& options);
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // GL renderer and version, screen size and refresh rate, window and framebuffer sizes.
  nlohmann::ordered_json display_info() const;
  // The stimuli's bits, the output path and the framebuffer's bits; the read-back check's result
  // and the dither seed where they apply.
  nlohmann::ordered_json output_info() const;
  double refresh_hz() const { return refresh_hz_; }

  // Uploads an 8-bit RGBA image as a nearest-neighbour texture; returns its id.
  unsigned upload_texture(const std::vector<uint8_t>& rgba, int width, int height);
  // Uploads a 16-bit RGBA image (a 16-bit study only); drawn through the output path.
  unsigned upload_texture16(const std::vector<uint16_t>& rgba, int width, int height);
  // How stimuli reach the framebuffer: 8-bit for 8-bit studies; ten-bit or dither for 16-bit ones.
  OutputPath output_path() const { return path_; }
  // Frames drawn since the window opened (the loading screens included): the next frame's dither
  // index.
  uint32_t frames_drawn() const { return frames_drawn_; }

  // Events since the last call. GLFW_REPEAT is dropped on purpose: the procedure times repeats.
  std::vector<WindowEvent> poll_events();
  // The session's clock: glfwGetTime(), or with DisplayOptions::frame_clock the frames paced so
  // far times the refresh period.
  double now() const;

  // Draws a frame; when `screenshot` is set, writes that frame (as displayed) to the PNG first.
  StimulusLayout draw(const FrameContent& content, const std::filesystem::path& screenshot = {});
  // Blocks until the next frame is due: vsync where the driver provides it, else a timer (with the
  // frame clock: advances it, without waiting).
  void pace();
  // How frames are paced: "vsync", "timer" or "frame-clock".
  const char* pacing() const;
  // How many GLFW_REPEAT events (the system's key repeat) were dropped.
  long system_repeats_ignored() const { return repeats_ignored_; }

 private:
  GLFWwindow* window_ = nullptr;
  DisplayOptions options_;
  double refresh_hz_ = 60;
  int screen_w_ = 0, screen_h_ = 0;
  std::vector<unsigned> textures_;
  std::vector<WindowEvent> events_;
  double last_swap_ = -1, next_deadline_ = 0;
  int frames_ = 0;
  std::vector<double> early_intervals_;
  bool timer_pacing_ = false;
  long repeats_ignored_ = 0;
  float text_rgb_ = 0;
  std::unique_ptr<DeepStimulusRenderer> deep_;  // 16-bit studies only
  OutputPath path_ = OutputPath::eight_bit;
  std::optional<bool> ten_bit_read_back_;  // the check's result, where it ran
  int framebuffer_bits_[3] = {8, 8, 8};
  uint32_t frames_drawn_ = 0;  // the dither's frame index

  // The constructor's steps: GLFW and the monitor (its size checked against the need_w × need_h
  // pixels the stimuli need), the window with its OpenGL context, Dear ImGui.
  GLFWmonitor* open_monitor(int need_w, int need_h);
  void check_visual_angle(GLFWmonitor* monitor, int width_px) const;
  void create_window(GLFWmonitor* monitor, int need_w, int need_h);
  void start_imgui();
  void choose_output_path();
  void close_window();
  void draw_deep_stimuli(const std::vector<unsigned>& row, const StimulusLayout& layout,
                         int fb_height);

  static void key_callback(GLFWwindow* w, int key, int scancode, int action, int mods);
  static void focus_callback(GLFWwindow* w, int focused);
  static void close_callback(GLFWwindow* w);
};

}  // namespace countershade::runtime
