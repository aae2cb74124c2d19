#include "exr_chunk_table.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <utility>
#include <vector>

#include "aaf/core/util/error.h"
#include "aaf/core/util/quoted.h"

namespace aaf::io {

namespace {

/// A little-endian integer of the file (OpenEXR stores every number so).
template <typename T>
T little_endian(const char *bytes) {
    std::uint64_t value = 0;  // unsigned, so no shift reaches a sign bit
    for (std::size_t i = 0; i < sizeof(T); ++i)
        value |= std::uint64_t(static_cast<unsigned char>(bytes[i])) << (8 * i);
    return static_cast<T>(value);
}

/// Scan lines per chunk for each compression code of the EXR header
/// (none, rle, zips, zip, piz, pxr24, b44, b44a, dwaa, dwab).
std::int64_t lines_per_chunk(int compression) {
    static const std::int64_t lines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
    return compression >= 0 && compression < 10 ? lines[compression] : 1;
}

/// Chunks of the full-resolution level: the first entries of the part's
/// offset table (lower mip levels follow them).
std::int64_t level0_chunks(const ExrPart &part) {
    if (part.width <= 0 || part.height <= 0) return 0;
    if (part.tile_x > 0 && part.tile_y > 0)
        return ((part.width + part.tile_x - 1) / part.tile_x) *
               ((part.height + part.tile_y - 1) / part.tile_y);
    const std::int64_t lines = lines_per_chunk(part.compression);
    return (part.height + lines - 1) / lines;
}

/// Entries in a channel list attribute (chlist): each a name, then 16 bytes.
std::int64_t channel_count(const std::vector<char> &chlist) {
    std::int64_t count = 0;
    for (std::size_t at = 0; at < chlist.size() && chlist[at] != '\0'; ++count) {
        while (at < chlist.size() && chlist[at] != '\0') ++at;
        at += 1 + 16;  // the name's terminator, pixel type, pLinear, reserved, x and y sampling
    }
    return count;
}

/// Reads one header (attributes up to the empty name) into `part`; false at
/// the empty header that ends a multi-part file's list.
bool read_header(std::istream &in, ExrPart &part, const std::string &path) {
    bool first = true;
    // What OpenEXR sizes its buffers from: without them it allocates from
    // defaults (a fuzzed 830-byte header with a mangled 'channels' took 2.1 GB).
    bool has_channels = false, has_compression = false, has_data_window = false;
    for (;;) {
        std::string name, type;
        if (!std::getline(in, name, '\0')) throw InputError(path + ": truncated OpenEXR header");
        if (name.empty()) {
            if (first) return false;
            for (const auto &[present, required] : {std::pair<bool, const char *>{has_channels, "channels"},
                                                    {has_compression, "compression"},
                                                    {has_data_window, "dataWindow"}})
                if (!present)
                    throw InputError(path + ": corrupt OpenEXR header (no '" + required + "' attribute)");
            return true;
        }
        first = false;
        has_channels = has_channels || name == "channels";
        has_compression = has_compression || name == "compression";
        has_data_window = has_data_window || name == "dataWindow";
        char size_bytes[4];
        if (!std::getline(in, type, '\0') || !in.read(size_bytes, 4))
            throw InputError(path + ": truncated OpenEXR header");
        const std::int32_t size = little_endian<std::int32_t>(size_bytes);
        const bool wanted = name == "dataWindow" || name == "compression" || name == "tiles" ||
                            name == "type" || name == "chunkCount" || name == "channels";
        // The attributes read here are small: a channel list of 100000 channels is ~4 MB.
        if (size < 0 || (wanted && size > (16 << 20)))
            throw InputError(path + ": corrupt OpenEXR header (attribute " + quoted(name) + " of " +
                             std::to_string(size) + " bytes)");
        if (!wanted) {
            in.seekg(size, std::ios::cur);
            continue;
        }
        std::vector<char> value(std::size_t(size) + 1, '\0');
        if (!in.read(value.data(), size)) throw InputError(path + ": truncated OpenEXR header");
        if (name == "dataWindow" && size >= 16) {
            // box2i: x_min, y_min, x_max, y_max, inclusive
            part.width = std::int64_t(little_endian<std::int32_t>(&value[8])) -
                         little_endian<std::int32_t>(&value[0]) + 1;
            part.height = std::int64_t(little_endian<std::int32_t>(&value[12])) -
                          little_endian<std::int32_t>(&value[4]) + 1;
        } else if (name == "channels") {
            value.pop_back();  // the terminator added above
            part.channels = channel_count(value);
        } else if (name == "compression" && size >= 1) {
            part.compression = static_cast<unsigned char>(value[0]);
        } else if (name == "tiles" && size >= 8) {
            part.tile_x = little_endian<std::uint32_t>(&value[0]);
            part.tile_y = little_endian<std::uint32_t>(&value[4]);
        } else if (name == "type") {
            part.deep = std::strncmp(value.data(), "deep", 4) == 0;
        } else if (name == "chunkCount" && size >= 4) {
            part.chunk_count = little_endian<std::int32_t>(&value[0]);
        }
    }
}

}  // namespace

ExrHeaders read_exr_headers(const std::string &path) {
    ExrHeaders headers;
    std::ifstream in(path, std::ios::binary);
    char magic[8];
    if (!in.read(magic, 8) || little_endian<std::uint32_t>(magic) != 20000630u) return headers;  // not EXR
    const std::uint32_t flags = little_endian<std::uint32_t>(magic + 4);
    const bool multipart = flags & 0x1000u;
    headers.deep = flags & 0x800u;
    ExrPart part;
    while (read_header(in, part, path)) {
        headers.parts.push_back(part);
        if (!multipart) break;
        part = ExrPart{};
    }
    headers.tables_offset = in.tellg();
    return headers;
}

void check_exr_chunk_tables(const std::string &path, const ExrHeaders &headers) {
    if (headers.deep) return;
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    const std::int64_t file_size = in.tellg();
    std::int64_t position = headers.tables_offset;
    for (std::size_t p = 0; p < headers.parts.size(); ++p) {
        const ExrPart &part = headers.parts[p];
        const std::int64_t level0 = level0_chunks(part);
        const std::int64_t entries = part.chunk_count >= 0 ? part.chunk_count : level0;
        const std::int64_t checked = part.deep ? 0 : std::min(entries, level0);
        if (entries < 0 || position + entries * 8 > file_size)
            throw InputError(path + ": truncated or corrupt: the header declares " + std::to_string(entries) +
                             " chunks, more than the " + std::to_string(file_size) + "-byte file can hold");
        std::vector<char> offsets(std::size_t(checked) * 8);
        in.seekg(position);
        if (!in.read(offsets.data(), std::streamsize(offsets.size())))
            throw InputError(path + ": truncated chunk offset table");
        for (std::int64_t c = 0; c < checked; ++c) {
            const std::uint64_t offset = little_endian<std::uint64_t>(&offsets[std::size_t(c) * 8]);
            if (offset <= std::uint64_t(position) || offset >= std::uint64_t(file_size))
                throw InputError(path + ": chunk " + std::to_string(c) + " of part " + std::to_string(p) +
                                 " is missing from the " + std::to_string(file_size) +
                                 "-byte file (truncated, or its write did not finish)");
        }
        position += entries * 8;
    }
}

}  // namespace aaf::io
