// The committed LTC table's error against brute-force integration over the
// light's surface (tests/trace/shading/ltc_reference.h), over roughness and view
// angle: prints the Markdown tables of scripts/ltc_fit/README.md.
//   cmake --build build --target ltc_error && build/scripts/ltc_fit/ltc_error
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "aaf/trace/shading/ltc_ggx.h"
#include "ltc_reference.h"

int main() {
    using namespace aaf;
    constexpr double kPi = 3.14159265358979323846;
    const double roughnesses[] = {0.1, 0.2, 0.3, 0.5, 0.7, 1.0};
    const double views_deg[] = {0, 30, 60, 75, 85};
    // Per cell: the highlight's relative error (F0 = 1, the light around the
    // mirror direction), the largest absolute error over the four placements
    // as a fraction of the lobe's hemispherical integral (F0 = 1), and the
    // same for the Fresnel integral (F0 = 0).
    std::vector<double> highlight, lobe, fresnel;
    for (double roughness : roughnesses)
        for (double view : views_deg) {
            const double theta = view * kPi / 180;
            const Vec3d wo{std::sin(theta), 0, std::cos(theta)};
            const double magnitude = ltc_ggx::lookup(roughness, wo.z).magnitude;
            double worst_lobe = 0, worst_fresnel = 0, mirror = 0;
            const std::vector<ltc_reference::Rectangle> lights = ltc_reference::ggx_placements(view);
            for (std::size_t k = 0; k < lights.size(); ++k) {
                const ltc_ggx::PolygonIntegral ltc = ltc_ggx::integrate(lights[k].polygon(), roughness, wo.z);
                const double ref_lobe = ltc_reference::ggx_by_quadrature(lights[k], wo, roughness, false);
                const double ref_fresnel = ltc_reference::ggx_by_quadrature(lights[k], wo, roughness, true);
                if (k == 0) mirror = std::fabs(ltc.magnitude_term - ref_lobe) / ref_lobe;
                worst_lobe = std::max(worst_lobe, std::fabs(ltc.magnitude_term - ref_lobe) / magnitude);
                worst_fresnel =
                    std::max(worst_fresnel, std::fabs(ltc.fresnel_term - ref_fresnel) / magnitude);
            }
            highlight.push_back(mirror);
            lobe.push_back(worst_lobe);
            fresnel.push_back(worst_fresnel);
        }
    const char *titles[] = {
        "Relative error of the highlight (a 1 m square at 2 m around the mirror direction, F0 = 1)",
        ("Largest absolute error over the four placements, as a fraction of the lobe's hemispherical "
         "integral (F0 = 1)"),
        "The same for the Fresnel integral (F0 = 0), as a fraction of the lobe's hemispherical integral"};
    const std::vector<double> *tables[] = {&highlight, &lobe, &fresnel};
    for (int t = 0; t < 3; ++t) {
        std::printf("%s:\n\n| roughness |", titles[t]);
        for (double view : views_deg) std::printf(" view %g deg |", view);
        std::printf("\n| --- |");
        for (std::size_t v = 0; v < std::size(views_deg); ++v) std::printf(" --- |");
        std::printf("\n");
        for (std::size_t r = 0; r < std::size(roughnesses); ++r) {
            std::printf("| %.2f |", roughnesses[r]);
            for (std::size_t v = 0; v < std::size(views_deg); ++v)
                std::printf(" %.4f |", (*tables[t])[r * std::size(views_deg) + v]);
            std::printf("\n");
        }
        std::printf("\n");
    }
    return 0;
}
