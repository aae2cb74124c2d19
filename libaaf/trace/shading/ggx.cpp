#include "aaf/trace/shading/ggx.h"

#include <algorithm>
#include <cmath>

namespace aaf::ggx {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

double distribution(double cos_h, double alpha) {
    if (!(cos_h > 0)) return 0;
    const double alpha_sq = alpha * alpha;
    const double denominator = cos_h * cos_h * (alpha_sq - 1) + 1;
    return alpha_sq / (kPi * denominator * denominator);
}

double masking(double cos_theta, double alpha) {
    if (!(cos_theta > 0)) return 0;
    const double alpha_sq = alpha * alpha;
    return 2 * cos_theta / (cos_theta + std::sqrt(alpha_sq + (1 - alpha_sq) * cos_theta * cos_theta));
}

double cosine_weighted(Vec3d wo, Vec3d wi, double alpha) {
    if (!(wo.z > 0) || !(wi.z > 0)) return 0;
    const Vec3d h = normalize(wo + wi);
    return distribution(h.z, alpha) * masking(wi.z, alpha) * masking(wo.z, alpha) / (4 * wo.z);
}

double schlick_weight(Vec3d wo, Vec3d wi) {
    const Vec3d h = normalize(wo + wi);
    return std::pow(1 - std::max(0.0, dot(wi, h)), 5.0);
}

Vec3d sample(Vec3d wo, double alpha, double u1, double u2) {
    // Inverse CDF of D(h) cos(theta_h): tan^2(theta_h) = alpha^2 u1 / (1 - u1).
    const double phi = 2 * kPi * u2;
    const double cos_sq = (1 - u1) / (1 + (alpha * alpha - 1) * u1);
    const double cos_h = std::sqrt(std::max(0.0, cos_sq)), sin_h = std::sqrt(std::max(0.0, 1 - cos_sq));
    const Vec3d h{sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h};
    return h * (2 * dot(wo, h)) - wo;
}

double sample_pdf(Vec3d wo, Vec3d wi, double alpha) {
    const Vec3d sum = wo + wi;
    const double norm = length(sum);
    if (!(norm > 0)) return 0;
    const Vec3d h = sum / norm;
    const double wo_h = std::fabs(dot(wo, h));
    if (!(wo_h > 0)) return 0;
    return distribution(h.z, alpha) * h.z / (4 * wo_h);
}

}  // namespace aaf::ggx
