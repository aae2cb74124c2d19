#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace aaf::io {

/// One part of an OpenEXR file as its header declares it.
struct ExrPart {
    std::int64_t width = 0, height = 0;  ///< of the data window
    std::int64_t channels = 0;
    int compression = 0;                   ///< the header's code: 0 none ... 9 dwab
    std::uint32_t tile_x = 0, tile_y = 0;  ///< 0 for scan-line parts
    bool deep = false;
    std::int64_t chunk_count = -1;  ///< the chunkCount attribute (multi-part files), or -1
};

/// The headers of an OpenEXR file, read from its bytes without allocating
/// anything of the declared image size.
struct ExrHeaders {
    std::vector<ExrPart> parts;      ///< empty when the file is not OpenEXR
    std::int64_t tables_offset = 0;  ///< where the chunk offset tables start
    bool deep = false;               ///< a single-part deep file
};

/// Reads the headers of `path`. Throws aaf::InputError "<path>: <problem>"
/// when an OpenEXR header is truncated or corrupt; returns no parts for a
/// file that is not OpenEXR (OpenImageIO reads those).
ExrHeaders read_exr_headers(const std::string &path);

/// Checks that the chunk offset tables fit in the file and that every chunk
/// of every part's full-resolution level starts inside it: a truncated file,
/// one whose write was killed (zero offsets), or a header that declares far
/// more pixels than the file holds fails here, before a full-size
/// allocation. Deep parts are not checked. Throws aaf::InputError.
void check_exr_chunk_tables(const std::string &path, const ExrHeaders &headers);

}  // namespace aaf::io
