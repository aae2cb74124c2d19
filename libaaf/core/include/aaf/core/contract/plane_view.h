#pragma once

#include <cstddef>
#include <type_traits>

namespace aaf {

/// Non-owning view of one float channel of an image. Strides are in floats,
/// so the same view describes planar storage (pixel_stride = 1) and one channel
/// of an interleaved buffer (pixel_stride = channel count).
template <typename T>
struct BasicPlaneView {
    T *data = nullptr;
    int width = 0;
    int height = 0;
    std::ptrdiff_t pixel_stride = 1;
    std::ptrdiff_t row_stride = 0;

    BasicPlaneView() = default;
    BasicPlaneView(T *data_, int width_, int height_, std::ptrdiff_t pixel_stride_,
                   std::ptrdiff_t row_stride_)
        : data(data_), width(width_), height(height_), pixel_stride(pixel_stride_), row_stride(row_stride_) {}
    /// A mutable view converts to a read-only one.
    template <typename U, typename = std::enable_if_t<std::is_same_v<T, const U>>>
    BasicPlaneView(const BasicPlaneView<U> &other)
        : BasicPlaneView(other.data, other.width, other.height, other.pixel_stride, other.row_stride) {}

    bool valid() const { return data != nullptr; }
    T &operator()(int x, int y) const { return data[y * row_stride + x * pixel_stride]; }
};

using PlaneView = BasicPlaneView<float>;
using ConstPlaneView = BasicPlaneView<const float>;

/// A view of a tightly packed width x height plane.
template <typename T>
BasicPlaneView<T> plane_view(T *data, int width, int height) {
    return {data, width, height, 1, width};
}

}  // namespace aaf
