#include "runtime/presenter.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <thread>

#include "core/error.h"
#include "core/image.h"
#include "core/visual_angle.h"
#include "runtime/deep_stimulus.h"

namespace countershade::runtime {

namespace {

const char* const kFontFile = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

std::string glfw_error;
void record_glfw_error(int, const char* description) {
  glfw_error = description ? description : "unknown error";
}

struct Margins {
  int side, top, bottom;
};
Margins margins_for(const DisplayOptions& o) {
  const double line = o.font_px * 1.35;
  return {int(std::ceil(o.font_px)), int(std::ceil(line * 4.5)), int(std::ceil(line * 2.5))};
}

std::optional<Key> key_of(int glfw_key) {
  switch (glfw_key) {
    case GLFW_KEY_UP:
      return Key::up;
    case GLFW_KEY_DOWN:
      return Key::down;
    case GLFW_KEY_LEFT:
      return Key::left;
    case GLFW_KEY_RIGHT:
      return Key::right;
    case GLFW_KEY_ENTER:
    case GLFW_KEY_KP_ENTER:
      return Key::enter;
    case GLFW_KEY_BACKSPACE:
      return Key::backspace;
    case GLFW_KEY_ESCAPE:
      return Key::escape;
    case GLFW_KEY_Q:
      return Key::quit;
    case GLFW_KEY_1:
    case GLFW_KEY_KP_1:
      return Key::one;
    case GLFW_KEY_2:
    case GLFW_KEY_KP_2:
      return Key::two;
    case GLFW_KEY_3:
    case GLFW_KEY_KP_3:
      return Key::three;
    case GLFW_KEY_4:
    case GLFW_KEY_KP_4:
      return Key::four;
    default:
      return std::nullopt;
  }
}

// Draws `text` wrapped to `wrap` pixels, the block centred on `centre_x`, from `top`; returns the
// height used.
float centred_text(ImDrawList* list, const char* text, float centre_x, float top, float wrap,
                   ImU32 colour) {
  ImFont* font = ImGui::GetFont();
  const float size = ImGui::GetFontSize();
  ImVec2 extent = font->CalcTextSizeA(size, FLT_MAX, wrap, text);
  list->AddText(font, size, ImVec2(std::floor(centre_x - extent.x / 2), std::floor(top)), colour,
                text, nullptr, wrap);
  return extent.y;
}

}  // namespace

DisplayOptions study_display(const Study& study, const std::string& app) {
  DisplayOptions display;
  display.stimulus_width = study.max_width();
  display.stimulus_height = study.max_height();
  display.gap_px = study.config.gap_px;
  display.surround = study.config.surround;
  display.font_px = study.config.font_px;
  display.title = "countershade " + app + ": " + study.set_name;
  display.pixels_per_degree = study.pixels_per_degree;
  display.distance_mm = study.distance_mm;
  display.stimulus_bits = study.bits;
  return display;
}

void Presenter::required_size(const DisplayOptions& o, int* width, int* height) {
  Margins m = margins_for(o);
  *width = o.columns * o.stimulus_width + (o.columns - 1) * o.gap_px + 2 * m.side;
  *height = o.stimulus_height + m.top + m.bottom;
}

Presenter::Presenter(const DisplayOptions& options) : options_(options) {
  int need_w = 0, need_h = 0;
  required_size(options, &need_w, &need_h);
  create_window(open_monitor(need_w, need_h), need_w, need_h);
  start_imgui();
  if (options.stimulus_bits == 16) choose_output_path();
  text_rgb_ = options.surround >= 128 ? 0.08f : 0.92f;
}

GLFWmonitor* Presenter::open_monitor(int need_w, int need_h) {
  glfwSetErrorCallback(record_glfw_error);
  if (!glfwInit())
    throw std::runtime_error("cannot open a window: " + glfw_error +
                             " (the app needs a display; for tests run it under xvfb-run)");
  int count = 0;
  GLFWmonitor** monitors = glfwGetMonitors(&count);
  if (count == 0 || !monitors) {
    glfwTerminate();
    throw std::runtime_error("cannot open a window: no monitor found");
  }
  const DisplayOptions& o = options_;
  if (o.monitor < 0 || o.monitor >= count) {
    glfwTerminate();
    throw_input_error("--monitor", std::to_string(o.monitor) + " is not a monitor (found " +
                                       std::to_string(count) + ", numbered from 0)");
  }
  GLFWmonitor* monitor = monitors[o.monitor];
  const GLFWvidmode* mode = glfwGetVideoMode(monitor);
  screen_w_ = mode->width;
  screen_h_ = mode->height;
  if (mode->refreshRate > 0) refresh_hz_ = mode->refreshRate;
  if (need_w > screen_w_ || need_h > screen_h_) {
    glfwTerminate();
    throw_input_error(
        "display", "two " + std::to_string(o.stimulus_width) + "x" +
                       std::to_string(o.stimulus_height) + " stimuli with the question text need " +
                       std::to_string(need_w) + "x" + std::to_string(need_h) +
                       " pixels at 1:1 scale, but monitor " + std::to_string(o.monitor) + " is " +
                       std::to_string(screen_w_) + "x" + std::to_string(screen_h_) +
                       " (use a larger screen or a set with smaller images)");
  }
  if (o.pixels_per_degree) check_visual_angle(monitor, screen_w_);
  return monitor;
}

// A set made for another screen would show its sizes and σ in degrees wrongly: refused.
void Presenter::check_visual_angle(GLFWmonitor* monitor, int width_px) const {
  const DisplayOptions& o = options_;
  double width_mm = o.monitor_width_mm.value_or(0.0);
  if (!o.monitor_width_mm) {
    int w = 0, h = 0;
    glfwGetMonitorPhysicalSize(monitor, &w, &h);
    width_mm = w;
  }
  char text[320];
  if (!(width_mm > 0)) {
    glfwTerminate();
    throw_input_error("--monitor-width-mm",
                      "the monitor does not report its size; give its width in mm");
  }
  const double ppd = pixels_per_degree(width_mm, width_px, *o.distance_mm);
  if (std::abs(ppd / *o.pixels_per_degree - 1.0) <= 0.02) return;
  std::snprintf(text, sizeof text,
                "the set was made for %.2f pixels per degree at %.0f mm, but monitor %d (%d px, "
                "%.0f mm wide) gives "
                "%.2f (%+.1f %%; at most 2 %% allowed): use the screen the set was made for, or "
                "--monitor-width-mm "
                "if the monitor misreports its size",
                *o.pixels_per_degree, *o.distance_mm, o.monitor, width_px, width_mm, ppd,
                100.0 * (ppd / *o.pixels_per_degree - 1.0));
  glfwTerminate();
  throw_input_error("display", text);
}

void Presenter::create_window(GLFWmonitor* monitor, int need_w, int need_h) {
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_FALSE);  // display values go to the screen unchanged
  glfwWindowHint(GLFW_SAMPLES, 0);
  // A 16-bit study asks for 10 bits per channel; GLFW gives the closest the display has.
  const bool ten = options_.stimulus_bits == 16 && options_.output_path.may_use_ten_bit();
  for (int hint : {GLFW_RED_BITS, GLFW_GREEN_BITS, GLFW_BLUE_BITS})
    glfwWindowHint(hint, ten ? 10 : 8);
  glfwWindowHint(GLFW_ALPHA_BITS, ten ? 2 : 8);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_FALSE);
  int win_w = std::max(need_w, std::min(1280, screen_w_)),
      win_h = std::max(need_h, std::min(800, screen_h_));
  if (options_.fullscreen) {
    glfwWindowHint(GLFW_REFRESH_RATE, glfwGetVideoMode(monitor)->refreshRate);
    win_w = screen_w_;
    win_h = screen_h_;
  }
  window_ = glfwCreateWindow(win_w, win_h, options_.title.c_str(),
                             options_.fullscreen ? monitor : nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw std::runtime_error("cannot open an OpenGL 3.3 core window: " + glfw_error);
  }
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, key_callback);
  glfwSetWindowFocusCallback(window_, focus_callback);
  glfwSetWindowCloseCallback(window_, close_callback);
  if (options_.fullscreen) glfwSetInputMode(window_, GLFW_CURSOR, GLFW_CURSOR_HIDDEN);
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(1);
}

void Presenter::start_imgui() {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // nothing written to the working folder
  io.LogFilename = nullptr;
  ImFontConfig font_config;
  font_config.OversampleH = 2;
  // Latin-1, Greek, general punctuation, arrows and mathematical operators: the study's texts
  // may speak of λ, σ, ±, ≤, ×, ° and – (ImGui's default atlas has Latin-1 alone).
  static const ImWchar kGlyphRanges[] = {0x0020, 0x00FF, 0x0370, 0x03FF, 0x2010, 0x205E,
                                         0x2190, 0x21FF, 0x2200, 0x22FF, 0};
  if (!io.Fonts->AddFontFromFileTTF(kFontFile, float(options_.font_px), &font_config,
                                    kGlyphRanges)) {
    ImFontConfig fallback;
    fallback.SizePixels = float(options_.font_px);
    io.Fonts->AddFontDefault(&fallback);
  }
  ImGui_ImplGlfw_InitForOpenGL(window_, false);  // the app handles keys itself
  ImGui_ImplOpenGL3_Init("#version 330 core");
}

// The 16-bit path: ten-bit where the framebuffer has 10 bits and a read-back of every level
// confirms them (a driver may report bits it does not keep), else the dither.
void Presenter::choose_output_path() {
  const GLenum sizes[3] = {GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE, GL_FRAMEBUFFER_ATTACHMENT_GREEN_SIZE,
                           GL_FRAMEBUFFER_ATTACHMENT_BLUE_SIZE};
  for (int c = 0; c < 3; ++c)
    glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GL_BACK_LEFT, sizes[c],
                                          &framebuffer_bits_[c]);
  deep_ = std::make_unique<DeepStimulusRenderer>();
  const OutputPathChoice& choice = options_.output_path;
  if (choice.may_use_ten_bit()) {
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    ten_bit_read_back_ = ten_bit_read_back_holds(*deep_, fh);
  }
  path_ = choice.automatic ? (*ten_bit_read_back_ ? OutputPath::ten_bit : OutputPath::dither)
                           : choice.path;
  if (path_ == OutputPath::ten_bit && !*ten_bit_read_back_) {
    close_window();
    throw_input_error(
        "--output-path",
        "ten-bit: this display's framebuffer has " + std::to_string(framebuffer_bits_[0]) +
            " bits per channel and does not read back 10-bit levels (use auto or dither)");
  }
}

void Presenter::close_window() {
  if (!window_) return;
  glfwMakeContextCurrent(window_);
  if (!textures_.empty()) glDeleteTextures(GLsizei(textures_.size()), textures_.data());
  deep_.reset();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window_);
  glfwTerminate();
  window_ = nullptr;
}

Presenter::~Presenter() { close_window(); }

nlohmann::ordered_json Presenter::display_info() const {
  int ww = 0, wh = 0, fw = 0, fh = 0;
  glfwGetWindowSize(window_, &ww, &wh);
  glfwGetFramebufferSize(window_, &fw, &fh);
  auto gl_string = [](GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return {{"gl_renderer", gl_string(GL_RENDERER)},
          {"gl_vendor", gl_string(GL_VENDOR)},
          {"gl_version", gl_string(GL_VERSION)},
          {"glfw_version", glfwGetVersionString()},
          {"monitor", options_.monitor},
          {"screen", {screen_w_, screen_h_}},
          {"refresh_hz", refresh_hz_},
          {"fullscreen", options_.fullscreen},
          {"window", {ww, wh}},
          {"framebuffer", {fw, fh}},
          {"surround", options_.surround},
          {"output", output_info()}};
}

nlohmann::ordered_json Presenter::output_info() const {
  nlohmann::ordered_json out = {{"stimulus_bits", options_.stimulus_bits},
                                {"path", output_path_name(path_)},
                                {"framebuffer_bits", framebuffer_bits_}};
  if (ten_bit_read_back_) out["ten_bit_read_back"] = *ten_bit_read_back_;
  if (path_ == OutputPath::dither) out["dither_seed"] = options_.dither_seed;
  return out;
}

unsigned Presenter::upload_texture(const std::vector<uint8_t>& rgba, int width, int height) {
  const unsigned id = new_nearest_texture();
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               rgba.data());
  if (glGetError() != GL_NO_ERROR)
    throw std::runtime_error("cannot upload a stimulus texture (out of GPU memory?)");
  textures_.push_back(id);
  return id;
}

unsigned Presenter::upload_texture16(const std::vector<uint16_t>& rgba, int width, int height) {
  if (!deep_) throw std::logic_error("a 16-bit texture in an 8-bit study");
  textures_.push_back(DeepStimulusRenderer::upload(rgba, width, height));
  return textures_.back();
}

void Presenter::key_callback(GLFWwindow* w, int key, int, int action, int) {
  auto* self = static_cast<Presenter*>(glfwGetWindowUserPointer(w));
  // GLFW_REPEAT comes at the system's rate; the procedure makes its own, controlled repeats.
  auto k = key_of(key);
  if (!k) return;
  if (action == GLFW_REPEAT) {
    ++self->repeats_ignored_;
    return;
  }
  self->events_.push_back(
      {action == GLFW_PRESS ? WindowEvent::Kind::press : WindowEvent::Kind::release, *k,
       glfwGetTime()});
}

void Presenter::focus_callback(GLFWwindow* w, int focused) {
  auto* self = static_cast<Presenter*>(glfwGetWindowUserPointer(w));
  self->events_.push_back(
      {focused ? WindowEvent::Kind::focus_gained : WindowEvent::Kind::focus_lost, Key::enter,
       glfwGetTime()});
}

void Presenter::close_callback(GLFWwindow* w) {
  auto* self = static_cast<Presenter*>(glfwGetWindowUserPointer(w));
  glfwSetWindowShouldClose(w, GLFW_FALSE);  // the session decides; its answers are already saved
  self->events_.push_back({WindowEvent::Kind::close, Key::enter, glfwGetTime()});
}

std::vector<WindowEvent> Presenter::poll_events() {
  glfwPollEvents();
  std::vector<WindowEvent> out;
  out.swap(events_);
  return out;
}

double Presenter::now() const {
  return options_.frame_clock ? frames_ / refresh_hz_ : glfwGetTime();
}

const char* Presenter::pacing() const {
  return options_.frame_clock ? "frame-clock" : timer_pacing_ ? "timer" : "vsync";
}

namespace {

// One frame's drawing surface: sizes (ImGui works in window coordinates, stimuli are placed in
// framebuffer pixels), text metrics and ImGui's draw lists.
struct Canvas {
  int fw = 0, fh = 0, ww = 0, wh = 0;
  float scale = 1, wrap = 0, line = 0;
  ImU32 text = 0;
  ImDrawList *back = nullptr, *front = nullptr;
};

// The images a frame shows, left to right: its row, or the left and right pair, or the one
// centred image.
std::vector<unsigned> stimulus_row(const FrameContent& c) {
  if (!c.row.empty()) return c.row;
  if (c.centred) return {c.left_texture};
  return {c.left_texture, c.right_texture};
}

// The stimuli side by side at 1:1 (or a request to enlarge the window), the header and question
// above them, the hint below.
// 16-bit stimuli are not ImGui images (`imgui_images` false): the presenter draws them itself.
StimulusLayout draw_stimuli(const FrameContent& c, const DisplayOptions& o, const Canvas& k,
                            bool imgui_images) {
  const Margins m = margins_for(o);
  const std::vector<unsigned> row = stimulus_row(c);
  StimulusLayout layout;
  layout.width = c.image_width;
  layout.height = c.image_height;
  const int n = int(row.size()), span = n * c.image_width + (n - 1) * o.gap_px;
  layout.fits = span + 2 * m.side <= k.fw && c.image_height + m.top + m.bottom <= k.fh;
  for (int i = 0; i < n; ++i)
    layout.xs.push_back((k.fw - span) / 2 + i * (c.image_width + o.gap_px));
  layout.left_x = layout.xs.front();
  layout.right_x = layout.xs.back();
  layout.y = m.top + std::max(0, (k.fh - m.top - m.bottom - c.image_height) / 2);
  const float centre = float(k.ww) / 2;
  if (layout.fits && imgui_images) {
    for (int i = 0; i < n; ++i)
      k.back->AddImage(reinterpret_cast<ImTextureID>(uintptr_t(row[size_t(i)])),
                       ImVec2(float(layout.xs[size_t(i)]) / k.scale, float(layout.y) / k.scale),
                       ImVec2(float(layout.xs[size_t(i)] + c.image_width) / k.scale,
                              float(layout.y + c.image_height) / k.scale));
  } else if (!layout.fits) {
    centred_text(k.front,
                 "The window is too small to show the images at 1:1 scale. Please enlarge it.",
                 centre, float(k.wh) / 2, k.wrap, k.text);
  }
  const float top = float(layout.y) / k.scale, bottom = float(layout.y + c.image_height) / k.scale;
  if (!c.header.empty())
    centred_text(k.front, c.header.c_str(), centre, top - 3.2f * k.line, k.wrap, k.text);
  if (!c.question.empty())
    centred_text(k.front, c.question.c_str(), centre, top - 1.9f * k.line, k.wrap, k.text);
  if (!c.hint.empty())
    centred_text(k.front, c.hint.c_str(), centre, bottom + 0.8f * k.line, k.wrap, k.text);
  return layout;
}

// A centred message over the surround, with an optional progress bar under it.
void draw_message(const FrameContent& c, const Canvas& k) {
  const float wrap = std::min(k.wrap, 900.0f);
  const float h =
      ImGui::GetFont()->CalcTextSizeA(ImGui::GetFontSize(), FLT_MAX, wrap, c.message.c_str()).y;
  const float top = float(k.wh) / 2 - h / 2 - k.line;
  const float used = centred_text(k.front, c.message.c_str(), float(k.ww) / 2, top, wrap, k.text);
  if (c.progress < 0) return;
  const float bw = std::min(600.0f, float(k.ww) * 0.6f), bh = k.line * 0.6f;
  const ImVec2 p0(float(k.ww) / 2 - bw / 2, top + used + k.line), p1(p0.x + bw, p0.y + bh);
  k.front->AddRect(p0, p1, k.text, 0, 0, 1.5f);
  k.front->AddRectFilled(p0, ImVec2(p0.x + bw * float(std::clamp(c.progress, 0.0, 1.0)), p1.y),
                         k.text);
}

// The back buffer as drawn, to a PNG: 8 bits, or 16 where the framebuffer has more than 8 (a
// 10-bit level l is written as round(l · 65535 / 1023), so it reads back exactly).
void write_screenshot(const std::filesystem::path& file, int fw, int fh, bool deep) {
  glReadBuffer(GL_BACK);
  const std::vector<uint16_t> rgba = read_back_rgba16({0, 0, fw, fh, fh});
  Image shot(fw, fh, 3);
  for (size_t p = 0; p < size_t(fw) * size_t(fh); ++p)
    for (size_t c = 0; c < 3; ++c) shot.pixels[p * 3 + c] = float(rgba[p * 4 + c]) / 65535.0f;
  ImageWriteOptions options;
  options.png_bits = deep ? 16 : 8;
  write_image(file, shot, options);
}

}  // namespace

StimulusLayout Presenter::draw(const FrameContent& c, const std::filesystem::path& screenshot) {
  Canvas k;
  glfwGetFramebufferSize(window_, &k.fw, &k.fh);
  glfwGetWindowSize(window_, &k.ww, &k.wh);
  k.scale = k.ww > 0 ? float(k.fw) / float(k.ww) : 1.0f;
  glViewport(0, 0, k.fw, k.fh);
  const float grey = float(options_.surround) / 255.0f;
  glDisable(GL_FRAMEBUFFER_SRGB);
  glClearColor(grey, grey, grey, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  k.back = ImGui::GetBackgroundDrawList();
  k.front = ImGui::GetForegroundDrawList();
  k.text = ImGui::ColorConvertFloat4ToU32(ImVec4(text_rgb_, text_rgb_, text_rgb_, 1));
  k.wrap = float(k.ww) * 0.8f;
  k.line = ImGui::GetFontSize() * 1.35f;

  StimulusLayout layout;
  if (!c.row.empty() || (c.left_texture && (c.right_texture || c.centred))) {
    layout = draw_stimuli(c, options_, k, !deep_);
    if (deep_ && layout.fits) draw_deep_stimuli(stimulus_row(c), layout, k.fh);
  }
  if (!c.message.empty()) draw_message(c, k);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (!screenshot.empty()) write_screenshot(screenshot, k.fw, k.fh, framebuffer_bits_[0] > 8);
  ++frames_drawn_;
  glfwSwapBuffers(window_);
  return layout;
}

void Presenter::draw_deep_stimuli(const std::vector<unsigned>& row, const StimulusLayout& layout,
                                  int fb_height) {
  for (size_t i = 0; i < row.size(); ++i)
    deep_->draw(row[i], {layout.xs[i], layout.y, layout.width, layout.height, fb_height}, path_,
                frames_drawn_, options_.dither_seed);
}

void Presenter::pace() {
  if (options_.frame_clock) return void(++frames_);
  const double period = 1.0 / refresh_hz_;
  const double t = glfwGetTime();
  if (last_swap_ >= 0 && frames_ < 20) early_intervals_.push_back(t - last_swap_);
  ++frames_;
  if (frames_ == 20 && !early_intervals_.empty()) {
    // Without a working swap interval (e.g. a virtual X server) frames would run unthrottled.
    std::nth_element(early_intervals_.begin(),
                     early_intervals_.begin() + early_intervals_.size() / 2,
                     early_intervals_.end());
    timer_pacing_ = early_intervals_[early_intervals_.size() / 2] < 0.5 * period;
    next_deadline_ = t + period;
  }
  if (timer_pacing_) {
    // Sleep to just before the deadline, then spin: a sleep can overshoot by a millisecond or more.
    constexpr double kSpin = 0.002;
    if (t < next_deadline_ - kSpin)
      std::this_thread::sleep_for(std::chrono::duration<double>(next_deadline_ - kSpin - t));
    while (glfwGetTime() < next_deadline_) std::this_thread::yield();
    next_deadline_ = std::max(next_deadline_ + period, glfwGetTime());
  }
  last_swap_ = glfwGetTime();
}

}  // namespace countershade::runtime
