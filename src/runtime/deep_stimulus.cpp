#include "runtime/deep_stimulus.h"

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace countershade::runtime {

namespace {

// Four vertices of a strip over the whole viewport, from gl_VertexID: no vertex buffer needed.
const char* const kVertexShader = R"(#version 330 core
void main() {
  gl_Position = vec4(float((gl_VertexID & 1) * 2 - 1), float((gl_VertexID >> 1) * 2 - 1), 0.0, 1.0);
}
)";

// The image pixel under each fragment, counted from the image's top-left as the reference does.
// MODE, one program per path: 0 the nearest 10-bit level, 1 dithered to 8 bits, 2 pseudo-grey (a
// software rasteriser runs every branch of a uniform `if` at some cost, a #if costs nothing).
const char* const kFragmentMain = R"(
uniform sampler2D image;  // the top half: each channel's high byte; the bottom half: its low byte
uniform ivec2 top_left;  // the image's top-left pixel in window coordinates (x, and y of its top row)
uniform uint frame;
uniform uint seed_mix;   // dither_seed_mix(seed), hashed once per frame rather than per pixel
out vec4 colour;
void main() {
  uvec2 p = uvec2(int(gl_FragCoord.x) - top_left.x, top_left.y - int(gl_FragCoord.y));
  int low = textureSize(image, 0).y / 2;
  uvec3 v = uvec3(texelFetch(image, ivec2(p), 0).rgb * 255.0 + 0.5) * 256u +
            uvec3(texelFetch(image, ivec2(p) + ivec2(0, low), 0).rgb * 255.0 + 0.5);
#if MODE == 0
  colour = vec4(vec3(ten_bit_level(v)) / 1023.0, 1.0);
#elif MODE == 2
  colour = vec4(vec3(pseudo_grey_levels((v.r + v.g + v.b + 1u) / 3u)) / 255.0, 1.0);  // pseudo_grey_value
#else
  colour = vec4(vec3(dither_level(v, dither_threshold(p.x, p.y, frame, seed_mix))) / 255.0, 1.0);
#endif
}
)";

unsigned compile(GLenum kind, const std::string& source) {
  const GLuint shader = glCreateShader(kind);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {0};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw std::runtime_error(std::string("the 16-bit stimulus shader does not compile: ") + log);
  }
  return shader;
}

}  // namespace

DeepStimulusRenderer::Program DeepStimulusRenderer::link(int mode) {
  const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader);
  const GLuint fs =
      compile(GL_FRAGMENT_SHADER, "#version 330 core\n#define MODE " + std::to_string(mode) + "\n" +
                                      kFineLevelsGlsl + kFragmentMain);
  Program p;
  p.id = glCreateProgram();
  glAttachShader(p.id, vs);
  glAttachShader(p.id, fs);
  glLinkProgram(p.id);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(p.id, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("the 16-bit stimulus shader does not link");
  p.top_left = glGetUniformLocation(p.id, "top_left");
  p.frame = glGetUniformLocation(p.id, "frame");
  p.seed_mix = glGetUniformLocation(p.id, "seed_mix");
  glUseProgram(p.id);
  glUniform1i(glGetUniformLocation(p.id, "image"), 0);
  glUseProgram(0);
  return p;
}

DeepStimulusRenderer::DeepStimulusRenderer() {
  for (int mode = 0; mode < 3; ++mode) programs_[mode] = link(mode);
  glGenVertexArrays(1, &vertex_array_);
}

DeepStimulusRenderer::~DeepStimulusRenderer() {
  glDeleteVertexArrays(1, &vertex_array_);
  for (const Program& p : programs_) glDeleteProgram(p.id);
}

unsigned new_nearest_texture() {
  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_2D, id);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  return id;
}

unsigned DeepStimulusRenderer::upload(const std::vector<uint16_t>& rgba, int width, int height) {
  // Two 8-bit halves rather than one 16-bit integer texture: a software rasteriser (Mesa's
  // llvmpipe) fetches two 8-bit texels faster than one of 64 bits, and the two bytes give the same
  // code exactly (docs/performance.md, "Adjustment app").
  const size_t layer = size_t(width) * size_t(height) * 4;
  std::vector<uint8_t> bytes(2 * layer);
  for (size_t i = 0; i < layer && i < rgba.size(); ++i) {
    bytes[i] = uint8_t(rgba[i] >> 8);
    bytes[layer + i] = uint8_t(rgba[i] & 0xFFu);
  }
  const GLuint id = new_nearest_texture();
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, 2 * height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               bytes.data());
  if (glGetError() != GL_NO_ERROR) {
    glDeleteTextures(1, &id);
    throw std::runtime_error("cannot upload a 16-bit stimulus texture (out of GPU memory?)");
  }
  return id;
}

void DeepStimulusRenderer::draw(unsigned texture, const PixelRect& r, OutputPath path,
                                uint32_t frame, uint32_t seed) const {
  GLint full[4];
  glGetIntegerv(GL_VIEWPORT, full);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_FRAMEBUFFER_SRGB);
  const int bottom = r.framebuffer_height - r.y - r.height;
  glViewport(r.x, bottom, r.width, r.height);
  const Program& p = programs_[path == OutputPath::ten_bit       ? 0
                               : path == OutputPath::pseudo_grey ? 2
                                                                 : 1];
  glUseProgram(p.id);
  glUniform2i(p.top_left, r.x, r.framebuffer_height - r.y - 1);
  glUniform1ui(p.frame, frame);
  glUniform1ui(p.seed_mix, dither_seed_mix(seed));
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture);
  glBindVertexArray(vertex_array_);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glBindVertexArray(0);
  glUseProgram(0);
  glViewport(full[0], full[1], full[2], full[3]);
}

std::vector<uint16_t> read_back_rgba16(const PixelRect& r) {
  const size_t row = size_t(r.width) * 4;
  std::vector<uint16_t> bottom_up(row * size_t(r.height)), out(bottom_up.size());
  glFinish();
  glPixelStorei(GL_PACK_ALIGNMENT, 2);
  glReadPixels(r.x, r.framebuffer_height - r.y - r.height, r.width, r.height, GL_RGBA,
               GL_UNSIGNED_SHORT, bottom_up.data());
  for (int y = 0; y < r.height; ++y)
    std::copy_n(&bottom_up[size_t(r.height - 1 - y) * row], row, &out[size_t(y) * row]);
  return out;
}

std::vector<uint16_t> ten_bit_probe(int* width, int* height) {
  *width = 256;
  *height = 12;
  std::vector<uint16_t> probe(size_t(*width) * size_t(*height) * 4, 65535);
  for (int level = 0; level < 1024; ++level) {
    const int centre = (level * 65535 + 511) / 1023;
    for (int k = 0; k < 3; ++k) {
      const int code = std::clamp(centre + (k - 1) * 31, 0, 65535);
      const size_t pixel = size_t(k * 4 + level / 256) * 256 + size_t(level % 256);
      for (int c = 0; c < 3; ++c) probe[pixel * 4 + size_t(c)] = uint16_t(code);
    }
  }
  return probe;
}

bool ten_bit_read_back_holds(const DeepStimulusRenderer& renderer, int framebuffer_height) {
  PixelRect where;
  const std::vector<uint16_t> probe = ten_bit_probe(&where.width, &where.height);
  where.framebuffer_height = framebuffer_height;
  const unsigned texture = DeepStimulusRenderer::upload(probe, where.width, where.height);
  renderer.draw(texture, where, OutputPath::ten_bit, 0, 0);
  const std::vector<uint16_t> back = read_back_rgba16(where);
  glDeleteTextures(1, &texture);
  for (size_t i = 0; i < probe.size(); ++i)
    if (i % 4 != 3 && ten_bit_level(back[i]) != ten_bit_level(probe[i])) return false;
  return true;
}

}  // namespace countershade::runtime
