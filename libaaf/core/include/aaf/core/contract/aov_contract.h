#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "aaf/core/contract/aov_set.h"
#include "aaf/core/contract/light_plane.h"

namespace aaf {

/// What a channel (or group of channels) means to the filters, named by its
/// key: the spelling of `--map key=...`, `aaf info` and the contract document.
/// The roles several methods and tracer groups share are declared here;
/// a method's own roles are declared in its folder (e.g. `aaf::roles::MaafWedge`
/// in maaf_roles.h) and registered with the contract through its
/// MethodInfo (method.h), so a plug-in brings its own. Roles compare by key.
/// libaaf/AOV_CONTRACT.md is generated from role_table() (contract_markdown.h).
struct Role {
    const char *key = "";

    static const Role Beauty;              ///< noisy final image
    static const Role Visibility;          ///< noisy light-weighted visibility
    static const Role D1;                  ///< light-plane distance of the receiver
    static const Role D2Min;               ///< smallest light-plane distance of an occluder
    static const Role D2Max;               ///< largest light-plane distance of an occluder
    static const Role Position;            ///< world position of the primary hit
    static const Role Normal;              ///< shading normal
    static const Role ObjectId;            ///< object identifier
    static const Role SamplesPerPixel;     ///< light samples taken at the pixel
    static const Role PixelSize;           ///< world length one pixel covers at the receiver
    static const Role Unshadowed;          ///< r(x) of AAF Eq. 1
    static const Role FilteredVisibility;  ///< output: filtered visibility
    static const Role NoisyBeauty;         ///< output: the input beauty kept beside the filtered one
    static const Role FilteredBeauty;  ///< output with --keep-beauty: the filtered image beside the beauty
    static const Role Depth;           ///< distance along the camera axis
    static const Role Albedo;          ///< diffuse reflectance
    static const Role Motion;          ///< screen-space motion since the previous frame
    static const Role OtherLights;     ///< shadowed shading of every light but the key light
    static const Role KeyLight;        ///< a renderer's own pass of the key light alone
};

inline constexpr Role Role::Beauty{"beauty"};
inline constexpr Role Role::Visibility{"visibility"};
inline constexpr Role Role::D1{"d1"};
inline constexpr Role Role::D2Min{"d2min"};
inline constexpr Role Role::D2Max{"d2max"};
inline constexpr Role Role::Position{"position"};
inline constexpr Role Role::Normal{"normal"};
inline constexpr Role Role::ObjectId{"object_id"};
inline constexpr Role Role::SamplesPerPixel{"spp"};
inline constexpr Role Role::PixelSize{"pixel_size"};
inline constexpr Role Role::Unshadowed{"unshadowed"};
inline constexpr Role Role::FilteredVisibility{"filtered_visibility"};
inline constexpr Role Role::NoisyBeauty{"noisy_beauty"};
inline constexpr Role Role::FilteredBeauty{"filtered_beauty"};
inline constexpr Role Role::Depth{"depth"};
inline constexpr Role Role::Albedo{"albedo"};
inline constexpr Role Role::Motion{"motion"};
inline constexpr Role Role::OtherLights{"other_lights"};
inline constexpr Role Role::KeyLight{"key_light"};

constexpr bool operator==(Role a, Role b) {
    return std::string_view(a.key) == std::string_view(b.key);
}
constexpr bool operator!=(Role a, Role b) {
    return !(a == b);
}
constexpr bool operator<(Role a, Role b) {
    return std::string_view(a.key) < std::string_view(b.key);
}

struct RoleInfo {
    Role role;
    std::vector<std::string> channels;  ///< default EXR channel names
    const char *units;
    const char *meaning;
    /// The channels hold colour (radiance, reflectance): what a display
    /// transform, half floats and lossy compression may touch. Positions,
    /// normals, distances, ids, counts and progressive sums are data.
    bool colour = false;
    /// Also written once per light, `ratio.` becoming `ratio.L<i>.`
    /// (ratio_layers.h), beside the sum over lights.
    bool per_light = false;
};

/// The roles declared here, shared by several methods and tracer groups.
const std::vector<RoleInfo> &shared_roles();

/// Every role: the shared ones, then each registered method's own
/// (MethodRoles::declared) in the method registry's order. Read by the I/O
/// layer, the tracer, the filters and `aaf info`; documented in
/// libaaf/AOV_CONTRACT.md. Defined by the method registry (methods/registry.cpp).
const std::vector<RoleInfo> &role_table();
/// Throws aaf::Error for a role no one declared.
const RoleInfo &role_info(Role role);

/// Per-image attributes, stored as EXR header attributes with the prefix "aaf:".
namespace attr {
inline constexpr const char *kLightCenter = "aaf:light:center";    // Vec3, world metres
inline constexpr const char *kLightNormal = "aaf:light:normal";    // Vec3, unit, emitting side
inline constexpr const char *kLightAxisU = "aaf:light:axis_u";     // Vec3, unit tangent
inline constexpr const char *kLightAxisV = "aaf:light:axis_v";     // Vec3, unit tangent
inline constexpr const char *kLightWidth = "aaf:light:width_m";    // float, extent along axis_u
inline constexpr const char *kLightHeight = "aaf:light:height_m";  // float, extent along axis_v
inline constexpr const char *kLightSigma = "aaf:light:sigma_m";    // float, Gaussian sigma before truncation
inline constexpr const char *kLightKind = "aaf:light:kind";        // "gaussian" or "uniform"
inline constexpr const char *kScene = "aaf:scene";                 // string
inline constexpr const char *kSeed = "aaf:seed";                   // int, the seed the render drew with
/// The --seed a sequence frame's aaf:seed was mixed from with its frame
/// number; absent when aaf:seed is the --seed itself.
inline constexpr const char *kBaseSeed = "aaf:base_seed";            // int
inline constexpr const char *kSpp = "aaf:spp";                       // int, (first-pass) samples
inline constexpr const char *kAdaptiveMu = "aaf:adaptive_mu";        // float, mu of the sampling plan
inline constexpr const char *kMaxSpp = "aaf:max_spp";                // int, adaptive cap
inline constexpr const char *kCosineFalloff = "aaf:cosine_falloff";  // int 0/1, falloff in l(y)
inline constexpr const char *kSppDone = "aaf:spp_done";              // int, samples per pixel traced so far
inline constexpr const char *kFrame = "aaf:frame";                   // float, animation time
inline constexpr const char *kSceneFile = "aaf:scene_file";          // string, the scene file rendered
inline constexpr const char *kSceneHash = "aaf:scene_hash";          // string, 16 hex digits (--resume)
inline constexpr const char *kApertureRadius = "aaf:camera:aperture_radius_m";  // float, 0 = pinhole
inline constexpr const char *kLightCount =
    "aaf:light_count";  // int, lights in the scene (light = the key light)
/// Written by the tracer's ratio group: how many lights have their own
/// ratio.L<i>.* layers beside the summed ratio.* layer (0 or absent = only the sum).
inline constexpr const char *kRatioLights = "aaf:ratio:lights";  // int
/// Written by the tracer: what its beauty R,G,B holds (beauty_holds).
inline constexpr const char *kBeauty = "aaf:beauty";  // string
/// Written by a tracer group that replaces the beauty R,G,B (maaf6): what
/// R,G,B then holds, comma-separated from key_light (that light alone),
/// soft_shadows or hard_shadows, defocus, indirect (one diffuse bounce).
/// Absent: the tracer's own beauty, every light's direct light with soft
/// shadows, through the lens when the camera has one.
inline constexpr const char *kBeautyEffects = "aaf:beauty_effects";  // string
}  // namespace attr

/// The values of attr::kBeauty: what the tracer's beauty is the sum of, so
/// that a filter can replace exactly the part it models.
namespace beauty_holds {
/// A pinhole render: r(x) V(x) of the key light (AAF Eq. 1, Role::Unshadowed
/// times Role::Visibility, as written) plus Role::OtherLights.
inline constexpr const char *kDirect = "unshadowed*visibility+other_lights";
/// The ratio estimator's S_N summed over the lights (ratio.S), as written.
inline constexpr const char *kRatio = "ratio.S";
/// MAAF's combined effects: maaf6.direct plus maaf6.indirect, as written.
inline constexpr const char *kMaaf6 = "maaf6.direct+maaf6.indirect";
}  // namespace beauty_holds

/// Whether `attributes` say the beauty holds `holds` (a beauty_holds value).
bool beauty_holds_exactly(const std::map<std::string, AttributeValue> &attributes, const char *holds);

void write_light_attributes(const LightPlane &light, AovSet &aovs);
/// The light's attributes (attr::kLight*), in the order read_light_attributes() reads them.
const std::vector<std::string> &light_attribute_names();
/// Throws aaf::Error naming the first missing or mistyped attribute.
LightPlane read_light_attributes(const std::map<std::string, AttributeValue> &attributes);
inline LightPlane read_light_attributes(const AovSet &aovs) {
    return read_light_attributes(aovs.attributes);
}

/// Other renderers' names for a role's channels, tried when the contract's
/// names are missing. A leading "*." stands for any prefix (a Blender view
/// layer, "ViewLayer." or "View Layer."), the same for all channels of the role.
struct RoleSynonym {
    Role role;
    const char *renderer;
    std::vector<std::string> channels;
    /// What each channel is multiplied by to follow the contract's
    /// convention (Blender's Vector pass: the previous frame minus this one
    /// in x); empty: as it is.
    std::vector<float> scale = {};
};
/// The synonym table (documented in libaaf/AOV_CONTRACT.md): the shared
/// roles' synonyms, then each registered method's (MethodRoles::synonyms).
/// Besides these, every role's contract names are also found under the
/// file's view-layer prefix (one every channel starts with and that is no
/// role's layer). Defined by the method registry, as role_table().
const std::vector<RoleSynonym> &role_synonyms();
const std::vector<RoleSynonym> &shared_role_synonyms();
/// The factors that bring `channels`, the channels a frame's `role` resolved
/// to (by a synonym, a --map or the contract's names), to the contract's
/// convention: the scale of the synonym whose names they are, else all 1.
std::vector<float> synonym_scale(Role role, const std::vector<std::string> &channels);

/// Role -> channel names, the defaults overridden by `--map role=channels`.
class ChannelMap {
  public:
    ChannelMap();

    /// Parses "role=name[,name...]". For a multi-channel role a single name
    /// is a layer: it replaces the role's layer (the dotted prefix its
    /// default channels share) and keeps what follows (`position=Pw` ->
    /// Pw.X, Pw.Y, Pw.Z; `ratio_u=myU` -> myU.R, myU.G, myU.B;
    /// `position=ViewLayer.Position` -> ViewLayer.Position.X, ...).
    /// Throws aaf::Error on a bad spec.
    void set_override(const std::string &spec);

    const std::vector<std::string> &channels(Role role) const;
    /// The single channel of a one-channel role.
    const std::string &channel(Role role) const;

    /// This map with each role that `aovs` lacks under its current names and
    /// that no --map override fixed, renamed to the first synonym `aovs` has
    /// in full (role_synonyms(), then the contract's names under the file's
    /// view-layer prefix). A role is never found in another role's layer
    /// (depth Z is not P.Z). Roles found nowhere keep their names.
    ChannelMap resolved(const AovSet &aovs) const;

  private:
    std::map<Role, std::vector<std::string>> names_;
    std::map<Role, bool> overridden_;
};

/// True for roles whose channels hold colour (radiance, reflectance): what a
/// display transform, half floats and lossy compression may touch. Positions,
/// normals, distances, ids, counts and progressive sums are data.
bool is_colour_role(Role role);

/// Which channels of `aovs` hold colour: those of a colour role as `map`
/// resolves them in `aovs`, and, among channels no role claims, names ending
/// in .R/.G/.B/.A and a bare Y (luminance). Data roles win over suffixes, so
/// Arnold's P.R is data. Indexed like aovs.channel_names().
std::vector<bool> colour_channels(const AovSet &aovs, const ChannelMap &map = ChannelMap{});

}  // namespace aaf
