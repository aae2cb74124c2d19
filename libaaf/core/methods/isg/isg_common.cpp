#include "isg_common.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/methods/isg/isg_roles.h"
#include "aaf/core/util/error.h"
#include "aaf/core/util/parallel.h"
#include "aaf/core/util/quoted.h"

namespace aaf::isg {

namespace {

std::string describe(float value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

const AttributeValue &attribute(const std::map<std::string, AttributeValue> &attributes, const char *name) {
    auto it = attributes.find(name);
    if (it == attributes.end())
        throw InputError("missing header attribute " + quoted(name) + " (render with --aovs isg)");
    return it->second;
}

}  // namespace

float float_attribute(const std::map<std::string, AttributeValue> &attributes, const char *name) {
    const AttributeValue &value = attribute(attributes, name);
    if (const float *f = std::get_if<float>(&value)) return *f;
    if (const int *i = std::get_if<int>(&value)) return float(*i);
    throw InputError("header attribute " + quoted(name) + " has the wrong type");
}

Vec3 vec3_attribute(const std::map<std::string, AttributeValue> &attributes, const char *name) {
    const Vec3 *v = std::get_if<Vec3>(&attribute(attributes, name));
    if (!v) throw InputError("header attribute " + quoted(name) + " has the wrong type");
    if (!all_finite(*v))
        throw InputError("header attribute " + quoted(name) + " must be finite (is " + describe(v->x) + " " +
                         describe(v->y) + " " + describe(v->z) + ")");
    return *v;
}

float positive_attribute(const std::map<std::string, AttributeValue> &attributes, const char *name,
                         float max_value) {
    const float value = float_attribute(attributes, name);
    if (!(value > 0) || !(value <= max_value))
        throw InputError("header attribute " + quoted(name) + " must be positive and at most " +
                         describe(max_value) + " (is " + describe(value) + ")");
    return value;
}

float non_negative_attribute(const std::map<std::string, AttributeValue> &attributes, const char *name) {
    const float value = float_attribute(attributes, name);
    if (!(value >= 0) || !std::isfinite(value))
        throw InputError("header attribute " + quoted(name) + " must be finite and not negative (is " +
                         describe(value) + ")");
    return value;
}

float focal_px_attribute(const std::map<std::string, AttributeValue> &attributes, int height) {
    // A vertical field of view of at least 1e-6 rad: focal_px = height / (2 tan(fov_y / 2)).
    return positive_attribute(attributes, attr::kCameraFocalPx, 1e6f * float(std::max(height, 1)));
}

Vec3Planes vec3_input(const MethodImages &images, Role role) {
    return {{images.input(role, 0), images.input(role, 1), images.input(role, 2)}};
}

float scene_size_m(const Vec3Planes &position, int width, int height, float scene_size) {
    if (scene_size > 0) return scene_size;
    constexpr float kInf = std::numeric_limits<float>::infinity();
    struct Box {
        Vec3 lo{kInf, kInf, kInf}, hi{-kInf, -kInf, -kInf};
        void add(Vec3 p) {
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
        }
    };
    // One box per row in parallel, then their union: min and max do not
    // depend on the order (a zero's sign aside, which the diagonal squares away).
    std::vector<Box> rows(std::size_t(std::max(height, 0)));
    parallel_for_rows(height, [&](int y) {
        Box &row = rows[std::size_t(y)];
        for (int x = 0; x < width; ++x) {
            const Vec3 p = position(x, y);
            if (all_finite(p)) row.add(p);
        }
    });
    Box box;
    for (const Box &row : rows) {
        if (!(row.hi.x >= row.lo.x)) continue;  // no finite position in the row
        box.add(row.lo);
        box.add(row.hi);
    }
    const float diagonal = box.hi.x >= box.lo.x ? length(box.hi - box.lo) : 0.0f;
    return diagonal > 0 && std::isfinite(diagonal) ? diagonal : 1.0f;
}

}  // namespace aaf::isg
