#pragma once

#include <memory>

#include "../aov_group.h"

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
/// ISG's image-space maps and distribution-ray-traced references (isg_group.cpp).
std::unique_ptr<AovAccumulator> make_isg_group();
/// ratio.*: the ratio estimator's U, S_N, U_N, summed and per light (ratio_group.cpp).
std::unique_ptr<AovAccumulator> make_ratio_group();
/// ratio.sto.*, ratio.cv.*: full-stochastic and control-variate estimates from the same samples.
std::unique_ptr<AovAccumulator> make_ratio_estimators_group();

}  // namespace aaf::trace
