#pragma once

#include <map>
#include <string>
#include <vector>

#include "aaf/core/aov_set.h"
#include "aaf/core/light_plane.h"

namespace aaf {

/// What a channel (or group of channels) means to the filters. The one table
/// of names, units and meanings is `role_table()`; which methods read and
/// write which roles is each method's declaration (method.h).
/// libaaf/AOV_CONTRACT.md is generated from both (contract_markdown.h).
enum class Role {
    Beauty,              ///< noisy final image
    Visibility,          ///< noisy light-weighted visibility
    D1,                  ///< light-plane distance of the receiver
    D2Min,               ///< smallest light-plane distance of an occluder
    D2Max,               ///< largest light-plane distance of an occluder
    Position,            ///< world position of the primary hit
    Normal,              ///< shading normal
    ObjectId,            ///< object identifier
    SamplesPerPixel,     ///< light samples taken at the pixel
    PixelSize,           ///< world length one pixel covers at the receiver
    Unshadowed,          ///< r(x) of AAF Eq. 1
    FilteredVisibility,  ///< output: filtered visibility
    FilterWidth,         ///< output: AAF beta
    NoisyBeauty,         ///< output: the input beauty kept beside the filtered one
    FilteredBeauty,      ///< output with --keep-beauty: the filtered image beside the untouched beauty
    PlannedSpp,          ///< output of the sampling plan: total samples per pixel (AAF Eq. 21)
    Depth,               ///< distance along the camera axis
    Albedo,              ///< diffuse reflectance
    Motion,              ///< screen-space motion since the previous frame
    OtherLights,         ///< shadowed shading of every light but the key light
    MaafValueSums,       ///< MAAF: samples' light-weighted visibility times the light-side functions
    MaafUnoccludedSums,  ///< MAAF: the same with every sample unoccluded (normalisation)
    MaafWedge,           ///< MAAF: the wedge the sums were accumulated with
    HardVisibility,      ///< ISG: one shadow ray towards the key light's centre, 1 = reached it
    OccluderDistance,    ///< ISG: distance from the hit to the occluder of that ray
    Reflection,          ///< ISG: radiance along the mirror reflection
    ReflectionDistance,  ///< ISG: distance from the hit to the reflected object
    ThetaMax,            ///< ISG: the material's glossy cone half-angle
    GlossyReference,     ///< ISG: the glossy reflection by cone sampling (reference)
    PinholeBeauty,       ///< ISG: the in-focus image a pinhole camera sees
    GlossyReflection,    ///< output of isg-glossy: the filtered reflection
    Defocused,           ///< output of isg-dof: the defocused image
    RatioAnalytic,       ///< ratio estimator: analytic unshadowed direct light U (ratio estimator Eq. 20)
    RatioShadowed,       ///< ratio estimator: stochastic shadowed direct light S_N (ratio estimator Eq. 21)
    RatioUnshadowed,     ///< ratio estimator: stochastic unshadowed direct light U_N (ratio estimator Eq. 22)
    RatioShadowedLuminance,    ///< ratio estimator: luminance of S_N (grey approximation, Sec. 3.4)
    RatioUnshadowedLuminance,  ///< ratio estimator: luminance of U_N (grey approximation, Sec. 3.4)
    Maaf6Direct,               ///< MAAF 6D: noisy direct radiance (soft shadows through the lens)
    Maaf6Indirect,             ///< MAAF 6D: noisy one-bounce indirect radiance
    Maaf6DirectSums,           ///< MAAF 6D: direct radiance times the (y, u) functions, per colour
    Maaf6DirectWeights,        ///< MAAF 6D: the same functions alone (normalisation)
    Maaf6IndirectSums,         ///< MAAF 6D: indirect radiance times the (y, u) functions, per colour
    Maaf6IndirectWeights,      ///< MAAF 6D: the same functions alone (normalisation)
    Maaf6Wedge,                ///< MAAF 6D: the 3D wedges the sums were accumulated with
    Maaf6Spp,                  ///< MAAF 6D: path samples of the pixel (first pass + rest + focal-plane extra)
};

struct RoleInfo {
    Role role;
    const char *key;                    ///< spelling on the command line (--map key=...)
    std::vector<std::string> channels;  ///< default EXR channel names
    const char *units;
    const char *meaning;
};

/// N of the MAAF channels the contract lists (MAAF Sec. 6.1: 5 filters per
/// 2D subspace, 25 in 4D); the core API takes any N, the AOV layer is this one.
inline constexpr int kMaafContractPairs = 3;

/// Every role, with its default channels. Read by the I/O layer, the tracer,
/// the filters and `aaf info`; documented in libaaf/AOV_CONTRACT.md.
const std::vector<RoleInfo> &role_table();
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
inline constexpr const char *kSeed = "aaf:seed";                   // int
inline constexpr const char *kSpp = "aaf:spp";                     // int, (first-pass) samples
inline constexpr const char *kAdaptiveMu = "aaf:adaptive_mu";      // float, mu of the sampling plan
inline constexpr const char *kMaxSpp = "aaf:max_spp";              // int, adaptive cap
inline constexpr const char *kCosineFalloff = "aaf:cosine_falloff";  // int 0/1, falloff in l(y)
inline constexpr const char *kSppDone = "aaf:spp_done";              // int, samples per pixel traced so far
inline constexpr const char *kFrame = "aaf:frame";                   // float, animation time
inline constexpr const char *kSceneFile = "aaf:scene_file";          // string, the scene file rendered
inline constexpr const char *kSceneHash = "aaf:scene_hash";          // string, 16 hex digits (--resume)
inline constexpr const char *kApertureRadius = "aaf:camera:aperture_radius_m";  // float, 0 = pinhole
/// Written by the tracer's isg group (ISG's screen projections need them).
inline constexpr const char *kCameraEye = "aaf:camera:eye";           // Vec3, world metres
inline constexpr const char *kCameraFocalPx = "aaf:camera:focal_px";  // float, height / (2 tan(fov_y / 2))
inline constexpr const char *kFocusDistance = "aaf:camera:focus_distance_m";  // float, plane in focus
inline constexpr const char *kLightCount =
    "aaf:light_count";  // int, lights in the scene (light = the key light)
/// Written by the tracer's ratio group: how many lights have their own
/// ratio.L<i>.* layers beside the summed ratio.* layer (0 or absent = only the sum).
inline constexpr const char *kRatioLights = "aaf:ratio:lights";  // int
inline constexpr const char *kMaafPairs = "aaf:maaf:pairs";      // int, N of the MAAF sums
inline constexpr const char *kMaafOmegaYMax =
    "aaf:maaf:omega_y_max";  // float, rad/m, the light's Omega_y^max of the MAAF sums
/// Written by the tracer's maaf6 group (MAAF Sec. 6.2, combined effects).
inline constexpr const char *kMaaf6Pairs = "aaf:maaf6:pairs";                     // int, N of the maaf6 sums
inline constexpr const char *kMaaf6OmegaDirect = "aaf:maaf6:omega_y_direct";      // float, rad/m, light band
inline constexpr const char *kMaaf6OmegaIndirect = "aaf:maaf6:omega_y_indirect";  // float, rad, bounce band
inline constexpr const char *kMaaf6OmegaLens = "aaf:maaf6:omega_u";               // float, rad/m, 0 = pinhole
inline constexpr const char *kMaaf6Effects = "aaf:maaf6:effects";  // string, e.g. "defocus,shadows,indirect"
/// The maaf6 group's timings, handed to render_scene() in memory, which
/// moves them into trace::RenderTimings: never written to a file.
inline constexpr const char *kMaaf6SamplingS = "aaf:maaf6:sampling_s";    // float, seconds tracing paths
inline constexpr const char *kMaaf6PrefilterS = "aaf:maaf6:prefilter_s";  // float, seconds wedges + sums
}  // namespace attr

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
};
/// The synonym table (documented in libaaf/AOV_CONTRACT.md). Besides these,
/// every role's contract names are also found under the file's view-layer
/// prefix (one every channel starts with and that is no role's layer).
const std::vector<RoleSynonym> &role_synonyms();

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
