#pragma once

#include <memory>

#include "../aov_group.h"
#include "../path_sample.h"

/// The tracer's AOV groups, one accumulator each (aov_group.h); the
/// registry in aov_group.cpp lists them in channel order.
namespace aaf::trace {

/// R, G, B: r(x) V(x) plus the other lights' shading (AAF Eq. 1), or with a
/// thin lens the lens rays' radiance.
std::unique_ptr<AovAccumulator> make_beauty_group();
/// shadow.*, pixel.spp, pixel.size and otherlights.*: the key light's shadow.
std::unique_ptr<AovAccumulator> make_shadow_group();
/// One value of the primary hit per pixel (primary_hit_groups.cpp).
std::unique_ptr<AovAccumulator> make_position_group();
std::unique_ptr<AovAccumulator> make_normal_group();
std::unique_ptr<AovAccumulator> make_object_id_group();
std::unique_ptr<AovAccumulator> make_unshadowed_group();
std::unique_ptr<AovAccumulator> make_depth_group();
std::unique_ptr<AovAccumulator> make_albedo_group();
/// motion.X/Y: screen motion since the previous frame.
std::unique_ptr<AovAccumulator> make_motion_group();
/// progress.*: the sums a resumed render continues from.
std::unique_ptr<AovAccumulator> make_progress_group();
/// maaf.*: MAAF's light-side sums and wedges (maaf_group.cpp).
std::unique_ptr<AovAccumulator> make_maaf_group();
/// The maaf group's settings, each declared once by maaf_group_parameters().
struct MaafGroupSettings {
    int first_pass_spp = 16;  ///< samples of its own first pass; MAAF Sec. 6.2 "Sampling" takes 16
};
const ParameterDeclarations<MaafGroupSettings> &maaf_group_parameters();
/// ISG's image-space maps and distribution-ray-traced references (isg_group.cpp).
std::unique_ptr<AovAccumulator> make_isg_group();
/// ratio.*: the ratio estimator's U, S_N, U_N, summed and per light (ratio_group.cpp).
std::unique_ptr<AovAccumulator> make_ratio_group();
/// ratio.sto.*, ratio.cv.*: full-stochastic and control-variate estimates from the same samples.
std::unique_ptr<AovAccumulator> make_ratio_estimators_group();
/// maaf6.*: MAAF for combined effects, path samples of its own (maaf6_group.cpp).
std::unique_ptr<AovAccumulator> make_maaf6_group();
/// The maaf6 group's settings, each declared once by maaf6_group_parameters().
struct Maaf6GroupSettings {
    unsigned effects = kMaaf6Defocus | kMaaf6Shadows | kMaaf6Indirect;  ///< what its path samples trace
};
const ParameterDeclarations<Maaf6GroupSettings> &maaf6_group_parameters();

}  // namespace aaf::trace
