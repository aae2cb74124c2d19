#include "aaf/io/exr_io.h"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfTiledInputPart.h>
#include <OpenEXR/ImfTiledOutputPart.h>
#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <set>
#include <thread>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/quoted.h"
#include "aaf/io/atomic_file.h"
#include "exr_chunk_table.h"
#include "exr_header.h"
#include "formats_module.h"
#include "memory_check.h"
#include "one_line.h"
#include "quiet_stderr.h"

namespace aaf::io {

struct ImageLayout::Impl {
    std::string source_path;
    std::optional<Imf::Header>
        first_part;  ///< an OpenEXR source's first header (its pixels live in the AovSet)
    PixelWindow data, display;
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
    return impl_->data;
}
std::string ImageLayout::format_name() const {
    return impl_->format;
}
PixelWindow ImageLayout::display_window() const {
    return impl_->display;
}

namespace {

constexpr std::uint64_t kDefaultMemoryBudget = std::uint64_t(16) << 30;
std::atomic<std::uint64_t> g_memory_budget_override{0};
std::atomic<int> g_io_threads{0};

/// Sizes OpenEXR's thread pool to set_io_threads() before a read or write
/// (resizing only when the count changes: the pool's threads are reused).
void use_io_threads() {
    static std::mutex mutex;
    const int wanted = g_io_threads.load() > 0 ? g_io_threads.load()
                                               : int(std::max(1u, std::thread::hardware_concurrency()));
    const std::lock_guard<std::mutex> lock(mutex);
    if (Imf::globalThreadCount() != wanted) Imf::setGlobalThreadCount(wanted);
}

/// What OpenEXR would allocate by the header alone is checked from the
/// file's bytes before OpenEXR opens it: the first part's declared size
/// against the budget, then the chunk tables against the file's length.
/// Returns false for a file that is not OpenEXR.
bool check_before_opening(const std::string &path) {
    // Given a folder, OpenImageIO tries every format reader on it, and some
    // (libheif's) can take minutes to give up.
    struct stat info {};
    if (stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode))
        throw InputError(path + ": is a directory, not an image");
    const ExrHeaders headers = read_exr_headers(path);
    if (headers.parts.empty()) return false;
    const ExrPart &first = headers.parts.front();
    check_memory_budget(path, first.width, first.height, first.channels, memory_budget_bytes());
    check_exr_chunk_tables(path, headers);
    return true;
}

bool is_regular_file(const std::string &path) {
    struct stat info {};
    return stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode);
}

bool is_deep(const Imf::Header &header) {
    return header.hasType() && Imf::isDeepData(header.type());
}

PixelWindow window_of(const Imath::Box2i &box) {
    return {box.min.x, box.min.y, box.max.x - box.min.x + 1, box.max.y - box.min.y + 1};
}

/// Width and height of a part's data window, as 64-bit numbers (a corrupt
/// header may declare more than an int holds).
std::pair<std::int64_t, std::int64_t> size_of(const Imath::Box2i &box) {
    return {std::int64_t(box.max.x) - box.min.x + 1, std::int64_t(box.max.y) - box.min.y + 1};
}

std::string part_name(const Imf::Header &header, int part) {
    return header.hasName() ? header.name() : "#" + std::to_string(part);
}

/// Adds `names` of `header`'s part to `aovs` and a float slice for each,
/// straight into its plane, to `frame`.
void add_planes(const Imf::Header &header, const std::vector<std::string> &names, AovSet &aovs,
                Imf::FrameBuffer &frame, const std::string &path) {
    for (const std::string &name : names) {
        const Imf::Channel &channel = *header.channels().findChannel(name);
        if (channel.xSampling != 1 || channel.ySampling != 1)
            throw InputError(path + ": channel " + quoted(name) + " is subsampled (" +
                             std::to_string(channel.xSampling) + "x" + std::to_string(channel.ySampling) +
                             "), which is not supported");
        if (aovs.has_channel(name)) throw InputError(path + ": duplicate channel " + quoted(name));
        PlaneView plane = aovs.add_channel(name);
        frame.insert(name, Imf::Slice::Make(Imf::FLOAT, plane.data, header.dataWindow()));
    }
}

/// Reads the pixels of part `part` into the slices of `frame`: OpenEXR
/// converts half and uint to float and decompresses on its own threads.
void read_part(Imf::MultiPartInputFile &file, int part, const Imf::FrameBuffer &frame) {
    Imf::InputPart input(file, part);
    input.setFrameBuffer(frame);
    const Imath::Box2i window = file.header(part).dataWindow();
    input.readPixels(window.min.y, window.max.y);
}

/// The first part of an OpenEXR file as read_aovs() reads it.
AovSet read_first_part(Imf::MultiPartInputFile &file, const std::string &path) {
    const Imf::Header &header = file.header(0);
    if (is_deep(header)) throw InputError(path + ": deep images are not supported");
    const std::vector<std::string> names = canonical_channel_order(header.channels());
    if (names.empty()) throw InputError(path + ": cannot read image: no channels");
    const auto [width, height] = size_of(header.dataWindow());
    check_memory_budget(path, width, height, std::int64_t(names.size()), memory_budget_bytes());
    AovSet aovs;
    try {
        aovs = AovSet(int(width), int(height));
    } catch (const Error &e) {
        throw InputError(path + ": " + e.what());
    }
    Imf::FrameBuffer frame;
    add_planes(header, names, aovs, frame, path);
    for (const std::string &name : names)
        if (header.channels().findChannel(name)->type == Imf::HALF)
            aovs.set_precision(name, Precision::Half);  // half channels stay half when written back
    try {
        read_part(file, 0, frame);
    } catch (const std::bad_alloc &) {
        throw InputError(path + ": cannot read pixels: the reader ran out of memory on a corrupt file");
    } catch (const std::exception &e) {
        throw InputError(path + ": cannot read pixels: " + one_line(e.what()));
    }
    read_exr_attributes(header, aovs);
    return aovs;
}

/// Opens `path` with OpenEXR; its errors become aaf::InputError "<path>: cannot read image: ...".
std::unique_ptr<Imf::MultiPartInputFile> open_exr(const std::string &path) {
    try {
        return std::make_unique<Imf::MultiPartInputFile>(path.c_str());
    } catch (const std::bad_alloc &) {
        throw InputError(path + ": cannot read image: the reader ran out of memory on a corrupt file");
    } catch (const std::exception &e) {
        throw InputError(path + ": cannot read image: " + one_line(e.what()));
    }
}

/// Fills `layout` with what `file` holds besides the first part's pixels.
void carry_layout(const std::string &path, const Imf::MultiPartInputFile &file, ImageLayout &layout) {
    ImageLayout::Impl &carried = layout.impl();
    const Imf::Header &header = file.header(0);
    carried.source_path = path;
    carried.first_part = header;
    carried.data = window_of(header.dataWindow());
    carried.display = window_of(header.displayWindow());
    carried.parts = file.parts();
    carried.format = "openexr";
    for (int part = 1; part < file.parts(); ++part)
        if (is_deep(file.header(part))) throw InputError(path + ": deep parts are not supported");
}

AovSet read_exr(const std::string &path, ImageLayout *layout) {
    use_io_threads();
    const std::unique_ptr<Imf::MultiPartInputFile> file = open_exr(path);
    AovSet aovs = read_first_part(*file, path);
    if (layout) carry_layout(path, *file, *layout);
    return aovs;
}

/// read_exr() from the header alone: the channels 0 in a 1 x 1 set.
AovSet read_exr_header(const std::string &path, ImageLayout &layout) {
    const std::unique_ptr<Imf::MultiPartInputFile> file = open_exr(path);
    const Imf::Header &header = file->header(0);
    if (is_deep(header)) throw InputError(path + ": deep images are not supported");
    const std::vector<std::string> names = canonical_channel_order(header.channels());
    if (names.empty()) throw InputError(path + ": cannot read image: no channels");
    AovSet aovs(1, 1);
    for (const std::string &name : names) {
        if (aovs.has_channel(name)) throw InputError(path + ": duplicate channel " + quoted(name));
        aovs.add_channel(name);
        if (header.channels().findChannel(name)->type == Imf::HALF) aovs.set_precision(name, Precision::Half);
    }
    read_exr_attributes(header, aovs);
    carry_layout(path, *file, layout);
    return aovs;
}

AovSet read_other(const std::string &path, ImageLayout *layout) {
    OtherImage image = formats_module().read_other_image(path, memory_budget_bytes());
    if (layout) {
        ImageLayout::Impl &carried = layout->impl();
        carried.source_path = path;
        carried.first_part.reset();
        carried.data = image.data_window;
        carried.display = image.display_window;
        carried.parts = 1;
        carried.format = image.format;
    }
    return std::move(image.aovs);
}

const std::set<std::string> &lossless_compressions() {
    static const std::set<std::string> names = {"zip", "zips", "piz", "rle", "none"};
    return names;
}

/// The header of the first part to write, holding channels `in_part` of
/// `aovs`: the carried header (every attribute, windows, tiling) with these
/// channels, this set's attributes and the chosen compression.
Imf::Header first_part_header(const AovSet &aovs, const std::vector<std::size_t> &in_part,
                              const std::vector<bool> &colour, const std::string &path,
                              const WriteOptions &options) {
    Imf::Header header(aovs.width(), aovs.height());
    if (options.layout) {
        const ImageLayout::Impl &source = options.layout->impl();
        if (source.data.width != aovs.width() || source.data.height != aovs.height())
            throw InputError(path + ": internal: the carried header has another size");
        if (source.first_part) {
            // Attributes of every type, data and display windows, tiling; not
            // its channels, nor its chunk count, recounted for the new
            // compression. Copied one by one: OpenEXR 3.1's Header::erase()
            // would leak the dropped attribute.
            for (auto it = source.first_part->begin(); it != source.first_part->end(); ++it)
                if (std::strcmp(it.name(), "channels") != 0 && std::strcmp(it.name(), "chunkCount") != 0)
                    header.insert(it.name(), it.attribute());
        } else {
            const PixelWindow d = source.data, s = source.display;
            header.dataWindow() = Imath::Box2i({d.x, d.y}, {d.x + d.width - 1, d.y + d.height - 1});
            header.displayWindow() = Imath::Box2i({s.x, s.y}, {s.x + s.width - 1, s.y + s.height - 1});
        }
        if (header.hasTileDescription()) {  // the pixels written are one level: no mipmaps
            Imf::TileDescription tiles = header.tileDescription();
            tiles.mode = Imf::ONE_LEVEL;
            header.setTileDescription(tiles);
        }
    }
    for (std::size_t c : in_part) {
        const bool half = aovs.precision(c) == Precision::Half || (options.half_colour && colour[c]);
        header.channels().insert(aovs.channel_names()[c], Imf::Channel(half ? Imf::HALF : Imf::FLOAT));
    }
    write_exr_attributes(aovs, header);
    const ExrCodec codec = exr_codec(options.compression);  // over any carried from an input
    header.compression() = codec.compression;
    header.zipCompressionLevel() = codec.zip_level;
    return header;
}

/// The header of the part that keeps data channels lossless when colour is
/// written with a lossy (DWA) compression: a compression is per part in
/// OpenEXR, and DWA's DCT would also quantise data named .R/.G/.B/.Y
/// (Arnold's P.R, our N.Y).
Imf::Header data_part_header(const AovSet &aovs, const std::vector<std::size_t> &in_part,
                             const Imf::Header &first) {
    Imf::Header header(first.displayWindow(), first.dataWindow());
    for (std::size_t c : in_part) {
        const bool half = aovs.precision(c) == Precision::Half;
        header.channels().insert(aovs.channel_names()[c], Imf::Channel(half ? Imf::HALF : Imf::FLOAT));
    }
    header.setName(kDataPartName);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.zipCompressionLevel() = exr_codec("zip").zip_level;
    return header;
}

/// Every header written by a MultiPartOutputFile has a type; those of a
/// multi-part file also a unique name.
void complete_headers(std::vector<Imf::Header> &headers) {
    for (std::size_t part = 0; part < headers.size(); ++part) {
        Imf::Header &header = headers[part];
        if (headers.size() > 1 && !header.hasName())
            header.setName(part == 0 ? kColourPartName : "part" + std::to_string(part));
        if (!header.hasType())
            header.setType(header.hasTileDescription() ? Imf::TILEDIMAGE : Imf::SCANLINEIMAGE);
    }
}

/// Writes channels `in_part` of `aovs` as the pixels of part `part`: float
/// channels straight from their planes, half ones from a half copy (OpenEXR
/// converts pixel types when reading only); OpenEXR compresses on its own threads.
void write_part(Imf::MultiPartOutputFile &file, int part, const AovSet &aovs,
                const std::vector<std::size_t> &in_part) {
    const Imf::Header &header = file.header(part);
    Imf::FrameBuffer frame;
    std::vector<std::vector<half>> halves;
    halves.reserve(in_part.size());  // stable addresses for the slices
    for (std::size_t c : in_part) {
        const std::string &name = aovs.channel_names()[c];
        const AovSet::Plane &plane = aovs.plane(c);
        if (header.channels().findChannel(name)->type == Imf::HALF) {
            halves.emplace_back(plane.begin(), plane.end());  // Imath's round to nearest even
            frame.insert(name, Imf::Slice::Make(Imf::HALF, halves.back().data(), header.dataWindow()));
        } else {
            frame.insert(name, Imf::Slice::Make(Imf::FLOAT, plane.data(), header.dataWindow()));
        }
    }
    if (header.hasTileDescription()) {
        Imf::TiledOutputPart output(file, part);
        output.setFrameBuffer(frame);
        output.writeTiles(0, output.numXTiles(0) - 1, 0, output.numYTiles(0) - 1);
    } else {
        Imf::OutputPart output(file, part);
        output.setFrameBuffer(frame);
        output.writePixels(aovs.height());
    }
}

/// Copies part `part` of `source` into the same part of `file`, still
/// compressed.
void copy_part(Imf::MultiPartInputFile &source, Imf::MultiPartOutputFile &file, int part) {
    if (source.header(part).hasTileDescription()) {
        Imf::TiledInputPart input(source, part);
        Imf::TiledOutputPart output(file, part);
        output.copyPixels(input);
    } else {
        Imf::InputPart input(source, part);
        Imf::OutputPart output(file, part);
        output.copyPixels(input);
    }
}

/// Reads every pixel of part `part` (one channel's slice: OpenEXR still
/// decompresses every chunk), or throws.
void decode_part(Imf::MultiPartInputFile &file, int part, const std::string &path) {
    const Imf::Header &header = file.header(part);
    const auto [width, height] = size_of(header.dataWindow());
    const Imf::ChannelList &channels = header.channels();
    if (is_deep(header) || width <= 0 || height <= 0 || channels.begin() == channels.end())
        throw InputError(path + ": not a flat image");
    std::int64_t count = 0;
    for (auto it = channels.begin(); it != channels.end(); ++it) ++count;
    check_memory_budget(path, width, height, count, memory_budget_bytes());
    const Imf::Channel &channel = channels.begin().channel();
    std::vector<float> plane(std::size_t(width / channel.xSampling + 1) *
                             std::size_t(height / channel.ySampling + 1));
    Imf::FrameBuffer frame;
    frame.insert(channels.begin().name(), Imf::Slice::Make(Imf::FLOAT, plane.data(), header.dataWindow(), 0,
                                                           0, channel.xSampling, channel.ySampling));
    read_part(file, part, frame);
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
    return check_before_opening(path) ? read_exr(path, layout) : read_other(path, layout);
}

AovSet read_aov_header(const std::string &path, ImageLayout &layout) {
    return check_before_opening(path) ? read_exr_header(path, layout) : read_other(path, &layout);
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
    try {
        Imf::MultiPartInputFile file(path.c_str());
        for (int part = 1; part < file.parts(); ++part) {
            const Imf::Header &header = file.header(part);
            const PixelWindow window = window_of(header.dataWindow());
            PartSummary summary{part,
                                part_name(header, part),
                                window.width,
                                window.height,
                                canonical_channel_order(header.channels()),
                                {}};
            for (const std::string &name : summary.channels)
                summary.half.push_back(header.channels().findChannel(name)->type == Imf::HALF);
            parts.push_back(std::move(summary));
        }
    } catch (const std::exception &e) {
        throw InputError(path + ": cannot read image: " + one_line(e.what()));
    }
    return parts;
}

namespace {

/// The channels of part `part` that `wanted` names and `aovs` lacks.
std::vector<std::string> channels_to_borrow(const Imf::Header &header, const std::vector<std::string> &wanted,
                                            const AovSet &aovs) {
    std::vector<std::string> names;
    for (const std::string &name : canonical_channel_order(header.channels()))
        if (!aovs.has_channel(name) && std::find(wanted.begin(), wanted.end(), name) != wanted.end())
            names.push_back(name);
    return names;
}

/// Adds channels `names` of part `part` to `aovs`, read straight into their planes.
void borrow_channels(Imf::MultiPartInputFile &file, int part, const std::vector<std::string> &names,
                     AovSet &aovs, const std::string &path) {
    const Imf::Header &header = file.header(part);
    const std::string name_of_part = part_name(header, part);
    const auto [width, height] = size_of(header.dataWindow());
    for (const std::string &name : names) {
        if (width != aovs.width() || height != aovs.height())
            throw InputError(path + ": channel " + quoted(name) + " is in part " + quoted(name_of_part) +
                             " of " + std::to_string(width) + "x" + std::to_string(height) +
                             ", but the first part is " + std::to_string(aovs.width()) + "x" +
                             std::to_string(aovs.height()) + ": AOVs must share one resolution");
        check_memory_budget(path, width, height, std::int64_t(aovs.channel_names().size()) + 1,
                            memory_budget_bytes());
    }
    Imf::FrameBuffer frame;
    add_planes(header, names, aovs, frame, path);
    try {
        read_part(file, part, frame);
    } catch (const std::exception &e) {
        throw InputError(path + ": cannot read part " + quoted(name_of_part) + ": " + one_line(e.what()));
    }
}

}  // namespace

std::vector<std::string> add_channels_from_other_parts(const std::string &path, const ImageLayout &layout,
                                                       const std::vector<std::string> &wanted, AovSet &aovs) {
    std::vector<std::string> added;
    if (layout.part_count() < 2) return added;
    use_io_threads();
    std::unique_ptr<Imf::MultiPartInputFile> file;
    try {
        file = std::make_unique<Imf::MultiPartInputFile>(path.c_str());
    } catch (const std::exception &e) {
        throw InputError(path + ": cannot read image: " + one_line(e.what()));
    }
    for (int part = 1; part < file->parts(); ++part) {
        const std::vector<std::string> names = channels_to_borrow(file->header(part), wanted, aovs);
        if (names.empty()) continue;
        borrow_channels(*file, part, names, aovs, path);
        added.insert(added.end(), names.begin(), names.end());
    }
    return added;
}

std::string read_string_attribute(const std::string &path, const std::string &name) {
    try {
        if (!is_regular_file(path)) return {};  // nothing to read: no need for the formats module
        if (!check_before_opening(path)) return formats_module().read_other_string_attribute(path, name);
        const Imf::MultiPartInputFile file(path.c_str());
        const auto *value = file.header(0).findTypedAttribute<Imf::StringAttribute>(name);
        return value ? value->value() : std::string();
    } catch (const std::exception &) {
        return {};
    }
}

bool is_readable_image(const std::string &path) {
    try {
        if (!is_regular_file(path))
            return false;  // e.g. an output not written yet: no need for the formats module
        if (!check_before_opening(path))
            return formats_module().is_readable_other_image(path, memory_budget_bytes());
        use_io_threads();
        Imf::MultiPartInputFile file(path.c_str());
        // Every pixel is decoded: a truncated file has a good header.
        for (int part = 0; part < file.parts(); ++part) decode_part(file, part, path);
        return true;
    } catch (const std::exception &) {  // aaf::InputError, OpenEXR's or std::bad_alloc: not a usable frame
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

void set_io_threads(int threads) {
    g_io_threads.store(std::max(threads, 0));
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
    std::vector<Imf::Header> headers{first_part_header(aovs, first_channels, colour, path, options)};

    // The other parts of a carried source, copied one at a time.
    use_io_threads();
    std::unique_ptr<Imf::MultiPartInputFile> source;
    if (options.layout && options.layout->part_count() > 1) {
        const std::string &source_path = options.layout->impl().source_path;
        try {
            source = std::make_unique<Imf::MultiPartInputFile>(source_path.c_str());
        } catch (const std::exception &e) {
            throw InputError(source_path + ": cannot reopen to copy its other parts: " + one_line(e.what()));
        }
        for (int part = 1; part < source->parts(); ++part) headers.push_back(source->header(part));
    }
    const int data_part = int(headers.size());
    if (!data_channels.empty()) headers.push_back(data_part_header(aovs, data_channels, headers[0]));
    complete_headers(headers);

    const std::string temporary = temporary_path_for(path);
    try {
        Imf::MultiPartOutputFile file(temporary.c_str(), headers.data(), int(headers.size()), true);
        write_part(file, 0, aovs, first_channels);
        for (int part = 1; part < data_part; ++part) copy_part(*source, file, part);
        if (!data_channels.empty()) write_part(file, data_part, aovs, data_channels);
    } catch (const std::exception &e) {
        discard_temporary(temporary);
        throw InputError(path + ": cannot write: " + one_line(e.what()));
    }
    commit_temporary(temporary, path);
}

}  // namespace aaf::io
