#include "aaf/core/contract/aov_contract.h"

#include <map>
#include <type_traits>

#include "aaf/core/util/error.h"
#include "aaf/core/util/quoted.h"

namespace aaf {

const std::vector<RoleInfo> &shared_roles() {
    static const std::vector<RoleInfo> table = {
        {Role::Beauty,
         {"R", "G", "B"},
         "linear radiance",
         "final noisy image, the one a filter corrects; the tracer records what it holds in aaf:beauty "
         "(through a pinhole r(x) V(x) plus the other lights)",
         true},
        {Role::Visibility,
         {"shadow.V"},
         "[0,1]",
         "noisy light-weighted visibility: sum of l(y) f(x, y) over the samples / sum of l(y) (with samples "
         "drawn "
         "proportionally to l, the unoccluded fraction)"},
        {Role::D1,
         {"shadow.d1"},
         "metres",
         "distance of the receiver from the light's plane, along the light normal"},
        {Role::D2Min,
         {"shadow.d2min"},
         "metres, 0 = no occluder",
         "smallest light-plane distance of an occluder hit by the pixel's shadow rays (0 in both d2 channels "
         "where "
         "none was hit)"},
        {Role::D2Max,
         {"shadow.d2max"},
         "metres, 0 = no occluder",
         "largest light-plane distance of an occluder hit by the pixel's shadow rays"},
        {Role::Position, {"P.X", "P.Y", "P.Z"}, "world metres", "world position of the primary hit"},
        {Role::Normal,
         {"N.X", "N.Y", "N.Z"},
         "unit vector",
         "the normal the renderer shades with, facing the camera; the bundled tracer writes the hit "
         "triangle's "
         "geometric normal (flat per triangle: its meshes have no vertex normals), the same one it shades "
         "with"},
        {Role::ObjectId,
         {"id.object"},
         "integer stored as float, 0 = background",
         "identifier of the object hit by the primary ray"},
        {Role::SamplesPerPixel, {"pixel.spp"}, "samples", "light samples taken at the pixel"},
        {Role::PixelSize,
         {"pixel.size"},
         "metres",
         "world length one pixel covers at the receiver, foreshortening included (d of AAF Eq. 6); the "
         "tracer "
         "computes it from ray differentials: sqrt of the area of the pixel's footprint on the hit's tangent "
         "plane"},
        {Role::Unshadowed,
         {"unshadowed.R", "unshadowed.G", "unshadowed.B"},
         "linear radiance",
         "r(x) of AAF Eq. 1 for the key light, without visibility; the bundled tracer writes the full BRDF "
         "(Lambert "
         "albedo / pi plus, for a material with `specular`, the GGX lobe) for the directions to the camera "
         "and to "
         "the light's centre, times the light's colour and intensity and cos(receiver) cos(light) / r^2 "
         "towards its "
         "centre (with `--falloff`, the mean of that factor over the light)",
         true},
        {Role::FilteredVisibility,
         {"aaf.V"},
         "[0,1]",
         "output of a visibility filter (`aaf filter aaf`, `gaussian`): filtered visibility"},
        {Role::NoisyBeauty,
         {"noisy.R", "noisy.G", "noisy.B"},
         "linear radiance",
         "output of a filter that composes a new beauty: the input beauty, kept",
         true},
        {Role::FilteredBeauty,
         {"aaf.R", "aaf.G", "aaf.B"},
         "linear radiance",
         "output of `aaf filter aaf --keep-beauty`: the filtered image, the beauty left as it was",
         true},
        {Role::Depth, {"Z"}, "metres, 0 = background", "distance of the primary hit along the camera axis"},
        {Role::Albedo,
         {"albedo.R", "albedo.G", "albedo.B"},
         "[0,1]",
         "diffuse reflectance of the primary hit",
         true},
        {Role::Motion,
         {"motion.X", "motion.Y"},
         "pixels, y down",
         "raster position of the pixel's surface point in this frame minus in the previous frame (frame - 1; "
         "geometry is static, the camera moves)"},
        {Role::OtherLights,
         {"otherlights.R", "otherlights.G", "otherlights.B"},
         "linear radiance",
         "noisy shadowed shading of every light but the key light (scenes with several lights); "
         "the beauty is r(x) V(x) plus this",
         true},
        {Role::KeyLight,
         {"keylight.R", "keylight.G", "keylight.B"},
         "linear radiance",
         "another renderer's own pass of the key light alone (a light group): filtered with the method's "
         "widths and swapped into that renderer's beauty",
         true},
    };
    return table;
}

bool beauty_holds_exactly(const std::map<std::string, AttributeValue> &attributes, const char *holds) {
    const auto found = attributes.find(attr::kBeauty);
    if (found == attributes.end()) return false;
    const std::string *value = std::get_if<std::string>(&found->second);
    return value && *value == holds;
}

const std::vector<std::string> &light_attribute_names() {
    static const std::vector<std::string> names = {attr::kLightCenter, attr::kLightNormal, attr::kLightAxisU,
                                                   attr::kLightAxisV,  attr::kLightWidth,  attr::kLightHeight,
                                                   attr::kLightSigma,  attr::kLightKind};
    return names;
}

void write_light_attributes(const LightPlane &light, AovSet &aovs) {
    aovs.attributes[attr::kLightCenter] = light.center;
    aovs.attributes[attr::kLightNormal] = light.normal;
    aovs.attributes[attr::kLightAxisU] = light.axis_u;
    aovs.attributes[attr::kLightAxisV] = light.axis_v;
    aovs.attributes[attr::kLightWidth] = light.width_m;
    aovs.attributes[attr::kLightHeight] = light.height_m;
    aovs.attributes[attr::kLightSigma] = light.sigma_m;
    aovs.attributes[attr::kLightKind] = std::string(to_string(light.profile));
}

namespace {

template <typename T>
T get_attribute(const std::map<std::string, AttributeValue> &attributes, const char *name) {
    auto it = attributes.find(name);
    if (it == attributes.end()) throw InputError("missing header attribute " + quoted(name));
    if (const T *value = std::get_if<T>(&it->second)) return *value;
    if constexpr (std::is_same_v<T, float>)
        if (const int *value = std::get_if<int>(&it->second)) return float(*value);
    throw InputError("header attribute " + quoted(name) + " has the wrong type");
}

}  // namespace

LightPlane read_light_attributes(const std::map<std::string, AttributeValue> &aovs) {
    LightPlane light;
    light.center = get_attribute<Vec3>(aovs, attr::kLightCenter);
    light.normal = get_attribute<Vec3>(aovs, attr::kLightNormal);
    light.axis_u = get_attribute<Vec3>(aovs, attr::kLightAxisU);
    light.axis_v = get_attribute<Vec3>(aovs, attr::kLightAxisV);
    light.width_m = get_attribute<float>(aovs, attr::kLightWidth);
    light.height_m = get_attribute<float>(aovs, attr::kLightHeight);
    light.sigma_m = get_attribute<float>(aovs, attr::kLightSigma);
    const std::string kind = get_attribute<std::string>(aovs, attr::kLightKind);
    try {
        light.profile = light_profile_from_string(kind);
    } catch (const Error &e) {
        throw InputError("header attribute " + quoted(attr::kLightKind) + ": " + e.what());
    }
    auto name = [](const char *attribute) { return "header attribute " + quoted(attribute); };
    LightFieldNames names;
    names.center = name(attr::kLightCenter);
    names.normal = name(attr::kLightNormal);
    names.axis_u = name(attr::kLightAxisU);
    names.axis_v = name(attr::kLightAxisV);
    names.width = name(attr::kLightWidth);
    names.height = name(attr::kLightHeight);
    names.sigma = name(attr::kLightSigma);
    light.validate(names);
    return light;
}

namespace {

/// The length of the dotted prefix every name in `names` starts with, dot
/// included ("ratio.U." of ratio.U.R/G/B, "P." of P.X/Y/Z, none of R/G/B).
std::size_t shared_layer_length(const std::vector<std::string> &names) {
    std::size_t length = 0;
    const std::string &first = names.front();
    for (std::size_t dot = first.find('.'); dot != std::string::npos; dot = first.find('.', dot + 1)) {
        for (const std::string &name : names)
            if (name.size() <= dot + 1 || name.compare(0, dot + 1, first, 0, dot + 1) != 0) return length;
        length = dot + 1;
    }
    return length;
}

}  // namespace

ChannelMap::ChannelMap() {
    for (const RoleInfo &info : role_table()) names_[info.role] = info.channels;
}

void ChannelMap::set_override(const std::string &spec) {
    std::size_t eq = spec.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size())
        throw Error("bad channel mapping '" + spec + "' (expected role=channel[,channel...])");
    std::string key = spec.substr(0, eq);
    const RoleInfo *info = nullptr;
    for (const RoleInfo &candidate : role_table())
        if (key == candidate.role.key) info = &candidate;
    if (!info) {
        std::string known;
        for (const RoleInfo &candidate : role_table())
            known += std::string(known.empty() ? "" : ", ") + candidate.role.key;
        throw Error("unknown role '" + key + "' in mapping '" + spec + "' (roles: " + known + ")");
    }

    std::vector<std::string> names;
    std::string rest = spec.substr(eq + 1);
    for (std::size_t start = 0;;) {
        std::size_t comma = rest.find(',', start);
        names.push_back(rest.substr(start, comma - start));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    const std::vector<std::string> &defaults = info->channels;
    if (names.size() == 1 && defaults.size() > 1) {
        // A layer name, dotted too (Blender's ViewLayer.Position), replaces
        // the role's layer, the dotted prefix all its channels share, and
        // keeps only what follows it: P.X -> Pw.X, ratio.U.R -> myU.R.
        const std::string layer = names[0];
        const std::size_t shared = shared_layer_length(defaults);
        names.clear();
        for (const std::string &name : defaults) names.push_back(layer + "." + name.substr(shared));
    }
    if (names.size() != defaults.size())
        throw Error("mapping '" + spec + "' names " + std::to_string(names.size()) + " channels, role '" +
                    key + "' needs " + std::to_string(defaults.size()));
    for (const std::string &name : names)
        if (name.empty()) throw Error("empty channel name in mapping '" + spec + "'");
    names_[info->role] = names;
    overridden_[info->role] = true;
}

const std::vector<std::string> &ChannelMap::channels(Role role) const {
    // A role registered after this map was made has its default names.
    const auto it = names_.find(role);
    return it != names_.end() ? it->second : role_info(role).channels;
}

const std::string &ChannelMap::channel(Role role) const {
    const std::vector<std::string> &names = channels(role);
    if (names.size() != 1) throw Error(std::string("internal: role '") + role.key + "' has several channels");
    return names.front();
}

const std::vector<RoleSynonym> &shared_role_synonyms() {
    static const std::vector<RoleSynonym> table = {
        {Role::Beauty, "Blender", {"*.Combined.R", "*.Combined.G", "*.Combined.B"}},
        {Role::Beauty, "Arnold", {"RGBA.R", "RGBA.G", "RGBA.B"}},
        {Role::Position, "Blender", {"*.Position.X", "*.Position.Y", "*.Position.Z"}},
        {Role::Position, "Arnold", {"P.R", "P.G", "P.B"}},
        {Role::Position, "Houdini/Karma", {"Pw.X", "Pw.Y", "Pw.Z"}},
        {Role::Normal, "Blender", {"*.Normal.X", "*.Normal.Y", "*.Normal.Z"}},
        {Role::Normal, "Arnold", {"N.R", "N.G", "N.B"}},
        {Role::Normal, "pbrt-v4 (shading normal)", {"Ns.X", "Ns.Y", "Ns.Z"}},
        {Role::ObjectId, "Blender", {"*.IndexOB.X"}},
        {Role::Depth, "Blender", {"*.Depth.Z"}},
        // Cycles writes the previous frame's raster position minus this
        // frame's, y up: x is the contract's negated, y (down) its own.
        {Role::Motion, "Blender (Vector pass)", {"*.Vector.X", "*.Vector.Y"}, {-1.0f, 1.0f}},
        {Role::Albedo, "Blender", {"*.DiffCol.R", "*.DiffCol.G", "*.DiffCol.B"}},
        {Role::Albedo, "pbrt-v4", {"Albedo.R", "Albedo.G", "Albedo.B"}},
        {Role::Albedo, "Arnold", {"albedo.R", "albedo.G", "albedo.B"}},
        {Role::KeyLight,
         "Blender (light group 'key')",
         {"*.Combined_key.R", "*.Combined_key.G", "*.Combined_key.B"}},
        {Role::KeyLight, "Arnold (light group 'key')", {"RGBA_key.R", "RGBA_key.G", "RGBA_key.B"}},
    };
    return table;
}

std::vector<float> synonym_scale(Role role, const std::vector<std::string> &channels) {
    // A name matches a pattern whole, or after any prefix for a "*." pattern.
    const auto matches = [](const std::string &name, const std::string &pattern) {
        if (pattern.rfind("*.", 0) != 0) return name == pattern;
        const std::string tail = pattern.substr(1);
        return name.size() > tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
    };
    for (const RoleSynonym &synonym : role_synonyms()) {
        if (synonym.role != role || synonym.scale.empty() || synonym.channels.size() != channels.size())
            continue;
        bool all = true;
        for (std::size_t c = 0; c < channels.size(); ++c)
            all = all && matches(channels[c], synonym.channels[c]);
        if (all) return synonym.scale;
    }
    return std::vector<float>(channels.size(), 1.0f);
}

namespace {

/// The channels of `patterns` as `aovs` names them, or none. A "*." prefix
/// matches any prefix that completes every pattern (the first found).
std::vector<std::string> match_channels(const std::vector<std::string> &patterns, const AovSet &aovs) {
    const auto complete = [&](const std::string &prefix) {
        std::vector<std::string> names;
        for (const std::string &pattern : patterns) {
            const std::string name = prefix.empty() ? pattern : prefix + pattern.substr(1);
            if (!aovs.has_channel(name)) return std::vector<std::string>{};
            names.push_back(name);
        }
        return names;
    };
    if (patterns.front().rfind("*.", 0) != 0) return complete("");
    const std::string tail = patterns.front().substr(1);  // ".Combined.R"
    for (const std::string &name : aovs.channel_names()) {
        if (name.size() <= tail.size() || name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
            continue;
        std::vector<std::string> names = complete(name.substr(0, name.size() - tail.size()));
        if (!names.empty()) return names;
    }
    return {};
}

/// The layer of a channel name ("P" of "P.X", "isg.reflection" of
/// "isg.reflection.R"), empty for a bare name ("Z"); a synonym's "*." dropped.
std::string layer_of(const std::string &name) {
    const std::string bare = name.rfind("*.", 0) == 0 ? name.substr(2) : name;
    const std::size_t dot = bare.rfind('.');
    return dot == std::string::npos ? std::string() : bare.substr(0, dot);
}

/// True when `prefix` ("ViewLayer.") ends in a layer some role's channels
/// live in ("P.", "ViewLayer.unshadowed."): such a prefix names a pass, not
/// a view layer, and a role found under it would be another role's data.
bool is_role_layer_prefix(const std::string &prefix) {
    const auto ends_in = [&prefix](const std::string &layer) {
        const std::string tail = layer + ".";
        if (prefix == tail) return true;
        return prefix.size() > tail.size() &&
               prefix.compare(prefix.size() - tail.size(), tail.size(), tail) == 0 &&
               prefix[prefix.size() - tail.size() - 1] == '.';
    };
    for (const RoleInfo &info : role_table())
        for (const std::string &name : info.channels)
            if (const std::string layer = layer_of(name); !layer.empty() && ends_in(layer)) return true;
    for (const RoleSynonym &synonym : role_synonyms())
        for (const std::string &name : synonym.channels)
            if (const std::string layer = layer_of(name); !layer.empty() && ends_in(layer)) return true;
    return false;
}

/// The contract's `names` under the file's view-layer prefix: one that every
/// channel of `aovs` starts with (a whole file under `ViewLayer.`, as
/// Blender writes it) and that is no role's layer. None when no such prefix
/// completes them, or when several do.
std::vector<std::string> under_view_layer(const std::vector<std::string> &names, const AovSet &aovs) {
    const std::vector<std::string> &channels = aovs.channel_names();
    if (channels.empty()) return {};
    std::vector<std::string> found;
    const std::string &first = channels.front();
    for (std::size_t dot = first.find('.'); dot != std::string::npos; dot = first.find('.', dot + 1)) {
        const std::string prefix = first.substr(0, dot + 1);
        bool shared = true;
        for (const std::string &channel : channels) shared = shared && channel.rfind(prefix, 0) == 0;
        if (!shared) break;  // a longer prefix is shared by fewer channels still
        if (is_role_layer_prefix(prefix)) continue;
        std::vector<std::string> complete;
        for (const std::string &name : names)
            if (aovs.has_channel(prefix + name)) complete.push_back(prefix + name);
        if (complete.size() != names.size()) continue;
        if (!found.empty()) return {};
        found = complete;
    }
    return found;
}

}  // namespace

ChannelMap ChannelMap::resolved(const AovSet &aovs) const {
    ChannelMap map = *this;
    for (const RoleInfo &info : role_table())
        map.names_.emplace(info.role, info.channels);  // registered since
    for (auto &[role, names] : map.names_) {
        if (overridden_.count(role)) continue;
        if (!match_channels(names, aovs).empty()) continue;
        // Other renderers' names first (their pass names say what they hold),
        // then the contract's own names under the file's view-layer prefix.
        // Never another pass's channels: a missing depth Z is not P.Z, a
        // missing beauty R is not unshadowed.R.
        std::vector<std::string> found;
        for (const RoleSynonym &synonym : role_synonyms())
            if (synonym.role == role && found.empty()) found = match_channels(synonym.channels, aovs);
        if (found.empty()) found = under_view_layer(role_info(role).channels, aovs);
        if (!found.empty()) names = found;
    }
    // Blender's compositor shows only the layers under a file's view-layer
    // prefix (TOOLCHAIN.md trap 6): where the beauty is Blender's
    // PREFIX.Combined, every role found nowhere (an output to write, an input
    // still missing) is named under that prefix too.
    const std::string combined = ".Combined.R", &beauty = map.names_[Role::Beauty].front();
    if (overridden_.count(Role::Beauty) || beauty.size() <= combined.size() ||
        beauty.compare(beauty.size() - combined.size(), combined.size(), combined) != 0)
        return map;
    const std::string prefix = beauty.substr(0, beauty.size() - combined.size() + 1);  // "ViewLayer."
    for (auto &[role, names] : map.names_) {
        if (overridden_.count(role) || !match_channels(names, aovs).empty()) continue;
        for (std::string &name : names)
            if (name.compare(0, prefix.size(), prefix) != 0) name = prefix + name;
    }
    return map;
}

bool is_colour_role(Role role) {
    return role_info(role).colour;
}

std::vector<bool> colour_channels(const AovSet &aovs, const ChannelMap &map) {
    const ChannelMap found = map.resolved(aovs);
    std::map<std::string, bool> claimed;  // channel -> colour, for channels a role claims
    for (const RoleInfo &info : role_table())
        for (const std::string &name : found.channels(info.role))
            if (aovs.has_channel(name)) claimed[name] = is_colour_role(info.role);
    std::vector<bool> colour;
    for (const std::string &name : aovs.channel_names()) {
        if (auto it = claimed.find(name); it != claimed.end()) {
            colour.push_back(it->second);
            continue;
        }
        const std::size_t dot = name.rfind('.');
        const std::string suffix = dot == std::string::npos ? name : name.substr(dot + 1);
        colour.push_back(suffix == "R" || suffix == "G" || suffix == "B" || suffix == "A" || name == "Y");
    }
    return colour;
}

}  // namespace aaf
