// Blending a filtered frame with its filtered neighbours in time: motion
// followed frame to frame, disocclusion rejected by geometry, changes of
// shading rejected against the residual noise.
#include "aaf/core/framework/temporal_window.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>

#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"

namespace aaf {

namespace {

/// Values closer than this, relative, are the same value: a noise-free
/// pixel's per-frame results may differ in their last bits.
constexpr float kSameValueRelative = 1e-5f;
/// Two values of a frame closer than this fraction of their layer's mean
/// magnitude are the same value when telling a noise-free pixel.
constexpr double kSameValueFloor = 1e-4;
constexpr float kNoValue = std::numeric_limits<float>::quiet_NaN();

/// The window's frames by offset; the centre's is 0.
using FramesByOffset = std::map<int, const TemporalFrameView *>;

void check_view(ConstPlaneView view, int width, int height, bool optional, const std::string &what) {
    if (optional && !view.valid()) return;
    if (!view.valid() || view.width != width || view.height != height)
        throw Error("temporal window: " + what + " is missing or has another size");
}

void check_frame(const TemporalFrameView &frame, std::size_t value_count, int width, int height) {
    const std::string which =
        "frame " + std::string(frame.offset >= 0 ? "+" : "") + std::to_string(frame.offset);
    if (frame.values.size() != value_count)
        throw Error("temporal window: " + which + " has another number of layers to blend");
    for (ConstPlaneView view : frame.values) check_view(view, width, height, false, which + "'s values");
    for (int c = 0; c < 3; ++c) {
        check_view(frame.position[c], width, height, false, which + "'s position");
        check_view(frame.normal[c], width, height, false, which + "'s normal");
    }
    for (int c = 0; c < 2; ++c) check_view(frame.motion[c], width, height, false, which + "'s motion");
    check_view(frame.object_id, width, height, true, which + "'s object id");
    check_view(frame.pixel_size_m, width, height, true, which + "'s pixel size");
}

/// Bilinear lookup at raster position (fx, fy), pixel centres at integers;
/// NaN outside the image.
float bilinear(ConstPlaneView view, float fx, float fy) {
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    if (x0 < 0 || y0 < 0 || x0 + 1 >= view.width || y0 + 1 >= view.height) {
        const int x = int(std::lround(fx)), y = int(std::lround(fy));
        if (x < 0 || y < 0 || x >= view.width || y >= view.height) return kNoValue;
        return view(x, y);
    }
    const float ax = fx - float(x0), ay = fy - float(y0);
    return (1 - ay) * ((1 - ax) * view(x0, y0) + ax * view(x0 + 1, y0)) +
           ay * ((1 - ax) * view(x0, y0 + 1) + ax * view(x0 + 1, y0 + 1));
}

/// Where the centre's pixel (x, y) lies in the frame at `offset`, following
/// each frame's motion (this frame minus the previous one) from frame to
/// frame; false when a frame between is missing or the point leaves the image.
bool follow_motion(const FramesByOffset &frames, int x, int y, int offset, float &fx, float &fy) {
    fx = float(x);
    fy = float(y);
    const int step = offset < 0 ? -1 : 1;
    for (int k = step; k != offset + step; k += step) {
        // Backward: frame k+1's motion at the point takes it to frame k.
        // Forward: frame k's motion, read where the point will be, takes it back.
        const auto motion_frame = frames.find(step < 0 ? k + 1 : k);
        if (motion_frame == frames.end() || !frames.count(k)) return false;
        const std::array<ConstPlaneView, 2> &motion = motion_frame->second->motion;
        float mx = bilinear(motion[0], fx, fy), my = bilinear(motion[1], fx, fy);
        if (!std::isfinite(mx + my)) return false;
        if (step > 0) {  // one fixed-point step: the motion where the point lands
            const float tx = bilinear(motion[0], fx + mx, fy + my),
                        ty = bilinear(motion[1], fx + mx, fy + my);
            if (std::isfinite(tx + ty)) mx = tx, my = ty;
        }
        fx += float(step) * mx;
        fy += float(step) * my;
        if (!(fx > -0.5f && fy > -0.5f && fx < float(motion[0].width) - 0.5f &&
              fy < float(motion[0].height) - 0.5f))
            return false;
    }
    return true;
}

/// World length one pixel covers at (x, y): the pixel-size layer, or the
/// distance to the farther of its right (left) and lower (upper) neighbours' positions.
float footprint_m(const TemporalFrameView &frame, int x, int y) {
    if (frame.pixel_size_m.valid()) return frame.pixel_size_m(x, y);
    const int width = frame.position[0].width, height = frame.position[0].height;
    const int nx = x + 1 < width ? x + 1 : x - 1, ny = y + 1 < height ? y + 1 : y - 1;
    float widest = 0;
    for (const auto &[ox, oy] : {std::pair<int, int>{nx, y}, std::pair<int, int>{x, ny}}) {
        if (ox < 0 || oy < 0) continue;
        float d2 = 0;
        for (int c = 0; c < 3; ++c) {
            const float d = frame.position[c](ox, oy) - frame.position[c](x, y);
            d2 += d * d;
        }
        widest = std::max(widest, std::sqrt(d2));
    }
    return widest;
}

/// Calls `visit(tx, ty, w)` for each of the 4 taps around (fx, fy) in
/// `neighbour` that lie on the centre pixel's surface (tangent plane,
/// normal, object id) and hold finite values, w its bilinear weight.
template <typename Visit>
void same_surface_taps(const TemporalFrameView &centre, const TemporalFrameView &neighbour, float fx,
                       float fy, int x, int y, float scale, float min_cos,
                       const TemporalWindowSettings &settings, const Visit &visit) {
    const float p[3] = {centre.position[0](x, y), centre.position[1](x, y), centre.position[2](x, y)};
    const float n[3] = {centre.normal[0](x, y), centre.normal[1](x, y), centre.normal[2](x, y)};
    const float id = centre.object_id.valid() ? centre.object_id(x, y) : 0.0f;
    const float n_len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const int width = centre.position[0].width, height = centre.position[0].height;
    const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    const float ax = fx - float(x0), ay = fy - float(y0);
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            const int tx = x0 + i, ty = y0 + j;
            const float w = (i ? ax : 1 - ax) * (j ? ay : 1 - ay);
            if (w <= 0 || tx < 0 || ty < 0 || tx >= width || ty >= height) continue;
            const float q[3] = {neighbour.position[0](tx, ty), neighbour.position[1](tx, ty),
                                neighbour.position[2](tx, ty)};
            const float m[3] = {neighbour.normal[0](tx, ty), neighbour.normal[1](tx, ty),
                                neighbour.normal[2](tx, ty)};
            if (!std::isfinite(q[0] + q[1] + q[2] + m[0] + m[1] + m[2])) continue;
            // Disocclusion: the neighbour's surface must lie on this pixel's tangent plane, ...
            const float d = (q[0] - p[0]) * n[0] + (q[1] - p[1]) * n[1] + (q[2] - p[2]) * n[2];
            if (!(std::fabs(d) <= settings.plane_tolerance * scale * n_len)) continue;
            // ... face the same way ...
            const float m_len = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
            if (!(m_len > 0) || (n[0] * m[0] + n[1] * m[1] + n[2] * m[2]) < min_cos * n_len * m_len) continue;
            // ... and belong to the same object.
            if (neighbour.object_id.valid() && centre.object_id.valid() && neighbour.object_id(tx, ty) != id)
                continue;
            bool finite = true;
            for (ConstPlaneView values : neighbour.values) finite = finite && std::isfinite(values(tx, ty));
            if (finite) visit(tx, ty, w);
        }
}

/// What the neighbour holds at the centre pixel's surface point: its
/// values bilinearly over the taps on the same surface, false when none is.
bool neighbour_values(const TemporalFrameView &centre, const TemporalFrameView &neighbour, float fx, float fy,
                      int x, int y, float scale, float min_cos, const TemporalWindowSettings &settings,
                      float *values) {
    const std::size_t count = centre.values.size();
    double weight_sum = 0;
    std::vector<double> sums(count, 0.0);
    same_surface_taps(centre, neighbour, fx, fy, x, y, scale, min_cos, settings,
                      [&](int tx, int ty, float w) {
                          weight_sum += w;
                          for (std::size_t c = 0; c < count; ++c)
                              sums[c] += double(w) * neighbour.values[c](tx, ty);
                      });
    if (weight_sum < 1e-3) return false;
    for (std::size_t c = 0; c < count; ++c) values[c] = float(sums[c] / weight_sum);
    return true;
}

/// One neighbour warped onto the centre: its values (NaN where no tap
/// survived) and the mean absolute difference from the centre's.
struct Warped {
    int offset = 0;                          ///< the neighbour's frame minus the centre's
    std::vector<std::vector<float>> values;  ///< per blended layer, row-major
    std::vector<float> difference;           ///< NaN where no tap survived
    /// 1 where the value was read at a pixel centre (a whole-pixel motion,
    /// nothing resampled), 0 where the lookup mixed pixels.
    std::vector<std::uint8_t> whole_pixel;
};

Warped warp_neighbour(const FramesByOffset &frames, const TemporalFrameView &neighbour,
                      const TemporalWindowSettings &settings) {
    const TemporalFrameView &centre = *frames.at(0);
    const int width = centre.position[0].width, height = centre.position[0].height;
    const std::size_t pixels = std::size_t(width) * std::size_t(height), count = centre.values.size();
    Warped warped;
    warped.offset = neighbour.offset;
    warped.values.assign(count, std::vector<float>(pixels, kNoValue));
    warped.difference.assign(pixels, kNoValue);
    warped.whole_pixel.assign(pixels, 0);
    const float min_cos = std::cos(settings.normal_threshold_deg * 3.14159265f / 180.0f);
    parallel_for_rows(height, [&](int y) {
        std::vector<float> values(count);
        for (int x = 0; x < width; ++x) {
            const float scale = footprint_m(centre, x, y);
            float fx = 0, fy = 0;
            if (!(scale > 0) || !std::isfinite(scale) ||
                !follow_motion(frames, x, y, neighbour.offset, fx, fy) ||
                !neighbour_values(centre, neighbour, fx, fy, x, y, scale, min_cos, settings, values.data()))
                continue;
            const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
            double difference = 0;
            for (std::size_t c = 0; c < count; ++c) {
                warped.values[c][i] = values[c];
                difference =
                    std::max(difference, std::fabs(double(values[c]) - double(centre.values[c](x, y))));
            }
            warped.difference[i] = float(difference);
            warped.whole_pixel[i] = fx == std::floor(fx) && fy == std::floor(fy) ? 1 : 0;
        }
    });
    return warped;
}

/// The robust scale of the differences around each block: 1.4826 x the
/// median of those that are not 0 over the region of blocks centred on it
/// (the standard deviation for Gaussian noise), or, with `majority`, 0 when
/// fewer than half of the region's are not 0: noise touches most pixels of
/// a region, a change (an edge that moved) a band. Not counting the zeros keeps the
/// noisy pixels of a region that is partly noise-free (fully lit, or lit by
/// a light sampled without noise) from looking like changes; a region
/// centred on each block follows the noise where it changes within a frame
/// (a penumbra beside a nearly noise-free background). One value per block,
/// row-major.
std::vector<float> block_noise_scales(const std::vector<float> &difference, int width, int height,
                                      float factor, bool majority) {
    const int blocks_x = (width + kTemporalBlockPx - 1) / kTemporalBlockPx;
    const int blocks_y = (height + kTemporalBlockPx - 1) / kTemporalBlockPx;
    constexpr int reach_px = kTemporalBlockPx * (kTemporalScaleRegionBlocks / 2);
    std::vector<float> scales(std::size_t(blocks_x) * std::size_t(blocks_y), 0.0f);
    parallel_for_rows(blocks_y, [&](int by) {
        std::vector<float> region;
        const int y_begin = std::max(0, by * kTemporalBlockPx - reach_px);
        const int y_end = std::min(height, (by + 1) * kTemporalBlockPx + reach_px);
        for (int bx = 0; bx < blocks_x; ++bx) {
            region.clear();
            std::size_t valid = 0;
            const int x_begin = std::max(0, bx * kTemporalBlockPx - reach_px);
            const int x_end = std::min(width, (bx + 1) * kTemporalBlockPx + reach_px);
            for (int y = y_begin; y < y_end; ++y)
                for (int x = x_begin; x < x_end; ++x) {
                    const float d = difference[std::size_t(y) * std::size_t(width) + std::size_t(x)];
                    if (!std::isfinite(d)) continue;
                    ++valid;
                    if (d > 0) region.push_back(d);
                }
            if (region.empty() || (majority && 2 * region.size() < valid)) continue;
            auto middle = region.begin() + std::ptrdiff_t(region.size() / 2);
            std::nth_element(region.begin(), middle, region.end());
            scales[std::size_t(by) * std::size_t(blocks_x) + std::size_t(bx)] = factor * *middle;
        }
    });
    return scales;
}

/// The noise of pixel `i` as its window shows it, in units of a difference
/// between two frames: sqrt(2) x 1.4826 x the median absolute deviation of
/// its values across the frames whose taps survived (the centre's
/// included), the largest over the blended layers. An edge that crosses the
/// pixel during the window moves a minority of its values and leaves this
/// near 0; noise the region's median misses (a pixel noisier than its
/// surroundings) shows here. Exactly 0 when most of its values are the same
/// (within a few ulps): the pixel is noise-free in those frames (in an
/// umbra, or fully lit). -1 with fewer than 3 values. `balanced`: as many
/// of those frames before the centre as after it.
float window_noise_scale(const TemporalFrameView &centre, const std::vector<Warped> &warped, int x, int y,
                         std::size_t i, std::vector<float> &scratch, bool &balanced) {
    int before = 0, after = 0;
    for (const Warped &neighbour : warped)
        if (std::isfinite(neighbour.difference[i])) (neighbour.offset < 0 ? before : after) += 1;
    balanced = before == after;
    if (before + after < 2) return -1.0f;
    double largest = 0;
    for (std::size_t c = 0; c < centre.values.size(); ++c) {
        scratch.clear();
        scratch.push_back(centre.values[c](x, y));
        for (const Warped &neighbour : warped)
            if (std::isfinite(neighbour.difference[i])) scratch.push_back(neighbour.values[c][i]);
        const auto middle = scratch.begin() + std::ptrdiff_t(scratch.size() / 2);
        std::nth_element(scratch.begin(), middle, scratch.end());
        const float median = *middle;
        for (float &v : scratch) v = std::fabs(v - median);
        std::nth_element(scratch.begin(), middle, scratch.end());
        if (*middle > kSameValueRelative * std::fabs(median)) largest = std::max(largest, double(*middle));
    }
    return float(1.41421356 * 1.4826 * largest);
}

/// Per blended layer, the difference below which two of the centre frame's
/// values are the same in noise_free_in_frame(): kSameValueFloor x the
/// layer's mean magnitude over the frame (a filter's faint residue in an
/// umbra, far below any noise, is not noise).
std::vector<float> same_value_floors(const TemporalFrameView &centre) {
    std::vector<float> floors;
    for (ConstPlaneView values : centre.values) {
        double sum = 0;
        for (int y = 0; y < values.height; ++y)
            for (int x = 0; x < values.width; ++x)
                if (std::isfinite(values(x, y))) sum += std::fabs(values(x, y));
        floors.push_back(float(kSameValueFloor * sum / (double(values.width) * double(values.height))));
    }
    return floors;
}

/// Whether the centre's pixel (x, y) holds, in every blended layer, the
/// value of at least two of its four neighbours in the frame (within
/// kSameValueRelative, or the layer's floor): noise does not repeat a value,
/// so the pixel is noise-free in this frame (an umbra, a region the sampled
/// effect does not reach) however its neighbours in time spread.
bool noise_free_in_frame(const TemporalFrameView &centre, int x, int y, const std::vector<float> &floor) {
    const int width = centre.position[0].width, height = centre.position[0].height;
    int same = 0;
    for (const auto &[nx, ny] : {std::pair<int, int>{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}}) {
        if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
        bool equal = true;
        for (std::size_t c = 0; c < centre.values.size(); ++c) {
            const float a = centre.values[c](x, y), b = centre.values[c](nx, ny);
            equal = equal && std::fabs(a - b) <= std::max(kSameValueRelative * std::fabs(a), floor[c]);
        }
        same += equal ? 1 : 0;
    }
    return same >= 2;
}

/// The shading test's weight of a neighbour's value that differs by `difference` where the noise is `scale`.
float shading_weight(float difference, float scale, float tolerance) {
    if (difference == 0) return 1.0f;
    if (!(scale > 0)) return 0.0f;  // noise-free: any difference is a change
    const float z = difference / (tolerance * scale);
    return std::exp(-0.5f * z * z);
}

/// The window's frames by offset, once every view is checked against the
/// centre's size and layer count and `out` against both; throws aaf::Error.
FramesByOffset checked_window(const TemporalFrameView &centre,
                              const std::vector<TemporalFrameView> &neighbours,
                              const std::vector<PlaneView> &out) {
    const int width = centre.position[0].width, height = centre.position[0].height;
    const std::size_t count = centre.values.size();
    check_frame(centre, count, width, height);
    FramesByOffset frames{{0, &centre}};
    for (const TemporalFrameView &frame : neighbours) {
        check_frame(frame, count, width, height);
        if (frame.offset == 0 || !frames.emplace(frame.offset, &frame).second)
            throw Error("temporal window: two frames at offset " + std::to_string(frame.offset));
    }
    if (out.size() != count) throw Error("temporal window: as many outputs as layers are needed");
    for (PlaneView view : out) check_view(view, width, height, false, "an output");
    return frames;
}

/// What the shading test knows of each pixel of the centre frame.
struct PixelNoise {
    std::vector<float> own;                          ///< window_noise_scale(), NaN with fewer than 3 values
    std::vector<std::uint8_t> balanced, noise_free;  ///< window_noise_scale()'s, noise_free_in_frame()
    /// The median of `own` over each block's region, with and without the majority rule.
    std::vector<float> region_own, region_own_robust;
};

/// Each pixel's own spread across the window, and its median over the
/// region: a moving shadow changes a coherent part of a region in every
/// neighbour (filling the differences' median) but a minority of each
/// pixel's frames (leaving its own spread to the noise).
PixelNoise pixel_noise(const TemporalFrameView &centre, const std::vector<Warped> &warped) {
    const int width = centre.position[0].width, height = centre.position[0].height;
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    const std::vector<float> same_floor = same_value_floors(centre);
    PixelNoise noise;
    noise.own.assign(pixels, kNoValue);
    noise.balanced.assign(pixels, 0);
    noise.noise_free.assign(pixels, 0);
    parallel_for_rows(height, [&](int y) {
        std::vector<float> scratch;
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
            bool even = false;
            const float scale = window_noise_scale(centre, warped, x, y, i, scratch, even);
            if (scale >= 0) noise.own[i] = scale;
            noise.balanced[i] = even;
            noise.noise_free[i] = noise_free_in_frame(centre, x, y, same_floor) ? 1 : 0;
        }
    });
    noise.region_own = block_noise_scales(noise.own, width, height, 1.0f, true);
    noise.region_own_robust = block_noise_scales(noise.own, width, height, 1.0f, false);
    return noise;
}

/// The shading test's weight of `neighbour`'s value at pixel `i` (in
/// `block`), `region_scale` its differences' scale over the block's region,
/// `robust` when the pixel has kTemporalRobustValues values or more.
float neighbour_weight(const PixelNoise &pixels, const Warped &neighbour, float region_scale, std::size_t i,
                       std::size_t block, bool robust, const TemporalWindowSettings &settings) {
    const float difference = neighbour.difference[i], own = pixels.own[i];
    // The region's noise: its differences' scale, bounded by its pixels' own spreads.
    float noise = std::min(region_scale, robust ? pixels.region_own_robust[block] : pixels.region_own[block]);
    if (pixels.noise_free[i]) {
        noise = 0;  // noise-free in this frame: any difference is a change
    } else if (std::isfinite(own)) {
        if (own == 0) {
            noise = 0;  // noise-free in most of its frames: any difference is a change
        } else if (pixels.balanced[i]) {
            // A pixel noisier than its region raises it, where as many
            // frames follow as precede (a steady change averages to the
            // centre's value): within kTemporalOwnScaleLimit where the
            // neighbour's value is resampled (it mixes four pixels and
            // carries the lookup's error besides the noise) or too few
            // values measure it; else to its own spread, a value beyond
            // tau of it then being a change (an edge's step), not noise.
            if (robust && neighbour.whole_pixel[i] && own > kTemporalOwnScaleLimit * noise) {
                if (difference > settings.shading_tolerance * own) return 0.0f;
                noise = own;
            } else {
                noise = std::max(noise, std::min(own, kTemporalOwnScaleLimit * noise));
            }
        }
    }
    return shading_weight(difference, noise, settings.shading_tolerance);
}

}  // namespace

void blend_temporal_window(const TemporalFrameView &centre, const std::vector<TemporalFrameView> &neighbours,
                           const TemporalWindowSettings &settings, const std::vector<PlaneView> &out) {
    const int width = centre.position[0].width, height = centre.position[0].height;
    const std::size_t count = centre.values.size();
    const FramesByOffset frames = checked_window(centre, neighbours, out);
    if (!(settings.plane_tolerance > 0) || !(settings.shading_tolerance > 0))
        throw Error("temporal window: the plane and shading tolerances must be > 0");

    // The region scales twice: with the majority rule for the pixels with
    // fewer than kTemporalRobustValues values, without for the others.
    std::vector<Warped> warped;
    std::vector<std::vector<float>> scales, scales_robust;
    for (const TemporalFrameView &frame : neighbours) {
        if (std::abs(frame.offset) > settings.radius_frames || (settings.causal && frame.offset > 0))
            continue;
        warped.push_back(warp_neighbour(frames, frame, settings));
        scales.push_back(block_noise_scales(warped.back().difference, width, height, 1.4826f, true));
        scales_robust.push_back(block_noise_scales(warped.back().difference, width, height, 1.4826f, false));
    }
    const PixelNoise noise = pixel_noise(centre, warped);
    const int blocks_x = (width + kTemporalBlockPx - 1) / kTemporalBlockPx;
    parallel_for_rows(height, [&](int y) {
        std::vector<double> sums(count);
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
            const std::size_t block =
                std::size_t(y / kTemporalBlockPx) * std::size_t(blocks_x) + std::size_t(x / kTemporalBlockPx);
            double weight_sum = 1;
            for (std::size_t c = 0; c < count; ++c) sums[c] = centre.values[c](x, y);
            int values = 1;
            for (const Warped &neighbour : warped) values += std::isfinite(neighbour.difference[i]) ? 1 : 0;
            const bool robust = values >= kTemporalRobustValues;
            for (std::size_t n = 0; n < warped.size(); ++n) {
                if (!std::isfinite(warped[n].difference[i])) continue;
                const float region_scale = robust ? scales_robust[n][block] : scales[n][block];
                const float w = neighbour_weight(noise, warped[n], region_scale, i, block, robust, settings);
                if (!(w > 0)) continue;
                weight_sum += w;
                for (std::size_t c = 0; c < count; ++c) sums[c] += double(w) * warped[n].values[c][i];
            }
            for (std::size_t c = 0; c < count; ++c) out[c](x, y) = float(sums[c] / weight_sum);
        }
    });
}

void temporal_window_extrema(const TemporalFrameView &centre,
                             const std::vector<TemporalFrameView> &neighbours,
                             const TemporalWindowSettings &settings, WindowExtreme extreme,
                             const std::vector<PlaneView> &out) {
    const int width = centre.position[0].width, height = centre.position[0].height;
    const std::size_t count = centre.values.size();
    const FramesByOffset frames = checked_window(centre, neighbours, out);
    const float min_cos = std::cos(settings.normal_threshold_deg * 3.14159265f / 180.0f);
    // Whether `a` replaces the extreme so far, `b` (a non-finite one always goes).
    const auto better = [extreme](float a, float b) {
        if (!std::isfinite(b)) return true;
        switch (extreme) {
            case WindowExtreme::Min:
                return a < b;
            case WindowExtreme::Max:
                return a > b;
            case WindowExtreme::MinNonNegative:
                return a >= 0 && (b < 0 || a < b);
        }
        return false;
    };
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            for (std::size_t c = 0; c < count; ++c) out[c](x, y) = centre.values[c](x, y);
            const float scale = footprint_m(centre, x, y);
            if (!(scale > 0) || !std::isfinite(scale)) continue;
            for (const TemporalFrameView &neighbour : neighbours) {
                if (std::abs(neighbour.offset) > settings.radius_frames ||
                    (settings.causal && neighbour.offset > 0))
                    continue;
                float fx = 0, fy = 0;
                if (!follow_motion(frames, x, y, neighbour.offset, fx, fy)) continue;
                same_surface_taps(centre, neighbour, fx, fy, x, y, scale, min_cos, settings,
                                  [&](int tx, int ty, float) {
                                      for (std::size_t c = 0; c < count; ++c) {
                                          const float v = neighbour.values[c](tx, ty);
                                          if (better(v, out[c](x, y))) out[c](x, y) = v;
                                      }
                                  });
            }
        }
    });
}

void blend_temporal_history(const TemporalFrameView &centre, const TemporalFrameView &history, float alpha,
                            const TemporalWindowSettings &settings, const std::vector<PlaneView> &out) {
    const int width = centre.position[0].width, height = centre.position[0].height;
    const std::size_t count = centre.values.size();
    check_frame(centre, count, width, height);
    check_frame(history, count, width, height);
    if (history.offset != -1) throw Error("temporal history: the history is the previous frame (offset -1)");
    if (out.size() != count) throw Error("temporal history: as many outputs as layers to blend are needed");
    for (PlaneView view : out) check_view(view, width, height, false, "an output");
    if (!(alpha > 0 && alpha <= 1) || !(settings.plane_tolerance > 0))
        throw Error("temporal history: alpha must be in (0, 1] and the plane tolerance > 0");
    const FramesByOffset frames{{0, &centre}, {-1, &history}};
    const Warped warped = warp_neighbour(frames, history, settings);
    parallel_for_rows(height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
            if (!std::isfinite(warped.difference[i])) {
                for (std::size_t c = 0; c < count; ++c) out[c](x, y) = centre.values[c](x, y);
                continue;
            }
            for (std::size_t c = 0; c < count; ++c)
                out[c](x, y) = alpha * centre.values[c](x, y) + (1 - alpha) * warped.values[c][i];
        }
    });
}

}  // namespace aaf
