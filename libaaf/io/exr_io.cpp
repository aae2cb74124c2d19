#include "aaf/io/exr_io.h"

#include <OpenImageIO/imageio.h>
#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <new>
#include <set>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/quoted.h"
#include "aaf/io/atomic_file.h"
#include "exr_chunk_table.h"
#include "one_line.h"
#include "quiet_stderr.h"

namespace aaf::io {

using OIIO::TypeDesc;

struct ImageLayout::Impl {
    std::string source_path;
    OIIO::ImageSpec first_part;  ///< header of part 0 (its pixels live in the AovSet)
    int parts = 1;
    std::string format;  ///< OpenImageIO's name of the file's format ("openexr", "png")
};

ImageLayout::ImageLayout() : impl_(std::make_unique<Impl>()) {}
ImageLayout::~ImageLayout() = default;
ImageLayout::ImageLayout(ImageLayout &&) noexcept = default;
ImageLayout &ImageLayout::operator=(ImageLayout &&) noexcept = default;
int ImageLayout::part_count() const {
    return impl_->parts;
}
PixelWindow ImageLayout::data_window() const {
    const OIIO::ImageSpec &spec = impl_->first_part;
    return {spec.x, spec.y, spec.width, spec.height};
}
std::string ImageLayout::format_name() const {
    return impl_->format;
}
PixelWindow ImageLayout::display_window() const {
    const OIIO::ImageSpec &spec = impl_->first_part;
    return {spec.full_x, spec.full_y, spec.full_width, spec.full_height};
}

namespace {

constexpr std::uint64_t kDefaultMemoryBudget = std::uint64_t(16) << 30;
std::atomic<std::uint64_t> g_memory_budget_override{0};

/// Throws aaf::InputError unless `channels` float planes of width x height
/// fit the memory budget: checked from the header, before any allocation.
void check_memory_budget(const std::string &path, std::int64_t width, std::int64_t height,
                         std::int64_t channels) {
    const double bytes = double(std::max<std::int64_t>(width, 0)) *
                         double(std::max<std::int64_t>(height, 0)) * double(channels) * 4;
    const double budget = double(memory_budget_bytes());
    if (bytes <= budget) return;
    char sizes[96];
    std::snprintf(sizes, sizeof sizes, "(%.3g GiB), over the memory limit of %.3g GiB",
                  bytes / double(1 << 30), budget / double(1 << 30));
    throw InputError(path + ": declares " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                     std::to_string(channels) + " channels " + sizes +
                     " (raise with --memory-limit-gb or AAF_MEMORY_LIMIT_GB)");
}

/// For a format other than OpenEXR (whose chunk tables are checked instead):
/// no such file can hold more than kMaxExpansion float bytes per byte of its
/// own (deflate's limit is about 1032:1 for 8-bit data, 4128:1 as float), so
/// a 26-byte header declaring gigabytes is refused before they are allocated.
void check_declared_size_against_file(const std::string &path, const OIIO::ImageSpec &spec,
                                      const std::string &format) {
    constexpr double kMaxExpansion = 8192, kSlackBytes = 64.0 * (1 << 20);
    if (format == "openexr") return;
    struct stat file {};
    const bool error = ::stat(path.c_str(), &file) != 0;
    const double file_bytes = double(file.st_size);
    const double declared = double(std::max(spec.width, 0)) * double(std::max(spec.height, 0)) *
                            double(std::max(spec.depth, 1)) * double(std::max(spec.nchannels, 0)) * 4;
    if (error || declared <= kSlackBytes || declared <= file_bytes * kMaxExpansion) return;
    throw InputError(path + ": declares " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                     " with " + std::to_string(spec.nchannels) + " channels, more than a " +
                     std::to_string(std::int64_t(file_bytes)) + "-byte " + format + " file can hold");
}

/// What OpenEXR would allocate by the header alone is checked from the
/// file's bytes before OpenImageIO opens it: the first part's declared size
/// against the budget, then the chunk tables against the file's length.
void check_before_opening(const std::string &path) {
    // Given a folder, OpenImageIO tries every format reader on it, and some
    // (libheif's) can take minutes to give up.
    struct stat info {};
    if (stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode))
        throw InputError(path + ": is a directory, not an image");
    const ExrHeaders headers = read_exr_headers(path);
    if (headers.parts.empty()) return;
    const ExrPart &first = headers.parts.front();
    check_memory_budget(path, first.width, first.height, first.channels);
    check_exr_chunk_tables(path, headers);
}

/// OpenImageIO's pending error, as one line (it may hold libpng's too).
std::string pending_error(OIIO::ImageInput *input = nullptr) {
    return one_line(input ? input->geterror() : OIIO::geterror());
}

bool is_vec3(TypeDesc type) {
    return type.basetype == TypeDesc::FLOAT && type.aggregate == TypeDesc::VEC3 && type.arraylen == 0;
}

void read_attributes(const OIIO::ImageSpec &spec, AovSet &aovs) {
    for (const OIIO::ParamValue &param : spec.extra_attribs) {
        const std::string name = param.name().string();
        const TypeDesc type = param.type();
        if (type == OIIO::TypeInt)
            aovs.attributes[name] = param.get_int();
        else if (type == OIIO::TypeFloat)
            aovs.attributes[name] = param.get_float();
        else if (type == OIIO::TypeString)
            aovs.attributes[name] = param.get_string();
        else if (is_vec3(type)) {
            const float *v = static_cast<const float *>(param.data());
            aovs.attributes[name] = Vec3{v[0], v[1], v[2]};
        }
    }
}

void write_attributes(const AovSet &aovs, OIIO::ImageSpec &spec) {
    for (const auto &[name, value] : aovs.attributes) {
        if (const int *i = std::get_if<int>(&value))
            spec.attribute(name, *i);
        else if (const float *f = std::get_if<float>(&value))
            spec.attribute(name, *f);
        else if (const std::string *s = std::get_if<std::string>(&value))
            spec.attribute(name, *s);
        else if (const Vec3 *v = std::get_if<Vec3>(&value)) {
            const float data[3] = {v->x, v->y, v->z};
            spec.attribute(name, OIIO::TypeVector, data);
        }
    }
}

const std::set<std::string> &lossless_compressions() {
    static const std::set<std::string> names = {"zip", "zips", "piz", "rle", "none"};
    return names;
}

/// The header of the first part to write, holding channels `in_part` of
/// `aovs`: the carried header (every attribute, windows) updated with these
/// channels and this set's attributes.
OIIO::ImageSpec first_part_spec(const AovSet &aovs, const std::vector<std::size_t> &in_part,
                                const std::vector<bool> &colour, const std::string &path,
                                const WriteOptions &options) {
    const int channels = int(in_part.size());
    OIIO::ImageSpec spec(aovs.width(), aovs.height(), channels, TypeDesc::FLOAT);
    if (options.layout) {
        const OIIO::ImageSpec &source = options.layout->impl().first_part;
        if (source.width != aovs.width() || source.height != aovs.height())
            throw InputError(path + ": internal: the carried header has another size");
        spec = source;  // attributes of every type, data and display windows, tiling
        spec.nchannels = channels;
        spec.set_format(TypeDesc::FLOAT);
        spec.channelformats.clear();
        spec.alpha_channel = spec.z_channel = -1;
        spec.erase_attribute("compression");
        if (!spec.find_attribute("DateTime")) spec.attribute("DateTime", "");  // no time stamp, as below
    } else {
        // OpenImageIO stamps the current time unless told otherwise; an empty
        // DateTime writes none, so equal inputs give byte-identical files.
        spec.attribute("DateTime", "");
    }
    spec.channelnames.clear();
    for (std::size_t c : in_part) spec.channelnames.push_back(aovs.channel_names()[c]);
    spec.alpha_channel = -1;
    write_attributes(aovs, spec);
    spec.attribute("compression", options.compression);  // over any carried from an input

    std::vector<TypeDesc> formats;
    bool any_half = false;
    for (std::size_t c : in_part) {
        const bool half = aovs.precision(c) == Precision::Half || (options.half_colour && colour[c]);
        formats.push_back(half ? TypeDesc::HALF : TypeDesc::FLOAT);
        any_half |= half;
    }
    if (any_half) spec.channelformats = formats;
    return spec;
}

/// The header of the part that keeps data channels lossless when colour is
/// written with a lossy (DWA) compression: a compression is per part in
/// OpenEXR, and DWA's DCT would also quantise data named .R/.G/.B/.Y
/// (Arnold's P.R, our N.Y).
OIIO::ImageSpec data_part_spec(const AovSet &aovs, const std::vector<std::size_t> &in_part,
                               const OIIO::ImageSpec &first) {
    OIIO::ImageSpec spec(aovs.width(), aovs.height(), int(in_part.size()), TypeDesc::FLOAT);
    spec.x = first.x;
    spec.y = first.y;
    spec.full_x = first.full_x;
    spec.full_y = first.full_y;
    spec.full_width = first.full_width;
    spec.full_height = first.full_height;
    spec.channelnames.clear();
    std::vector<TypeDesc> formats;
    bool any_half = false;
    for (std::size_t c : in_part) {
        spec.channelnames.push_back(aovs.channel_names()[c]);
        const bool half = aovs.precision(c) == Precision::Half;
        formats.push_back(half ? TypeDesc::HALF : TypeDesc::FLOAT);
        any_half |= half;
    }
    if (any_half) spec.channelformats = formats;
    spec.alpha_channel = -1;
    spec.attribute("oiio:subimagename", kDataPartName);
    spec.attribute("DateTime", "");
    spec.attribute("compression", "zip");
    return spec;
}

/// Rows per strip when pixels go through an interleaved buffer, in whole
/// 32-row chunks (ZIP, PIZ and DWAA): about 4 MiB of float pixels, so the
/// buffer stays small instead of holding the whole image; and, where that
/// stays within an eighth of the image, at least 128 rows (8 ZIP chunks), so
/// OpenEXR's threads have chunks to (de)compress between two (de)interleaved
/// strips. (A 3840x2160 read and write of 38 channels: 4 MiB strips are 32
/// rows, 2 chunks, and kept 2 cores 1.2x busy; 128 rows made it 1.2x faster.)
int strip_rows(int width, std::size_t channels, int height) {
    constexpr std::size_t kStripBytes = std::size_t(4) << 20, kRowMultiple = 32, kParallelRows = 128;
    const std::size_t row_bytes = std::max<std::size_t>(1, std::size_t(std::max(width, 1)) * channels * 4);
    const std::size_t by_bytes =
        std::max(kRowMultiple, kStripBytes / row_bytes / kRowMultiple * kRowMultiple);
    const std::size_t eighth = std::size_t(std::max(height, 0)) / 8 / kRowMultiple * kRowMultiple;
    const std::size_t for_threads = std::min(kParallelRows, std::max(kRowMultiple, eighth));
    return int(std::min<std::size_t>(std::max(by_bytes, for_threads), std::size_t(std::max(height, 1))));
}

/// Block of pixels (de)interleaved at a time: its interleaved floats (up to a
/// few dozen channels) stay in the L1 cache while each channel is copied.
constexpr std::size_t kBlockPixels = 256;

/// planes[c][i] = pixels[i * planes.size() + c] for i in [0, count).
void deinterleave(const float *pixels, std::size_t count, const std::vector<float *> &planes) {
    const std::size_t channels = planes.size();
    for (std::size_t begin = 0; begin < count; begin += kBlockPixels) {
        const std::size_t end = std::min(count, begin + kBlockPixels);
        for (std::size_t c = 0; c < channels; ++c) {
            float *plane = planes[c];
            const float *source = pixels + c;
            for (std::size_t i = begin; i < end; ++i) plane[i] = source[i * channels];
        }
    }
}

/// pixels[i * planes.size() + c] = planes[c][i] for i in [0, count).
void interleave(const std::vector<const float *> &planes, std::size_t count, float *pixels) {
    const std::size_t channels = planes.size();
    for (std::size_t begin = 0; begin < count; begin += kBlockPixels) {
        const std::size_t end = std::min(count, begin + kBlockPixels);
        for (std::size_t c = 0; c < channels; ++c) {
            const float *plane = planes[c];
            float *target = pixels + c;
            for (std::size_t i = begin; i < end; ++i) target[i * channels] = plane[i];
        }
    }
}

/// The pixel type to ask OpenImageIO for to get float pixels: "native"
/// (UNKNOWN) when every channel is stored as float. Asked for FLOAT instead,
/// OpenImageIO 2.4 reads into a buffer of its own and converts float to
/// float from there: a 640x480 frame of 33 float channels took 460 ms and
/// 12900 page faults to read, natively 205 ms and 2900.
TypeDesc float_request(const OIIO::ImageSpec &spec) {
    const bool all_float = spec.format == TypeDesc::FLOAT &&
                           std::all_of(spec.channelformats.begin(), spec.channelformats.end(),
                                       [](TypeDesc format) { return format == TypeDesc::FLOAT; });
    return all_float ? TypeDesc::UNKNOWN : TypeDesc::FLOAT;
}

/// Reads every channel of the current part of `input` as float into
/// `planes` (one width x height plane per channel), a strip of scanlines at
/// a time: no interleaved copy of the whole image is held.
void read_into_planes(OIIO::ImageInput &input, const OIIO::ImageSpec &spec,
                      const std::vector<float *> &planes, const std::string &path) {
    const std::size_t channels = planes.size(), width = std::size_t(spec.width);
    const TypeDesc request = float_request(spec);
    if (spec.tile_width > 0) {  // tiled: OpenImageIO assembles the tiles
        std::vector<float> pixels(width * std::size_t(spec.height) * channels);
        if (!input.read_image(0, 0, 0, int(channels), request, pixels.data()))
            throw InputError(path + ": cannot read pixels: " + pending_error(&input));
        deinterleave(pixels.data(), width * std::size_t(spec.height), planes);
        return;
    }
    const int rows = strip_rows(spec.width, channels, spec.height);
    std::vector<float> strip(width * std::size_t(rows) * channels);
    for (int row = 0; row < spec.height; row += rows) {
        const int count = std::min(rows, spec.height - row);
        if (!input.read_scanlines(0, 0, spec.y + row, spec.y + row + count, spec.z, 0, int(channels), request,
                                  strip.data()))
            throw InputError(path + ": cannot read pixels: " + pending_error(&input));
        std::vector<float *> rows_of_planes;
        for (float *plane : planes) rows_of_planes.push_back(plane + std::size_t(row) * width);
        deinterleave(strip.data(), std::size_t(count) * width, rows_of_planes);
    }
}

/// Interleaves rows [row, row + count) of channels `in_part` of `aovs` as
/// float pixels into `pixels`.
void interleave_rows(const AovSet &aovs, const std::vector<std::size_t> &in_part, int row, int count,
                     std::vector<float> &pixels) {
    const std::size_t first = std::size_t(row) * std::size_t(aovs.width()),
                      n = std::size_t(count) * std::size_t(aovs.width());
    pixels.resize(n * in_part.size());
    std::vector<const float *> planes;
    for (std::size_t c : in_part) planes.push_back(aovs.plane(c).data() + first);
    interleave(planes, n, pixels.data());
}

/// Writes channels `in_part` of `aovs` as the pixels of the output's
/// current part (opened with `spec`), a strip of scanlines at a time.
void write_pixels(const AovSet &aovs, const std::vector<std::size_t> &in_part, const OIIO::ImageSpec &spec,
                  OIIO::ImageOutput &output) {
    std::vector<float> pixels;
    if (spec.tile_width > 0) {  // tiled (carried from a tiled input): OpenImageIO cuts the tiles
        interleave_rows(aovs, in_part, 0, aovs.height(), pixels);
        if (!output.write_image(TypeDesc::FLOAT, pixels.data()))
            throw InputError(one_line(output.geterror()));
        return;
    }
    const int rows = strip_rows(aovs.width(), in_part.size(), aovs.height());
    for (int row = 0; row < aovs.height(); row += rows) {
        const int count = std::min(rows, aovs.height() - row);
        interleave_rows(aovs, in_part, row, count, pixels);
        if (!output.write_scanlines(spec.y + row, spec.y + row + count, spec.z, TypeDesc::FLOAT,
                                    pixels.data()))
            throw InputError(one_line(output.geterror()));
    }
}

/// Copies part `part` of `source` (native pixel types) into the open output.
void copy_part(OIIO::ImageInput &source, int part, OIIO::ImageOutput &output, const std::string &path) {
    const OIIO::ImageSpec spec = source.spec(part, 0);
    std::vector<unsigned char> pixels(spec.image_bytes(true));
    if (!source.read_image(part, 0, 0, spec.nchannels, TypeDesc::UNKNOWN, pixels.data()))
        throw InputError(path + ": cannot read part " + std::to_string(part) + ": " +
                         one_line(source.geterror()));
    if (!output.open(path, spec, OIIO::ImageOutput::AppendSubimage) ||
        !output.write_image(TypeDesc::UNKNOWN, pixels.data()))
        throw InputError(one_line(output.geterror()));
}

}  // namespace

bool is_known_compression(const std::string &name) {
    // zip:N and zips:N: ZIP at deflate level N (1 fastest, 9 smallest); any
    // reader decodes them as plain zip.
    const std::size_t colon = name.find(':');
    if (colon != std::string::npos) {
        const std::string codec = name.substr(0, colon), level = name.substr(colon + 1);
        return (codec == "zip" || codec == "zips") && level.size() == 1 && level[0] >= '1' && level[0] <= '9';
    }
    return lossless_compressions().count(name) || is_lossy_compression(name);
}

bool is_lossy_compression(const std::string &name) {
    return name == "dwaa" || name == "dwab";
}

AovSet read_aovs(const std::string &path, ImageLayout *layout) {
    check_before_opening(path);
    const QuietStderr quiet_libpng(has_png_signature(path));
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) {
        std::string message = pending_error();
        throw InputError(path + ": cannot read image" + (message.empty() ? "" : ": " + message));
    }
    const OIIO::ImageSpec &spec = input->spec();
    if (spec.deep) throw InputError(path + ": deep images are not supported");
    if (spec.depth > 1) throw InputError(path + ": volume images are not supported");
    const int channels = spec.nchannels;
    check_memory_budget(path, spec.width, std::int64_t(spec.height) * std::max(spec.depth, 1), channels);
    check_declared_size_against_file(path, spec, input->format_name());
    AovSet aovs;
    try {
        aovs = AovSet(spec.width, spec.height);
    } catch (const Error &e) {
        throw InputError(path + ": " + e.what());
    }

    std::vector<float *> planes;
    for (int c = 0; c < channels; ++c) {
        const std::string &name = spec.channelnames[c];
        if (aovs.has_channel(name)) throw InputError(path + ": duplicate channel " + quoted(name));
        planes.push_back(aovs.add_channel(name).data);
        // Half channels stay half when written back.
        if (spec.channelformat(c) == TypeDesc::HALF) aovs.set_precision(name, Precision::Half);
    }
    try {
        read_into_planes(*input, spec, planes, path);
    } catch (const std::bad_alloc &) {
        // OpenImageIO's scanline reader may reserve far more than the image
        // (2.5 GB for a fuzzed 1.4 KB file of 131332x4 pixels): still this file's problem.
        throw InputError(path + ": cannot read pixels: the reader ran out of memory on a corrupt file");
    }
    read_attributes(spec, aovs);
    if (layout) {
        ImageLayout::Impl &carried = layout->impl();
        carried.source_path = path;
        carried.first_part = spec;
        carried.parts = 1;
        carried.format = input->format_name();
        while (input->seek_subimage(carried.parts, 0)) {
            if (input->spec().deep) throw InputError(path + ": deep parts are not supported");
            ++carried.parts;
        }
        OIIO::geterror();  // the failed seek past the last part leaves a message
    }
    return aovs;
}

void require_exr_file(const std::string &path) {
    struct stat info {};
    if (stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode)) return;
    std::ifstream file(path, std::ios::binary);
    if (!file) return;
    char magic[4] = {};
    // OpenEXR's magic number, 20000630 as a little-endian int.
    if (file.read(magic, sizeof magic) && std::string(magic, sizeof magic) == "\x76\x2f\x31\x01") return;
    throw InputError(path + ": not an AOV EXR (" +
                     (has_png_signature(path) ? "a PNG image" : "not an OpenEXR file") +
                     "; the AOVs are read from OpenEXR files)");
}

std::vector<PartSummary> other_parts(const std::string &path, const ImageLayout &layout) {
    std::vector<PartSummary> parts;
    if (layout.part_count() < 2) return parts;
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) throw InputError(path + ": cannot read image: " + pending_error());
    for (int part = 1; part < layout.part_count(); ++part) {
        const OIIO::ImageSpec spec = input->spec(part, 0);
        parts.push_back({part, spec.get_string_attribute("name", "#" + std::to_string(part)), spec.width,
                         spec.height, spec.channelnames});
    }
    return parts;
}

std::vector<std::string> add_channels_from_other_parts(const std::string &path, const ImageLayout &layout,
                                                       const std::vector<std::string> &wanted, AovSet &aovs) {
    std::vector<std::string> added;
    if (layout.part_count() < 2) return added;
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) throw InputError(path + ": cannot read image: " + pending_error());
    for (int part = 1; part < layout.part_count(); ++part) {
        const OIIO::ImageSpec spec = input->spec(part, 0);
        const std::string part_name = spec.get_string_attribute("name", "#" + std::to_string(part));
        for (int c = 0; c < spec.nchannels; ++c) {
            const std::string &name = spec.channelnames[c];
            if (aovs.has_channel(name) || std::find(wanted.begin(), wanted.end(), name) == wanted.end())
                continue;
            if (spec.width != aovs.width() || spec.height != aovs.height())
                throw InputError(path + ": channel " + quoted(name) + " is in part " + quoted(part_name) +
                                 " of " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                                 ", but the first part is " + std::to_string(aovs.width()) + "x" +
                                 std::to_string(aovs.height()) + ": AOVs must share one resolution");
            check_memory_budget(path, spec.width, spec.height, std::int64_t(aovs.channel_names().size()) + 1);
            std::vector<float> values(aovs.pixel_count());
            if (!input->read_image(part, 0, c, c + 1, TypeDesc::FLOAT, values.data()))
                throw InputError(path + ": cannot read part " + quoted(part_name) + ": " +
                                 pending_error(input.get()));
            PlaneView plane = aovs.add_channel(name);
            std::copy(values.begin(), values.end(), plane.data);
            added.push_back(name);
        }
    }
    return added;
}

namespace {

/// `path` opened for reading, or null (OIIO's message cleared); libpng's own
/// complaints stay off stderr. Throws as check_before_opening().
std::unique_ptr<OIIO::ImageInput> open_quietly(const std::string &path) {
    check_before_opening(path);
    const QuietStderr quiet_libpng(has_png_signature(path));
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) OIIO::geterror();  // clear the pending message
    return input;
}

}  // namespace

std::string read_string_attribute(const std::string &path, const std::string &name) {
    try {
        const std::unique_ptr<OIIO::ImageInput> input = open_quietly(path);
        if (!input) return {};
        const OIIO::ParamValue *value = input->spec().find_attribute(name, OIIO::TypeString);
        return value ? std::string(value->get_string()) : std::string();
    } catch (const std::exception &) {
        return {};
    }
}

bool is_readable_image(const std::string &path) {
    try {
        const QuietStderr quiet_libpng(has_png_signature(path));
        const std::unique_ptr<OIIO::ImageInput> input = open_quietly(path);
        if (!input) return false;
        bool complete = true;
        for (int part = 0; complete && input->seek_subimage(part, 0); ++part) {
            const OIIO::ImageSpec spec = input->spec();
            if (spec.deep || spec.width <= 0 || spec.height <= 0) return false;
            check_memory_budget(path, spec.width, spec.height, spec.nchannels);
            check_declared_size_against_file(path, spec, input->format_name());
            // Every pixel is decoded: a truncated file has a good header.
            std::vector<unsigned char> scratch(spec.image_bytes(true));
            complete = input->read_image(part, 0, 0, spec.nchannels, TypeDesc::UNKNOWN, scratch.data());
        }
        input->geterror();  // the failed seek past the last part, or the read error
        OIIO::geterror();
        return complete;
    } catch (const std::exception &) {  // aaf::InputError or std::bad_alloc: not a usable frame
        return false;
    }
}

std::uint64_t memory_budget_bytes() {
    if (const std::uint64_t set = g_memory_budget_override.load()) return set;
    const char *text = std::getenv("AAF_MEMORY_LIMIT_GB");
    if (!text || !*text) return kDefaultMemoryBudget;
    char *end = nullptr;
    const double gib = std::strtod(text, &end);
    if (*end != '\0' || !(gib > 0) || !(gib < 1e9))
        throw Error("AAF_MEMORY_LIMIT_GB: " + quoted(text) + " is not a positive number of GiB");
    return std::uint64_t(std::ceil(gib * double(1 << 30)));
}

void set_memory_budget_bytes(std::uint64_t bytes) {
    g_memory_budget_override.store(bytes);
}

void write_aovs(const AovSet &aovs, const std::string &path, const WriteOptions &options) {
    const int channels = int(aovs.channel_names().size());
    if (channels == 0) throw InputError(path + ": nothing to write (no channels)");
    if (!is_known_compression(options.compression))
        throw InputError(path + ": unknown compression '" + options.compression + "'");
    // Which channels go where: everything in the first part, unless a lossy
    // compression must leave the data channels to a lossless part of their own.
    const std::vector<bool> colour = colour_channels(aovs);
    std::vector<std::size_t> first_channels, data_channels;
    const bool lossy = is_lossy_compression(options.compression);
    for (std::size_t c = 0; c < colour.size(); ++c)
        (lossy && !colour[c] ? data_channels : first_channels).push_back(c);
    if (first_channels.empty())
        throw InputError(path + ": " + options.compression +
                         " is lossy and only for colour layers, and there is no colour to write "
                         "(use a lossless compression)");
    const OIIO::ImageSpec spec = first_part_spec(aovs, first_channels, colour, path, options);

    // The other parts of a carried source, copied one at a time.
    std::unique_ptr<OIIO::ImageInput> source;
    std::vector<OIIO::ImageSpec> specs{spec};
    if (options.layout && options.layout->part_count() > 1) {
        const std::string &source_path = options.layout->impl().source_path;
        source = OIIO::ImageInput::open(source_path);
        if (!source)
            throw InputError(source_path + ": cannot reopen to copy its other parts: " + pending_error());
        for (int part = 1; part < options.layout->part_count(); ++part)
            specs.push_back(source->spec(part, 0));
    }
    const std::size_t data_part = specs.size();
    if (!data_channels.empty()) {
        specs[0].attribute("oiio:subimagename",
                           specs[0].get_string_attribute("oiio:subimagename", kColourPartName));
        specs.push_back(data_part_spec(aovs, data_channels, specs[0]));
    }

    const std::string temporary = temporary_path_for(path);
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create("openexr");
    if (!output) throw InputError(path + ": no OpenEXR writer: " + pending_error());
    try {
        const bool opened = specs.size() == 1 ? output->open(temporary, spec)
                                              : output->open(temporary, int(specs.size()), specs.data());
        if (!opened) throw InputError(one_line(output->geterror()));
        write_pixels(aovs, first_channels, spec, *output);
        for (int part = 1; part < int(data_part); ++part) copy_part(*source, part, *output, temporary);
        if (!data_channels.empty()) {
            if (!output->open(temporary, specs[data_part], OIIO::ImageOutput::AppendSubimage))
                throw InputError(one_line(output->geterror()));
            write_pixels(aovs, data_channels, specs[data_part], *output);
        }
        if (!output->close()) throw InputError(one_line(output->geterror()));
    } catch (const InputError &e) {
        output.reset();
        discard_temporary(temporary);
        throw InputError(path + ": cannot write: " + e.what());
    }
    commit_temporary(temporary, path);
}

}  // namespace aaf::io
