// The I/O floor of `aaf filter` on one frame: an OpenEXR-only program that
// reads every channel of every part of an EXR as float, straight into one
// plane per channel, and writes them back with the input's channel types as
// ZIP at deflate level 1 (aaf's default, zip:1), on N OpenEXR threads.
// scripts/bench_io.sh times `aaf filter` against it, alternately.
// Usage: exr_copy_floor IN.exr OUT.exr THREADS
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfThreading.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <vector>

namespace {

/// One float plane per channel of `header`, and the slices that point into them.
Imf::FrameBuffer float_planes(const Imf::Header &header, std::vector<std::vector<float>> &planes) {
    const Imath::Box2i window = header.dataWindow();
    const std::size_t pixels =
        std::size_t(window.max.x - window.min.x + 1) * std::size_t(window.max.y - window.min.y + 1);
    Imf::FrameBuffer frame;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
        planes.emplace_back(pixels);
        frame.insert(it.name(), Imf::Slice::Make(Imf::FLOAT, planes.back().data(), window));
    }
    return frame;
}

}  // namespace

int main(int argc, char **argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: exr_copy_floor IN.exr OUT.exr THREADS\n");
        return 2;
    }
    try {
        Imf::setGlobalThreadCount(std::atoi(argv[3]));
        Imf::MultiPartInputFile input(argv[1]);
        std::vector<Imf::Header> headers;
        std::vector<std::vector<std::vector<float>>> planes(std::size_t(input.parts()));
        std::vector<Imf::FrameBuffer> frames;
        for (int part = 0; part < input.parts(); ++part) {
            Imf::Header header = input.header(part);
            frames.push_back(float_planes(header, planes[std::size_t(part)]));
            Imf::InputPart reader(input, part);
            reader.setFrameBuffer(frames.back());
            reader.readPixels(header.dataWindow().min.y, header.dataWindow().max.y);
            header.compression() = Imf::ZIP_COMPRESSION;
            header.zipCompressionLevel() = 1;
            headers.push_back(header);
        }
        Imf::MultiPartOutputFile output(argv[2], headers.data(), int(headers.size()));
        for (int part = 0; part < input.parts(); ++part) {
            Imf::OutputPart writer(output, part);
            writer.setFrameBuffer(frames[std::size_t(part)]);
            const Imath::Box2i window = headers[std::size_t(part)].dataWindow();
            writer.writePixels(window.max.y - window.min.y + 1);
        }
    } catch (const std::exception &e) {
        std::fprintf(stderr, "exr_copy_floor: %s\n", e.what());
        return 1;
    }
    return 0;
}
