// The 16-bit output paths on OpenGL (Mesa llvmpipe on a private Xvfb), offscreen: the shader's
// 10-bit output read back from a GL_RGB10_A2 framebuffer, and its dithered 8-bit frames, against
// the C++ reference of runtime/fine_levels.h.

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>

#include "../adjust/tiny_set.h"
#include "../adjust/x_display.h"
#include "runtime/deep_stimulus.h"
#include "runtime/image_decode.h"
#include "runtime/study.h"

namespace countershade::runtime {

namespace {

// A hidden window's OpenGL 3.3 core context on a private X server. Mesa's driver keeps
// allocations until it is unloaded, after LeakSanitizer looks, so they are not counted.
class GlContext {
 public:
  GlContext() : x_("640x480x24") {
#if defined(__SANITIZE_ADDRESS__)
    __lsan_disable();
#endif
    ::setenv("DISPLAY", x_.display().c_str(), 1);
    if (!glfwInit()) throw std::runtime_error("glfwInit failed");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    window_ = glfwCreateWindow(64, 64, "test", nullptr, nullptr);
    if (!window_) throw std::runtime_error("no OpenGL 3.3 context");
    glfwMakeContextCurrent(window_);
  }
  ~GlContext() {
    glfwDestroyWindow(window_);
    glfwTerminate();
#if defined(__SANITIZE_ADDRESS__)
    __lsan_enable();
#endif
  }

 private:
  testing::XvfbServer x_;
  GLFWwindow* window_ = nullptr;
};

// An offscreen framebuffer of one colour renderbuffer in `format`, bound for drawing and reading.
class Framebuffer {
 public:
  Framebuffer(GLenum format, int width, int height) {
    glGenFramebuffers(1, &fbo_);
    glGenRenderbuffers(1, &colour_);
    glBindRenderbuffer(GL_RENDERBUFFER, colour_);
    glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
    complete_ = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glViewport(0, 0, width, height);
  }
  ~Framebuffer() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteRenderbuffers(1, &colour_);
    glDeleteFramebuffers(1, &fbo_);
  }
  bool complete() const { return complete_; }

 private:
  GLuint fbo_ = 0, colour_ = 0;
  bool complete_ = false;
};

// A 16-bit stimulus of the tiny set (its most enhanced image: the widest range of codes).
struct DeepStimulus {
  std::vector<uint16_t> rgba;
  int width = 0, height = 0;
};
DeepStimulus deep_stimulus(const testing::TempDir& dir) {
  const auto manifest = testing::make_tiny_set(dir, "", 96, 72, 0.4, R"("output": {"bits": 16},)");
  const Study study = load_study(manifest, std::nullopt);
  EXPECT_EQ(study.bits, 16);
  const StimulusImage& image = study.images.back();
  return {decode_rgba16(image), image.width, image.height};
}

// Codes that no 8-bit image has: the test would pass trivially on values that are multiples of 257.
bool has_fine_codes(const DeepStimulus& s) {
  for (size_t i = 0; i < s.rgba.size(); ++i)
    if (i % 4 != 3 && s.rgba[i] % 257 != 0) return true;
  return false;
}

TEST(DeepOutput, ATenBitFramebufferReadsBackEachSixteenBitCodesNearestTenBitLevel) {
  testing::TempDir dir;
  const DeepStimulus s = deep_stimulus(dir);
  ASSERT_TRUE(has_fine_codes(s));
  GlContext gl;
  Framebuffer fb(GL_RGB10_A2, 300, s.height + 10);  // wide enough for the 256-pixel probe too
  ASSERT_TRUE(fb.complete());
  DeepStimulusRenderer renderer;
  const PixelRect where{7, 3, s.width, s.height, s.height + 10};
  const unsigned texture = DeepStimulusRenderer::upload(s.rgba, s.width, s.height);
  renderer.draw(texture, where, OutputPath::ten_bit, 0, 0);
  const std::vector<uint16_t> back = read_back_rgba16(where);
  long exact = 0, channels = 0;
  for (size_t i = 0; i < s.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    // A 10-bit level l reads back as round(l · 65535 / 1023): the level is recovered exactly.
    exact += ten_bit_level(back[i]) == ten_bit_level(s.rgba[i]);
    ++channels;
  }
  EXPECT_EQ(exact, channels);
  // The app's own check passes on this framebuffer, and fails on an 8-bit one.
  EXPECT_TRUE(ten_bit_read_back_holds(renderer, s.height + 10));
  Framebuffer eight(GL_RGBA8, 300, 20);
  EXPECT_FALSE(ten_bit_read_back_holds(renderer, 20));
  glDeleteTextures(1, &texture);
}

TEST(DeepOutput, DitheredFramesAreTheReferencesAndAverageToTheSixteenBitValue) {
  testing::TempDir dir;
  const DeepStimulus s = deep_stimulus(dir);
  GlContext gl;
  Framebuffer fb(GL_RGBA8, s.width, s.height);
  ASSERT_TRUE(fb.complete());
  DeepStimulusRenderer renderer;
  const unsigned texture = DeepStimulusRenderer::upload(s.rgba, s.width, s.height);
  const PixelRect where{0, 0, s.width, s.height, s.height};
  constexpr uint32_t kSeed = 2718;
  const size_t pixels = size_t(s.width) * size_t(s.height);
  std::vector<double> sum(pixels * 3, 0.0);
  long differing = 0;
  for (uint32_t frame = 100; frame < 164; ++frame) {
    renderer.draw(texture, where, OutputPath::dither, frame, kSeed);
    const std::vector<uint16_t> back = read_back_rgba16(where);
    for (size_t p = 0; p < pixels; ++p)
      for (size_t c = 0; c < 3; ++c) {
        const uint32_t shown = back[p * 4 + c] / 257u;  // an 8-bit level l reads back as l · 257
        const uint32_t x = uint32_t(p % size_t(s.width)), y = uint32_t(p / size_t(s.width));
        differing += shown != dither_level(s.rgba[p * 4 + c], dither_threshold(x, y, frame, kSeed));
        sum[p * 3 + c] += shown;
      }
  }
  EXPECT_EQ(differing, 0) << "frames differ from the seed's reference";
  double worst = 0;
  for (size_t p = 0; p < pixels; ++p)
    for (size_t c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(sum[p * 3 + c] / 64 - s.rgba[p * 4 + c] * 255.0 / 65535.0));
  EXPECT_LT(worst, 0.02) << "the worst pixel's 64-frame mean, in 8-bit levels";
  glDeleteTextures(1, &texture);
}

// Every 16-bit grey value, drawn in pseudo-grey into an 8-bit framebuffer, reads back as the C++
// reference's three levels; odd values have green one code up (a near-grey pixel of a render),
// which the mean of the three rounds away.
TEST(DeepOutput, PseudoGreyDrawsEverySixteenBitGreyAsTheReferenceLevels) {
  GlContext gl;
  Framebuffer fb(GL_RGBA8, 256, 256);
  ASSERT_TRUE(fb.complete());
  std::vector<uint16_t> ramp(256 * 256 * 4);
  for (uint32_t v = 0; v < 65536; ++v)
    for (int c = 0; c < 4; ++c)
      ramp[v * 4 + c] = uint16_t(c == 3 ? 65535 : c == 1 ? std::min(v + (v & 1), 65535u) : v);
  DeepStimulusRenderer renderer;
  const unsigned texture = DeepStimulusRenderer::upload(ramp, 256, 256);
  const PixelRect where{0, 0, 256, 256, 256};
  renderer.draw(texture, where, OutputPath::pseudo_grey, 0, 0);
  const std::vector<uint16_t> back = read_back_rgba16(where);
  const uint32_t masks[3] = {kPseudoGreyRed, kPseudoGreyGreen, kPseudoGreyBlue};
  long differing = 0, tilted = 0;
  for (uint32_t v = 0; v < 65536; ++v) {
    const uint32_t grey = pseudo_grey_value(ramp[v * 4], ramp[v * 4 + 1], ramp[v * 4 + 2]);
    for (int c = 0; c < 3; ++c)
      differing += back[v * 4 + c] / 257u != pseudo_grey_level(grey, masks[c]);
    tilted += back[v * 4] != back[v * 4 + 1] || back[v * 4 + 1] != back[v * 4 + 2];
  }
  EXPECT_EQ(differing, 0);
  EXPECT_GT(tilted, 50000);  // most values are shown between two greys
  glDeleteTextures(1, &texture);
}

}  // namespace
}  // namespace countershade::runtime
