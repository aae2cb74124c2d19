#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "aaf/io/exr_io.h"

/// Hand-made damaged EXR files for the robustness tests.
namespace aaf_test {

/// Writes `channels` channels of noise (so ZIP keeps them large), width x
/// height, as a float EXR.
inline void write_noise_exr(const std::string &path, int width, int height, int channels) {
    aaf::AovSet aovs(width, height);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> noise(0.0f, 1.0f);
    for (int c = 0; c < channels; ++c) {
        aaf::PlaneView plane = aovs.add_channel("noise." + std::to_string(c));
        for (std::size_t i = 0; i < aovs.pixel_count(); ++i) plane.data[i] = noise(rng);
    }
    aaf::io::write_aovs(aovs, path);
}

inline std::vector<char> file_bytes(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Patches the dataWindow attribute of an EXR header in place so that the
/// file declares width x height pixels (its chunks stay as they are).
inline void declare_size(const std::string &path, std::int32_t width, std::int32_t height) {
    std::vector<char> bytes = file_bytes(path);
    const std::string key("dataWindow\0box2i\0", 17);
    const auto at = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
    if (at == bytes.end()) throw std::runtime_error(path + ": no dataWindow to patch");
    std::size_t value = std::size_t(at - bytes.begin()) + key.size() + 4;  // after the int32 size
    for (std::int32_t v : {std::int32_t(0), std::int32_t(0), width - 1, height - 1})
        for (int b = 0; b < 4; ++b) bytes[value++] = char((std::uint32_t(v) >> (8 * b)) & 0xff);
    std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

/// Cuts a file to half its size, as a full disk or a killed copy leaves it.
inline void truncate_to_half(const std::string &path) {
    std::filesystem::resize_file(path, std::filesystem::file_size(path) / 2);
}

}  // namespace aaf_test
