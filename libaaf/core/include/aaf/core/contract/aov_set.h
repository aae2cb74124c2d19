#pragma once

#include <map>
#include <string>
#include <variant>
#include <vector>

#include "aaf/core/contract/plane_view.h"
#include "aaf/core/math/vec3.h"
#include "aaf/core/util/frame_allocator.h"

namespace aaf {

/// How a channel is to be stored in a file: 32-bit float (the default), or
/// 16-bit half where its values need no more (colours, albedo, motion).
/// Computation is always in float.
enum class Precision { Float, Half };

/// Value of a per-image (not per-pixel) attribute, e.g. the light's centre.
using AttributeValue = std::variant<int, float, std::string, Vec3>;

/// An in-memory set of named float channels of one size, plus per-image
/// attributes: what a renderer produces and what the filters consume.
/// Channel names follow the EXR `layer.channel` convention (see aov_contract.h).
/// Channel order is insertion order; storage is planar and stable, so views
/// stay valid while channels are added.
class AovSet {
  public:
    /// One channel's storage: from the frame allocator (frame_allocator.h),
    /// which backs frame-sized planes with huge pages, so reading a frame
    /// into its planes costs far fewer page faults.
    using Plane = FrameVector<float>;

    AovSet() = default;
    AovSet(int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }
    std::size_t pixel_count() const { return std::size_t(width_) * std::size_t(height_); }

    /// Adds a channel filled with `fill`; throws aaf::Error if the name exists.
    PlaneView add_channel(const std::string &name, float fill = 0.0f);
    /// Adds a channel holding `plane` (moved in, width * height floats);
    /// throws aaf::Error if the name exists or the size differs.
    PlaneView add_channel(const std::string &name, Plane plane);
    /// Removes channel `name` and returns its plane (moved out, no copy);
    /// throws aaf::Error naming the channel when it is missing.
    Plane take_channel(const std::string &name);

    bool has_channel(const std::string &name) const;
    /// Throws aaf::Error naming the channel when it is missing.
    PlaneView channel(const std::string &name);
    ConstPlaneView channel(const std::string &name) const;

    const std::vector<std::string> &channel_names() const { return names_; }
    /// Position of `name` in channel_names(), or std::string::npos when absent.
    std::size_t index_of(const std::string &name) const;
    /// Storage precision of the i-th channel; set_precision throws aaf::Error
    /// naming a missing channel.
    Precision precision(std::size_t index) const { return precisions_[index]; }
    void set_precision(const std::string &name, Precision precision);
    /// Contiguous storage of the i-th channel (width * height floats, row-major).
    const Plane &plane(std::size_t index) const { return planes_[index]; }

    std::map<std::string, AttributeValue> attributes;

  private:
    int width_ = 0;
    int height_ = 0;
    std::vector<std::string> names_;
    std::vector<Plane> planes_;
    std::vector<Precision> precisions_;
};

}  // namespace aaf
