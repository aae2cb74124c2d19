// AovSet's moves: filter_aovs() takes the input's planes into its output
// without copying them, so a frame less of memory is held at the peak.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_set.h"
#include "aaf/core/util/error.h"

using namespace aaf;

TEST_CASE("AovSet: a plane taken out and added to another set moves, keeping its data and the order",
          "[core][aovs]") {
    AovSet from(3, 2), to(3, 2);
    from.add_channel("A", 1.0f);
    from.add_channel("B", 2.0f);
    from.add_channel("C", 3.0f);
    const float *b_data = from.channel("B").data;

    AovSet::Plane b = from.take_channel("B");
    CHECK(b.data() == b_data);  // moved, not copied
    CHECK(from.channel_names() == std::vector<std::string>{"A", "C"});
    CHECK(from.plane(from.index_of("C")) == AovSet::Plane(6, 3.0f));
    CHECK_THROWS_AS(from.take_channel("B"), Error);

    const PlaneView added = to.add_channel("B", std::move(b));
    CHECK(added.data == b_data);
    CHECK(to.plane(to.index_of("B")) == AovSet::Plane(6, 2.0f));
    CHECK_THROWS_AS(to.add_channel("B", AovSet::Plane(6)), Error);  // the name exists
    CHECK_THROWS_AS(to.add_channel("D", AovSet::Plane(5)), Error);  // another size
    // Adding more channels keeps earlier planes where they are (views stay valid).
    for (int i = 0; i < 20; ++i) to.add_channel("E" + std::to_string(i));
    CHECK(to.channel("B").data == b_data);
}
