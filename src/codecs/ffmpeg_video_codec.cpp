// The video codec library (codecs/video_codec.h) over libavcodec and libavformat.

#include <memory>
#include <stdexcept>
#include <string>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
}

#include "codecs/video_codec.h"

namespace countershade::codecs {
namespace {

// Failures inside the library are exceptions, turned into the interface's messages at its edge.
[[noreturn]] void fail(const std::string& what, int code = 0) {
  char text[AV_ERROR_MAX_STRING_SIZE] = "";
  if (code < 0) av_strerror(code, text, sizeof text);
  throw std::runtime_error(what + (code < 0 ? std::string(" (") + text + ")" : ""));
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

void open_muxer(Muxer& m, const std::string& file, int width, int height, double fps) {
  if (avformat_alloc_output_context2(&m.format, nullptr, "matroska", file.c_str()) < 0)
    fail("no Matroska muxer");
  m.format->flags |=
      AVFMT_FLAG_BITEXACT;  // no random ids or dates: the same frames, the same bytes
  const AVCodec* ffv1 = avcodec_find_encoder(AV_CODEC_ID_FFV1);
  if (!ffv1) fail("this libavcodec has no FFV1 encoder");
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
  if (int e = avcodec_open2(c, ffv1, nullptr); e < 0) fail("cannot open the FFV1 encoder", e);
  m.stream = avformat_new_stream(m.format, nullptr);
  avcodec_parameters_from_context(m.stream->codecpar, c);
  m.stream->time_base = c->time_base;
  if (int e = avio_open(&m.format->pb, file.c_str(), AVIO_FLAG_WRITE); e < 0)
    fail("cannot write", e);
  if (int e = avformat_write_header(m.format, nullptr); e < 0) fail("cannot write the header", e);
}

// Sends one frame (null: the end) and writes every packet the encoder has ready.
void encode(Muxer& m, const AVFrame* frame) {
  if (int e = avcodec_send_frame(m.codec.get(), frame); e < 0) fail("cannot encode", e);
  PacketPtr packet(av_packet_alloc());
  while (avcodec_receive_packet(m.codec.get(), packet.get()) == 0) {
    av_packet_rescale_ts(packet.get(), m.codec->time_base, m.stream->time_base);
    packet->stream_index = m.stream->index;
    if (int e = av_interleaved_write_frame(m.format, packet.get()); e < 0)
      fail("cannot write a frame", e);
  }
}

// Where channel c (R, G, B) of a pixel lies in FFV1's 8-bit RGB layout, B G R 0 bytes per pixel.
constexpr int kByteOf[3] = {2, 1, 0};

// An RGB frame in that layout.
FramePtr packed_frame(const RgbFrame& rgb, int64_t pts) {
  FramePtr f(av_frame_alloc());
  f->format = AV_PIX_FMT_BGR0;
  f->width = rgb.width;
  f->height = rgb.height;
  av_frame_get_buffer(f.get(), 0);
  for (int y = 0; y < rgb.height; ++y)
    for (int x = 0; x < rgb.width; ++x) {
      uint8_t* pixel = f->data[0] + y * f->linesize[0] + 4 * x;
      for (int c = 0; c < 3; ++c) pixel[kByteOf[c]] = rgb.rgb[(size_t(y) * rgb.width + x) * 3 + c];
      pixel[3] = 0;
    }
  f->pts = pts;
  return f;
}

void write_frames(const std::string& file, const std::vector<RgbFrame>& frames, double fps) {
  Muxer m;
  open_muxer(m, file, frames.front().width, frames.front().height, fps);
  for (size_t k = 0; k < frames.size(); ++k) encode(m, packed_frame(frames[k], int64_t(k)).get());
  encode(m, nullptr);
  if (int e = av_write_trailer(m.format); e < 0) fail("cannot finish", e);
}

RgbFrame rgb_of(const AVFrame* f) {
  if (f->format != AV_PIX_FMT_BGR0) fail("not an 8-bit RGB video");
  RgbFrame out{f->width, f->height, std::vector<uint8_t>(size_t(f->width) * f->height * 3)};
  for (int y = 0; y < f->height; ++y)
    for (int x = 0; x < f->width; ++x)
      for (int c = 0; c < 3; ++c)
        out.rgb[(size_t(y) * f->width + x) * 3 + c] =
            f->data[0][y * f->linesize[0] + 4 * x + kByteOf[c]];
  return out;
}

// Receives every frame the decoder has ready.
void drain(AVCodecContext* decoder, std::vector<RgbFrame>& out) {
  FramePtr frame(av_frame_alloc());
  while (avcodec_receive_frame(decoder, frame.get()) == 0) out.push_back(rgb_of(frame.get()));
}

void read_frames(const std::string& video, std::vector<RgbFrame>& frames) {
  AVFormatContext* input = nullptr;
  if (int e = avformat_open_input(&input, video.c_str(), nullptr, nullptr); e < 0)
    fail("cannot open", e);
  std::unique_ptr<AVFormatContext, void (*)(AVFormatContext*)> guard(
      input, [](AVFormatContext* c) { avformat_close_input(&c); });
  if (int e = avformat_find_stream_info(input, nullptr); e < 0) fail("cannot read the streams", e);
  const AVCodec* codec = nullptr;
  const int stream = av_find_best_stream(input, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
  if (stream < 0 || !codec) fail("no video stream", stream);
  CodecPtr decoder(avcodec_alloc_context3(codec));
  avcodec_parameters_to_context(decoder.get(), input->streams[stream]->codecpar);
  if (int e = avcodec_open2(decoder.get(), codec, nullptr); e < 0)
    fail("cannot open the decoder", e);
  PacketPtr packet(av_packet_alloc());
  while (av_read_frame(input, packet.get()) >= 0) {
    if (packet->stream_index == stream && avcodec_send_packet(decoder.get(), packet.get()) == 0)
      drain(decoder.get(), frames);
    av_packet_unref(packet.get());
  }
  avcodec_send_packet(decoder.get(), nullptr);
  drain(decoder.get(), frames);
}

class FfmpegCodec final : public VideoCodec {
 public:
  std::string write_ffv1(const std::string& path, const std::vector<RgbFrame>& frames,
                         double fps) const override {
    try {
      if (frames.empty()) fail("no frames");
      write_frames(path, frames, fps);
      return "";
    } catch (const std::exception& e) {
      return e.what();
    }
  }
  std::string read(const std::string& path, std::vector<RgbFrame>& frames) const override {
    try {
      read_frames(path, frames);
      return "";
    } catch (const std::exception& e) {
      return e.what();
    }
  }
};

}  // namespace
}  // namespace countershade::codecs

extern "C" __attribute__((visibility("default"))) void* countershade_video_codec() {
  static countershade::codecs::FfmpegCodec codec;
  return static_cast<countershade::codecs::VideoCodec*>(&codec);
}
