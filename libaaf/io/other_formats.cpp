#include "other_formats.h"

#include <OpenImageIO/imageio.h>
#include <sys/stat.h>

#include <algorithm>
#include <memory>
#include <new>
#include <vector>

#include "aaf/core/util/error.h"
#include "aaf/core/util/quoted.h"
#include "memory_check.h"
#include "one_line.h"
#include "quiet_stderr.h"

namespace aaf::io {

using OIIO::TypeDesc;

namespace {

/// No file of a format other than OpenEXR (whose chunk tables are checked
/// instead) can hold more than kMaxExpansion float bytes per byte of its own
/// (deflate's limit is about 1032:1 for 8-bit data, 4128:1 as float), so a
/// 26-byte header declaring gigabytes is refused before they are allocated.
void check_declared_size_against_file(const std::string &path, const OIIO::ImageSpec &spec,
                                      const std::string &format) {
    constexpr double kMaxExpansion = 8192, kSlackBytes = 64.0 * (1 << 20);
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

/// Reads every channel of the current subimage as float into `aovs`'s planes
/// (added here), through one interleaved copy: these formats are small.
void read_pixels(OIIO::ImageInput &input, const OIIO::ImageSpec &spec, AovSet &aovs,
                 const std::string &path) {
    const std::size_t channels = std::size_t(spec.nchannels), count = aovs.pixel_count();
    std::vector<float *> planes;
    for (int c = 0; c < spec.nchannels; ++c) {
        const std::string &name = spec.channelnames[c];
        if (aovs.has_channel(name)) throw InputError(path + ": duplicate channel " + quoted(name));
        planes.push_back(aovs.add_channel(name).data);
        if (spec.channelformat(c) == TypeDesc::HALF) aovs.set_precision(name, Precision::Half);
    }
    std::vector<float> pixels(count * channels);
    if (!input.read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, pixels.data()))
        throw InputError(path + ": cannot read pixels: " + pending_error(&input));
    for (std::size_t c = 0; c < channels; ++c)
        for (std::size_t i = 0; i < count; ++i) planes[c][i] = pixels[i * channels + c];
}

/// `path` opened for reading, or null (OIIO's message cleared); libpng's own
/// complaints stay off stderr.
std::unique_ptr<OIIO::ImageInput> open_quietly(const std::string &path) {
    const QuietStderr quiet_libpng(has_png_signature(path));
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) OIIO::geterror();  // clear the pending message
    return input;
}

}  // namespace

OtherImage read_other_image(const std::string &path, std::uint64_t memory_budget_bytes) {
    const QuietStderr quiet_libpng(has_png_signature(path));
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) {
        std::string message = pending_error();
        throw InputError(path + ": cannot read image" + (message.empty() ? "" : ": " + message));
    }
    const OIIO::ImageSpec &spec = input->spec();
    if (spec.deep) throw InputError(path + ": deep images are not supported");
    if (spec.depth > 1) throw InputError(path + ": volume images are not supported");
    check_memory_budget(path, spec.width, std::int64_t(spec.height) * std::max(spec.depth, 1), spec.nchannels,
                        memory_budget_bytes);
    check_declared_size_against_file(path, spec, input->format_name());
    OtherImage image;
    try {
        image.aovs = AovSet(spec.width, spec.height);
    } catch (const Error &e) {
        throw InputError(path + ": " + e.what());
    }
    try {
        read_pixels(*input, spec, image.aovs, path);
    } catch (const std::bad_alloc &) {
        throw InputError(path + ": cannot read pixels: the reader ran out of memory on a corrupt file");
    }
    read_attributes(spec, image.aovs);
    image.data_window = {spec.x, spec.y, spec.width, spec.height};
    image.display_window = {spec.full_x, spec.full_y, spec.full_width, spec.full_height};
    image.format = input->format_name();
    return image;
}

bool is_readable_other_image(const std::string &path, std::uint64_t memory_budget_bytes) {
    try {
        const QuietStderr quiet_libpng(has_png_signature(path));
        const std::unique_ptr<OIIO::ImageInput> input = open_quietly(path);
        if (!input) return false;
        bool complete = true;
        for (int part = 0; complete && input->seek_subimage(part, 0); ++part) {
            const OIIO::ImageSpec spec = input->spec();
            if (spec.deep || spec.width <= 0 || spec.height <= 0) return false;
            check_memory_budget(path, spec.width, spec.height, spec.nchannels, memory_budget_bytes);
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

std::string read_other_string_attribute(const std::string &path, const std::string &name) {
    try {
        const std::unique_ptr<OIIO::ImageInput> input = open_quietly(path);
        if (!input) return {};
        const OIIO::ParamValue *value = input->spec().find_attribute(name, OIIO::TypeString);
        return value ? std::string(value->get_string()) : std::string();
    } catch (const std::exception &) {
        return {};
    }
}

}  // namespace aaf::io
