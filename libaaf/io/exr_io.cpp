#include "aaf/io/exr_io.h"

#include <OpenImageIO/imageio.h>

#include <memory>
#include <vector>

#include "aaf/core/error.h"
#include "image_writer.h"

namespace aaf::io {

namespace {

using OIIO::TypeDesc;

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

}  // namespace

AovSet read_aovs(const std::string &path) {
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) {
        std::string message = OIIO::geterror();
        throw InputError(path + ": cannot read image" + (message.empty() ? "" : ": " + message));
    }
    const OIIO::ImageSpec &spec = input->spec();
    if (spec.deep) throw InputError(path + ": deep images are not supported");
    if (spec.depth > 1) throw InputError(path + ": volume images are not supported");
    const int channels = spec.nchannels;
    AovSet aovs;
    try {
        aovs = AovSet(spec.width, spec.height);
    } catch (const Error &e) {
        throw InputError(path + ": " + e.what());
    }

    std::vector<float> pixels(aovs.pixel_count() * std::size_t(channels));
    if (!input->read_image(0, 0, 0, channels, TypeDesc::FLOAT, pixels.data()))
        throw InputError(path + ": cannot read pixels: " + input->geterror());

    for (int c = 0; c < channels; ++c) {
        const std::string &name = spec.channelnames[c];
        if (aovs.has_channel(name)) throw InputError(path + ": duplicate channel '" + name + "'");
        PlaneView plane = aovs.add_channel(name);
        for (std::size_t i = 0; i < aovs.pixel_count(); ++i) plane.data[i] = pixels[i * channels + c];
        // Half channels stay half when written back.
        if (spec.channelformat(c) == TypeDesc::HALF) aovs.set_precision(name, Precision::Half);
    }
    read_attributes(spec, aovs);
    return aovs;
}

bool is_readable_image(const std::string &path) {
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path);
    if (!input) {
        OIIO::geterror();  // clear the pending message
        return false;
    }
    return input->spec().width > 0 && input->spec().height > 0;
}

void write_aovs(const AovSet &aovs, const std::string &path) {
    const int channels = int(aovs.channel_names().size());
    if (channels == 0) throw InputError(path + ": nothing to write (no channels)");
    OIIO::ImageSpec spec(aovs.width(), aovs.height(), channels, TypeDesc::FLOAT);
    spec.channelnames = aovs.channel_names();
    bool any_half = false;
    for (int c = 0; c < channels; ++c) any_half |= aovs.precision(std::size_t(c)) == Precision::Half;
    if (any_half)
        for (int c = 0; c < channels; ++c)
            spec.channelformats.push_back(aovs.precision(std::size_t(c)) == Precision::Half ? TypeDesc::HALF
                                                                                             : TypeDesc::FLOAT);
    spec.alpha_channel = -1;
    spec.attribute("compression", "zip");
    // OpenImageIO stamps the current time unless told otherwise; an empty
    // DateTime writes none, so equal inputs give byte-identical files.
    spec.attribute("DateTime", "");
    write_attributes(aovs, spec);

    std::vector<float> pixels(aovs.pixel_count() * std::size_t(channels));
    for (int c = 0; c < channels; ++c) {
        const std::vector<float> &plane = aovs.plane(std::size_t(c));
        for (std::size_t i = 0; i < aovs.pixel_count(); ++i) pixels[i * channels + c] = plane[i];
    }

    write_image_atomically(path, "openexr", spec, pixels.data());
}

}  // namespace aaf::io
