#pragma once

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfHeader.h>

#include <string>
#include <vector>

#include "aaf/core/contract/aov_set.h"

namespace aaf::io {

/// The channels of `channels` in the order OpenImageIO 2.4 presents them
/// (the order aaf listed them in before it read OpenEXR itself): by layer
/// (the name up to its last '.'), then R, G, B (X, Y, Z in a layer that has
/// X and Y or Z), A... before the other names, alphabetically. An EXR file
/// stores its channels sorted by name, so this order is aaf's, not the file's.
std::vector<std::string> canonical_channel_order(const Imf::ChannelList &channels);

/// Reads the header's int, float, string and 3-vector (V3f) attributes into
/// `aovs.attributes`, except those that describe the file's structure
/// (channels, compression, windows, tiles, part name and type...).
void read_exr_attributes(const Imf::Header &header, AovSet &aovs);

/// Writes `aovs.attributes` into `header`, over attributes of the same name
/// (of any type); structural names are skipped.
void write_exr_attributes(const AovSet &aovs, Imf::Header &header);

/// An OpenEXR compression and its deflate level (ZIP and ZIPS only).
struct ExrCodec {
    Imf::Compression compression = Imf::ZIP_COMPRESSION;
    int zip_level = 4;
};

/// The codec of a name that is_known_compression() accepts: zip, zips,
/// zip:N, zips:N, piz, rle, none, dwaa, dwab. Plain zip and zips are level 4,
/// as OpenImageIO wrote them.
ExrCodec exr_codec(const std::string &name);

}  // namespace aaf::io
