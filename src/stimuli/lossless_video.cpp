#include "stimuli/lossless_video.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
}

#include "core/atomic_file.h"

namespace countershade {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void fail(const fs::path& file, const std::string& what, int code = 0) {
  char text[AV_ERROR_MAX_STRING_SIZE] = "";
  if (code < 0) av_strerror(code, text, sizeof text);
  throw std::runtime_error(file.string() + ": " + what +
                           (code < 0 ? std::string(" (") + text + ")" : ""));
}

struct CodecFree {
  void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct FrameFree {
  void operator()(AVFrame* f) const { av_frame_free(&f); }
};
struct PacketFree {
  void operator()(AVPacket* p) const { av_packet_free(&p); }
};
using CodecPtr = std::unique_ptr<AVCodecContext, CodecFree>;
using FramePtr = std::unique_ptr<AVFrame, FrameFree>;
using PacketPtr = std::unique_ptr<AVPacket, PacketFree>;

// An output file: the Matroska muxer with one FFV1 stream.
struct Muxer {
  AVFormatContext* format = nullptr;
  AVStream* stream = nullptr;
  CodecPtr codec;
  ~Muxer() {
    if (format && format->pb) avio_closep(&format->pb);
    avformat_free_context(format);
  }
};

void open_muxer(Muxer& m, const fs::path& file, int width, int height, double fps) {
  if (avformat_alloc_output_context2(&m.format, nullptr, "matroska", file.c_str()) < 0)
    fail(file, "no Matroska muxer");
  m.format->flags |=
      AVFMT_FLAG_BITEXACT;  // no random ids or dates: the same frames, the same bytes
  const AVCodec* ffv1 = avcodec_find_encoder(AV_CODEC_ID_FFV1);
  if (!ffv1) fail(file, "this libavcodec has no FFV1 encoder");
  m.codec.reset(avcodec_alloc_context3(ffv1));
  AVCodecContext* c = m.codec.get();
  c->width = width;
  c->height = height;
  c->pix_fmt = AV_PIX_FMT_BGR0;
  c->time_base = av_inv_q(av_d2q(fps, 1000000));
  c->framerate = av_d2q(fps, 1000000);
  c->level = 3;
  c->thread_count = 1;
  c->flags |= AV_CODEC_FLAG_BITEXACT;
  if (m.format->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if (int e = avcodec_open2(c, ffv1, nullptr); e < 0) fail(file, "cannot open the FFV1 encoder", e);
  m.stream = avformat_new_stream(m.format, nullptr);
  avcodec_parameters_from_context(m.stream->codecpar, c);
  m.stream->time_base = c->time_base;
  if (int e = avio_open(&m.format->pb, file.c_str(), AVIO_FLAG_WRITE); e < 0)
    fail(file, "cannot write", e);
  if (int e = avformat_write_header(m.format, nullptr); e < 0)
    fail(file, "cannot write the header", e);
}

// Sends one frame (null: the end) and writes every packet the encoder has ready.
void encode(Muxer& m, const AVFrame* frame, const fs::path& file) {
  if (int e = avcodec_send_frame(m.codec.get(), frame); e < 0) fail(file, "cannot encode", e);
  PacketPtr packet(av_packet_alloc());
  while (avcodec_receive_packet(m.codec.get(), packet.get()) == 0) {
    av_packet_rescale_ts(packet.get(), m.codec->time_base, m.stream->time_base);
    packet->stream_index = m.stream->index;
    if (int e = av_interleaved_write_frame(m.format, packet.get()); e < 0)
      fail(file, "cannot write a frame", e);
  }
}

uint8_t code(float value) { return uint8_t(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f)); }

// Where channel c (R, G, B) of a pixel lies in FFV1's 8-bit RGB layout, B G R 0 bytes per pixel.
constexpr int kByteOf[3] = {2, 1, 0};

// An RGB image as a frame of that layout.
FramePtr packed_frame(const Image& image, int64_t pts) {
  FramePtr f(av_frame_alloc());
  f->format = AV_PIX_FMT_BGR0;
  f->width = image.width;
  f->height = image.height;
  av_frame_get_buffer(f.get(), 0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      uint8_t* pixel = f->data[0] + y * f->linesize[0] + 4 * x;
      for (int c = 0; c < 3; ++c)
        pixel[kByteOf[c]] = code(image.at(x, y, std::min(c, image.channels - 1)));
      pixel[3] = 0;
    }
  f->pts = pts;
  return f;
}

void write_frames(const fs::path& file, const std::vector<Image>& frames, double fps) {
  Muxer m;
  open_muxer(m, file, frames.front().width, frames.front().height, fps);
  for (size_t k = 0; k < frames.size(); ++k)
    encode(m, packed_frame(frames[k], int64_t(k)).get(), file);
  encode(m, nullptr, file);
  if (int e = av_write_trailer(m.format); e < 0) fail(file, "cannot finish", e);
}

Image rgb_of(const AVFrame* f, const fs::path& file) {
  if (f->format != AV_PIX_FMT_BGR0) fail(file, "not an 8-bit RGB video");
  Image image(f->width, f->height, 3);
  for (int y = 0; y < f->height; ++y)
    for (int x = 0; x < f->width; ++x)
      for (int c = 0; c < 3; ++c)
        image.at(x, y, c) = float(f->data[0][y * f->linesize[0] + 4 * x + kByteOf[c]]) / 255.0f;
  return image;
}

// Receives every frame the decoder has ready.
void drain(AVCodecContext* decoder, std::vector<Image>& out, const fs::path& file) {
  FramePtr frame(av_frame_alloc());
  while (avcodec_receive_frame(decoder, frame.get()) == 0) out.push_back(rgb_of(frame.get(), file));
}

}  // namespace

std::vector<Image> read_video_frames(const fs::path& video) {
  AVFormatContext* input = nullptr;
  if (int e = avformat_open_input(&input, video.c_str(), nullptr, nullptr); e < 0)
    fail(video, "cannot open", e);
  std::unique_ptr<AVFormatContext, void (*)(AVFormatContext*)> guard(
      input, [](AVFormatContext* c) { avformat_close_input(&c); });
  if (int e = avformat_find_stream_info(input, nullptr); e < 0)
    fail(video, "cannot read the streams", e);
  const AVCodec* codec = nullptr;
  const int stream = av_find_best_stream(input, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
  if (stream < 0 || !codec) fail(video, "no video stream", stream);
  CodecPtr decoder(avcodec_alloc_context3(codec));
  avcodec_parameters_to_context(decoder.get(), input->streams[stream]->codecpar);
  if (int e = avcodec_open2(decoder.get(), codec, nullptr); e < 0)
    fail(video, "cannot open the decoder", e);
  std::vector<Image> frames;
  PacketPtr packet(av_packet_alloc());
  while (av_read_frame(input, packet.get()) >= 0) {
    if (packet->stream_index == stream && avcodec_send_packet(decoder.get(), packet.get()) == 0)
      drain(decoder.get(), frames, video);
    av_packet_unref(packet.get());
  }
  avcodec_send_packet(decoder.get(), nullptr);
  drain(decoder.get(), frames, video);
  return frames;
}

void write_lossless_video(const fs::path& output, const std::vector<Image>& frames, double fps) {
  if (frames.empty()) fail(output, "no frames");
  const fs::path temporary = output.parent_path() / ("." + output.filename().string() + ".tmp");
  write_frames(temporary, frames, fps);
  const std::vector<Image> back = read_video_frames(temporary);
  bool same = back.size() == frames.size();
  for (size_t k = 0; same && k < frames.size(); ++k) {
    same = back[k].width == frames[k].width && back[k].height == frames[k].height;
    for (int y = 0; same && y < frames[k].height; ++y)
      for (int x = 0; same && x < frames[k].width; ++x)
        for (int c = 0; c < 3; ++c)
          same = same && code(back[k].at(x, y, c)) ==
                             code(frames[k].at(x, y, std::min(c, frames[k].channels - 1)));
  }
  if (!same) {
    fs::remove(temporary);
    fail(output, "the video does not decode back to its frames");
  }
  fs::rename(temporary, output);
}

}  // namespace countershade
