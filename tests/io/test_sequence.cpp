#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "aaf/core/util/error.h"
#include "aaf/io/sequence.h"

using namespace aaf;
namespace fs = std::filesystem;

TEST_CASE("Frame ranges: single, span, steps with x and :, lists", "[io][sequence]") {
    CHECK(io::FrameRange::parse("7").to_vector() == std::vector<int>{7});
    CHECK(io::FrameRange::parse("1-4").to_vector() == std::vector<int>{1, 2, 3, 4});
    CHECK(io::FrameRange::parse("1-9x3").to_vector() == std::vector<int>{1, 4, 7});
    CHECK(io::FrameRange::parse("1-9:3").to_vector() ==
          std::vector<int>{1, 4, 7});  // ':' is a step, not ignored
    CHECK(io::FrameRange::parse("1,5,7-9").to_vector() == std::vector<int>{1, 5, 7, 8, 9});
    CHECK(io::FrameRange::parse("3,1-3").to_vector() ==
          std::vector<int>{3, 1, 2});  // order kept, no duplicates
    CHECK(io::FrameRange::parse("-2-1").to_vector() == std::vector<int>{-2, -1, 0, 1});
    for (const char *bad : {"", "a", "1-", "5-1", "1-9x0", "1-9:-2", "1,,2", "4x2"})
        CHECK_THROWS_AS(io::FrameRange::parse(bad), Error);
}

TEST_CASE("a frame range holds its items, not its frames: two billion frames cost nothing up front",
          "[io][sequence]") {
    const io::FrameRange huge = io::FrameRange::parse("1-2000000000");
    CHECK(huge.size() == 2000000000u);
    CHECK(huge.front() == 1);
    CHECK(io::FrameRange::parse("1-9x3,20-21").size() == 5);
    CHECK(io::FrameRange::parse("3,1-3").size() == 3);  // overlapping items: counted without duplicates
    CHECK(io::FrameRange::of({4, 2, 4}).to_vector() == std::vector<int>{4, 2});
    // The last frames below INT_MAX end the item instead of wrapping round.
    CHECK(io::FrameRange::parse("2147483645-2147483647").to_vector() ==
          std::vector<int>{2147483645, 2147483646, 2147483647});
    CHECK(io::FrameRange::parse("-2147483648--2147483647x5").to_vector() == std::vector<int>{-2147483648});
}

TEST_CASE("a frame number past the int range is an error saying so, not 'stoi'", "[io][sequence]") {
    for (const char *spec : {"1-99999999999", "99999999999", "1-10x99999999999", "-99999999999-1"}) {
        INFO(spec);
        CHECK_THROWS_AS(io::FrameRange::parse(spec), Error);
        CHECK_THROWS_WITH(io::FrameRange::parse(spec),
                          Catch::Contains("out of range") && !Catch::Contains("stoi"));
    }
}

TEST_CASE("Frame paths: # and @ pad one digit each, printf fields", "[io][sequence]") {
    CHECK(io::frame_path("shot.####.exr", 7) == "shot.0007.exr");
    CHECK(io::frame_path("shot.#.exr", 12) == "shot.12.exr");
    CHECK(io::frame_path("shot.@@@.exr", 7) == "shot.007.exr");
    CHECK(io::frame_path("shot.%04d.exr", 7) == "shot.0007.exr");
    CHECK(io::frame_path("shot.%d.exr", 7) == "shot.7.exr");
    CHECK(io::frame_path("a/b.####.exr", 123456) == "a/b.123456.exr");
    CHECK(io::is_sequence_pattern("x.####.exr"));
    CHECK(!io::is_sequence_pattern("x.exr"));
    CHECK_THROWS_AS(io::frame_path("plain.exr", 1), Error);
    // Only the file name holds the frame field: folders may contain # or @.
    CHECK(io::frame_path("v@2/take#3/b.###.exr", 7) == "v@2/take#3/b.007.exr");
    CHECK(!io::is_sequence_pattern("v@2/single.exr"));
    CHECK(!io::is_sequence_pattern("shots_%04d/single.exr"));
}

TEST_CASE("Frames on disk are found by pattern", "[io][sequence]") {
    const fs::path dir = fs::path(AAF_TEST_BINARY_DIR) / "scratch" / "sequence";
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const char *name : {"shot.0001.exr", "shot.0003.exr", "shot.0010.exr", "shot.1.exr",
                             "other.0002.exr", "shot.0002.exr.tmp"})
        std::ofstream(dir / name) << "x";
    CHECK(io::frames_on_disk((dir / "shot.####.exr").string()) == std::vector<int>{1, 3, 10});
    CHECK(io::frames_on_disk((dir / "shot.#.exr").string()) == std::vector<int>{1});

    const fs::path folder = dir / "v@2#";
    fs::create_directories(folder);
    for (const char *name : {"in.0004.exr", "in.0005.exr"}) std::ofstream(folder / name) << "x";
    CHECK(io::frames_on_disk((folder / "in.####.exr").string()) == std::vector<int>{4, 5});
}

TEST_CASE("a huge range whose items overlap is refused at once, not counted frame by frame", "[sequence]") {
    // Found by scripts/fuzz.sh: counting the distinct frames of such a spec took minutes.
    CHECK_THROWS_WITH(io::FrameRange::parse("12,853223,12,8-380084412,964"), Catch::Contains("overlap"));
    CHECK_THROWS_WITH(io::FrameRange::parse("1-2000000000,5"), Catch::Contains("list each frame once"));
    // Small overlaps still work, repeats skipped.
    CHECK(io::FrameRange::parse("1-5,3-7").size() == 7);
    CHECK(io::FrameRange::parse("1-2000000000,2000000001").size() ==
          2000000001u);  // disjoint: counted by items
}
