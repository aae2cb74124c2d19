#include "exr_header.h"

#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfVecAttribute.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <tuple>

namespace aaf::io {

namespace {

bool same_ignoring_case(const std::string &a, const char *b) {
    const std::size_t size = std::strlen(b);
    if (a.size() != size) return false;
    for (std::size_t i = 0; i < size; ++i)
        if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i])))
            return false;
    return true;
}

/// Rank of a channel's suffix within its layer (OpenImageIO's "special"
/// names first); names not listed come after, alphabetically.
int suffix_rank(const std::string &suffix, bool xyz_layer) {
    static const char *const kUsual[] = {"R",    "Red",  "G",  "Green", "B",     "Blue", "Y",
                                         "real", "imag", "A",  "Alpha", "AR",    "RA",   "AG",
                                         "GA",   "AB",   "BA", "Z",     "Depth", "Zback"};
    static const char *const kXyz[] = {"R",  "Red", "G",    "Green", "B",  "Blue",  "X",
                                       "Y",  "Z",   "real", "imag",  "A",  "Alpha", "AR",
                                       "RA", "AG",  "GA",   "AB",    "BA", "Depth", "Zback"};
    const auto rank = [&suffix](const auto &names) {
        for (std::size_t i = 0; i < std::size(names); ++i)
            if (same_ignoring_case(suffix, names[i])) return int(i);
        return 10000;
    };
    return xyz_layer ? rank(kXyz) : rank(kUsual);
}

const std::set<std::string> &structural_attributes() {
    static const std::set<std::string> names = {
        "channels", "compression", "dataWindow", "displayWindow", "lineOrder",         "tiles",
        "type",     "name",        "version",    "chunkCount",    "maxSamplesPerPixel"};
    return names;
}

}  // namespace

std::vector<std::string> canonical_channel_order(const Imf::ChannelList &channels) {
    struct Key {
        std::string layer, suffix, name;
        int rank = 0;
    };
    std::vector<Key> keys;
    for (auto it = channels.begin(); it != channels.end(); ++it) {
        const std::string name = it.name();
        const std::size_t dot = name.rfind('.');
        keys.push_back({dot == std::string::npos ? "" : name.substr(0, dot + 1),
                        dot == std::string::npos ? name : name.substr(dot + 1), name});
    }
    // A layer holding X and Y or Z is a position or a normal: X, Y, Z in that order.
    std::map<std::string, std::pair<bool, bool>> has_x_and_yz;
    for (const Key &key : keys) {
        auto &[x, yz] = has_x_and_yz[key.layer];
        x = x || same_ignoring_case(key.suffix, "X");
        yz = yz || same_ignoring_case(key.suffix, "Y") || same_ignoring_case(key.suffix, "Z");
    }
    for (Key &key : keys) {
        const auto [x, yz] = has_x_and_yz[key.layer];
        key.rank = suffix_rank(key.suffix, x && yz);
    }
    std::sort(keys.begin(), keys.end(), [](const Key &a, const Key &b) {
        return std::tie(a.layer, a.rank, a.suffix) < std::tie(b.layer, b.rank, b.suffix);
    });
    std::vector<std::string> names;
    for (const Key &key : keys) names.push_back(key.name);
    return names;
}

void read_exr_attributes(const Imf::Header &header, AovSet &aovs) {
    for (auto it = header.begin(); it != header.end(); ++it) {
        const std::string name = it.name();
        if (structural_attributes().count(name)) continue;
        const Imf::Attribute &attribute = it.attribute();
        if (const auto *i = dynamic_cast<const Imf::IntAttribute *>(&attribute))
            aovs.attributes[name] = i->value();
        else if (const auto *f = dynamic_cast<const Imf::FloatAttribute *>(&attribute))
            aovs.attributes[name] = f->value();
        else if (const auto *s = dynamic_cast<const Imf::StringAttribute *>(&attribute))
            aovs.attributes[name] = s->value();
        else if (const auto *v = dynamic_cast<const Imf::V3fAttribute *>(&attribute))
            aovs.attributes[name] = Vec3{v->value().x, v->value().y, v->value().z};
    }
}

void write_exr_attributes(const AovSet &aovs, Imf::Header &header) {
    for (const auto &[name, value] : aovs.attributes) {
        if (structural_attributes().count(name)) continue;
        std::unique_ptr<Imf::Attribute> attribute;
        if (const int *i = std::get_if<int>(&value))
            attribute = std::make_unique<Imf::IntAttribute>(*i);
        else if (const float *f = std::get_if<float>(&value))
            attribute = std::make_unique<Imf::FloatAttribute>(*f);
        else if (const std::string *s = std::get_if<std::string>(&value))
            attribute = std::make_unique<Imf::StringAttribute>(*s);
        else if (const Vec3 *v = std::get_if<Vec3>(&value))
            attribute = std::make_unique<Imf::V3fAttribute>(Imath::V3f(v->x, v->y, v->z));
        const auto existing = header.find(name);
        if (existing != header.end() &&
            std::strcmp(existing.attribute().typeName(), attribute->typeName()) != 0)
            header.erase(name);
        header.insert(name, *attribute);
    }
}

ExrCodec exr_codec(const std::string &name) {
    const std::size_t colon = name.find(':');
    const std::string codec = name.substr(0, colon);
    ExrCodec result;
    if (colon != std::string::npos) result.zip_level = std::stoi(name.substr(colon + 1));
    static const std::map<std::string, Imf::Compression> kCodecs = {
        {"zip", Imf::ZIP_COMPRESSION},  {"zips", Imf::ZIPS_COMPRESSION}, {"piz", Imf::PIZ_COMPRESSION},
        {"rle", Imf::RLE_COMPRESSION},  {"none", Imf::NO_COMPRESSION},   {"dwaa", Imf::DWAA_COMPRESSION},
        {"dwab", Imf::DWAB_COMPRESSION}};
    result.compression = kCodecs.at(codec);
    return result;
}

}  // namespace aaf::io
