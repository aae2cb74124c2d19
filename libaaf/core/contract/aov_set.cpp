#include "aaf/core/contract/aov_set.h"

#include "aaf/core/util/error.h"
#include "aaf/core/util/quoted.h"

namespace aaf {

AovSet::AovSet(int width, int height) : width_(width), height_(height) {
    if (width <= 0 || height <= 0)
        throw Error("image size must be positive, got " + std::to_string(width) + "x" +
                    std::to_string(height));
}

std::size_t AovSet::index_of(const std::string &name) const {
    for (std::size_t i = 0; i < names_.size(); ++i)
        if (names_[i] == name) return i;
    return std::string::npos;
}

bool AovSet::has_channel(const std::string &name) const {
    return index_of(name) != std::string::npos;
}

PlaneView AovSet::add_channel(const std::string &name, float fill) {
    if (has_channel(name)) throw Error("channel " + quoted(name) + " already exists");
    names_.push_back(name);
    planes_.emplace_back(pixel_count(), fill);
    precisions_.push_back(Precision::Float);
    return plane_view(planes_.back().data(), width_, height_);
}

PlaneView AovSet::add_channel(const std::string &name, Plane plane) {
    if (has_channel(name)) throw Error("channel " + quoted(name) + " already exists");
    if (plane.size() != pixel_count()) throw Error("channel " + quoted(name) + " has another size");
    names_.push_back(name);
    planes_.push_back(std::move(plane));
    precisions_.push_back(Precision::Float);
    return plane_view(planes_.back().data(), width_, height_);
}

AovSet::Plane AovSet::take_channel(const std::string &name) {
    const std::size_t i = index_of(name);
    if (i == std::string::npos) throw Error("missing channel " + quoted(name));
    Plane plane = std::move(planes_[i]);
    names_.erase(names_.begin() + std::ptrdiff_t(i));
    planes_.erase(planes_.begin() + std::ptrdiff_t(i));
    precisions_.erase(precisions_.begin() + std::ptrdiff_t(i));
    return plane;
}

PlaneView AovSet::channel(const std::string &name) {
    std::size_t i = index_of(name);
    if (i == std::string::npos) throw InputError("missing channel " + quoted(name));
    return plane_view(planes_[i].data(), width_, height_);
}

ConstPlaneView AovSet::channel(const std::string &name) const {
    std::size_t i = index_of(name);
    if (i == std::string::npos) throw InputError("missing channel " + quoted(name));
    return plane_view(planes_[i].data(), width_, height_);
}

void AovSet::set_precision(const std::string &name, Precision precision) {
    const std::size_t i = index_of(name);
    if (i == std::string::npos) throw InputError("missing channel " + quoted(name));
    precisions_[i] = precision;
}

}  // namespace aaf
