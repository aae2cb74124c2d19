#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_set.h"
#include "aaf/io/preview.h"

namespace aaf::io {

/// What a file holds besides the channels of its first part, kept so that a
/// pipeline step can write it back unchanged: the first part's complete
/// header (attributes of every type, custom ones included, and the data and
/// display windows) and the file's other parts (EXR multi-part subimages),
/// which are copied from the source file when the output is written.
class ImageLayout {
  public:
    ImageLayout();
    ~ImageLayout();
    ImageLayout(ImageLayout &&) noexcept;
    ImageLayout &operator=(ImageLayout &&) noexcept;

    /// Parts in the source file (1 for a single-part image).
    int part_count() const;
    /// The first part's data window (where its pixels lie) and display window.
    PixelWindow data_window() const;
    PixelWindow display_window() const;
    /// OpenImageIO's name of the source file's format: "openexr", "png",
    /// "jpeg", "tiff"...; empty before a read.
    std::string format_name() const;

    struct Impl;  ///< OpenEXR details, private to aaf_io
    const Impl &impl() const { return *impl_; }
    Impl &impl() { return *impl_; }

  private:
    std::unique_ptr<Impl> impl_;
};

/// Reads every channel of the first part of an image file (OpenEXR, read by
/// OpenEXR straight into the planes; any other format OpenImageIO reads) as float (half channels are marked
/// Precision::Half, so writing them back keeps them half), with its header
/// attributes: the "aaf:" attributes and every other int, float, string or
/// 3-vector attribute. When `layout` is given it receives everything else
/// the file holds (ImageLayout). Throws aaf::InputError "<path>: <problem>"
/// when the file is missing, unreadable, deep, or has duplicate channel names.
AovSet read_aovs(const std::string &path, ImageLayout *layout = nullptr);

/// What read_aovs() reads of `path` but its pixels, for a quick look: from
/// an OpenEXR file's header alone, its first part's channels (each 0, half
/// ones marked) and attributes in a 1 x 1 set, its size and parts in
/// `layout` (data_window()); an image of another format is read whole.
/// Throws as read_aovs() does for what the header shows (a missing or
/// corrupt file, deep data, no channels, a size over the memory limit);
/// a file whose pixels are damaged passes (read_aovs() reports it).
AovSet read_aov_header(const std::string &path, ImageLayout &layout);

/// Throws aaf::InputError "<path>: not an AOV EXR (...)" when `path` is a
/// file of another format (a PNG, a JPEG): the AOVs are read from OpenEXR
/// files. A missing or unreadable path passes, for read_aovs() to report.
void require_exr_file(const std::string &path);

/// One part of a multi-part file beyond the first, as `aaf info` lists it.
struct PartSummary {
    int index = 0;
    std::string name;
    int width = 0, height = 0;
    std::vector<std::string> channels;
    std::vector<bool> half;  ///< per channel: stored as half (else float or uint)
};
/// The parts of `path` after the first (none for a single-part file).
/// Throws aaf::InputError "<path>: <problem>" when the file cannot be read.
std::vector<PartSummary> other_parts(const std::string &path, const ImageLayout &layout);

/// Adds to `aovs` (the first part of `path`, read with `layout`) the channels
/// of `wanted` that it lacks and that another part of the file holds, as
/// renderers do that write one AOV per part. Returns the names added.
/// Throws aaf::InputError "<path>: <problem>" when such a part's size differs
/// from the first part's (AOVs must share one resolution).
std::vector<std::string> add_channels_from_other_parts(const std::string &path, const ImageLayout &layout,
                                                       const std::vector<std::string> &wanted, AovSet &aovs);

/// The string attribute `name` of `path`'s first part, or "" when the file
/// cannot be opened or has no such string; reads the header only, never throws.
std::string read_string_attribute(const std::string &path, const std::string &name);

/// True when `path` exists and reads back completely: every part's header
/// and every pixel (e.g. a finished output frame, not a truncated one);
/// never throws.
bool is_readable_image(const std::string &path);

/// The memory budget for one image read, in bytes: the pixel data a file
/// declares (width x height x channels x 4 bytes, summed over the parts that
/// are read) is checked against it from the header, before anything is
/// allocated, so that a huge or corrupt header fails with aaf::InputError
/// "<path>: declares WxH with N channels (X GiB), over the memory limit of
/// Y GiB (raise with --memory-limit-gb or AAF_MEMORY_LIMIT_GB)" instead of exhausting memory.
/// The default is 16 GiB (an 8K frame, 7680x4320, of 64 float channels
/// takes 7.9 GiB), or the environment variable AAF_MEMORY_LIMIT_GB (a positive
/// number of GiB; any other value throws aaf::Error) when set.
std::uint64_t memory_budget_bytes();

/// Overrides the budget for this process (e.g. a command-line option);
/// 0 returns to the default above.
void set_memory_budget_bytes(std::uint64_t bytes);

/// OpenEXR's worker threads for reading and writing (decompression and
/// compression of its chunks): `threads`, or all hardware threads for 0 (the
/// default). A command sets it from its --threads; results never depend on it.
void set_io_threads(int threads);

/// Lossless EXR compressions, and the lossy DWA ones (colour layers only).
bool is_known_compression(const std::string &name);
bool is_lossy_compression(const std::string &name);

struct WriteOptions {
    /// Header and other parts to carry over from a source file (read_aovs).
    const ImageLayout *layout = nullptr;
    /// zip, zips, piz, rle, none, zip:N or zips:N (deflate level N in 1-9;
    /// plain zip is level 4, as OpenImageIO wrote it), or the lossy dwaa/dwab. A lossy compression
    /// applies to the colour channels only (colour_channels() of
    /// aov_contract.h): the data channels then go to a part of their own
    /// named kDataPartName, ZIP-compressed, after any carried parts. The
    /// default, zip:1, is for intermediates (renders feeding the filter): the
    /// same codec as zip for every reader, about 4 % larger, several times
    /// faster to write (scripts/bench_io.sh).
    std::string compression = "zip:1";
    /// Stores colour channels (colour_channels(): beauty, unshadowed, albedo...
    /// never P, N or Arnold's P.R) as half; data channels stay as they are.
    bool half_colour = false;
};

/// Part names when a lossy compression splits colour from data.
inline constexpr const char *kColourPartName = "rgba";
inline constexpr const char *kDataPartName = "data";

/// Writes all channels as OpenEXR, each as 32-bit float or, where
/// AovSet::precision says so, 16-bit half; and the attributes as header
/// attributes (over those of `options.layout`; no time stamp unless one is
/// carried, so equal inputs give equal bytes). The file is written under a
/// temporary name in the same directory and renamed into place, so `path`
/// never holds a half-written image. Throws aaf::InputError "<path>: <problem>".
void write_aovs(const AovSet &aovs, const std::string &path, const WriteOptions &options = {});

}  // namespace aaf::io
