#include <tbb/parallel_for.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <vector>

#include "aaf/core/framework/method.h"
#include "aaf/core/util/error.h"

using namespace aaf;

TEST_CASE("MethodImages: a deferred output is made once, when first asked for, or at the end", "[method]") {
    const std::map<std::string, AttributeValue> attributes;
    std::vector<float> plane(6, 0.0f);
    std::atomic<int> made{0};
    auto maker = [&] {
        ++made;
        return std::vector<PlaneView>{plane_view(plane.data(), 3, 2)};
    };

    SECTION("asked for from many threads at once: made once, the same views for all") {
        MethodImages images(3, 2, attributes);
        images.set_deferred_output(Role::Beauty, maker);
        CHECK(made == 0);  // nothing is made before it is asked for
        std::atomic<int> wrong{0};
        tbb::parallel_for(0, 64, [&](int) {
            if (images.output(Role::Beauty).data != plane.data()) ++wrong;
        });
        CHECK(made == 1);
        CHECK(wrong == 0);
        images.make_deferred_outputs();
        CHECK(made == 1);
    }
    SECTION("never asked for: made by make_deferred_outputs, once") {
        MethodImages images(3, 2, attributes);
        images.set_deferred_output(Role::Beauty, maker);
        images.make_deferred_outputs();
        images.make_deferred_outputs();
        CHECK(made == 1);
        CHECK(images.output(Role::Beauty).data == plane.data());
    }
    SECTION("a channel it did not make is refused") {
        MethodImages images(3, 2, attributes);
        images.set_deferred_output(Role::Beauty, maker);
        CHECK_THROWS_AS(images.output(Role::Beauty, 1), Error);
        CHECK_THROWS_AS(images.output(Role::FilteredVisibility), Error);
    }
}
