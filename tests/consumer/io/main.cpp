// Writes a small AOV set to EXR with the installed io library and reads it back.
#include <cstdio>
#include <exception>
#include <string>
#include <variant>

#include "aaf/core/contract/aov_set.h"
#include "aaf/io/exr_io.h"

int main(int argc, char **argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: io_consumer OUTPUT.exr\n");
        return 2;
    }
    const std::string path = argv[1];
    try {
        aaf::AovSet aovs(3, 2);
        aaf::PlaneView r = aovs.add_channel("R");
        aaf::PlaneView depth = aovs.add_channel("Z");
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 3; ++x) {
                r(x, y) = 0.25f * float(x + 3 * y);
                depth(x, y) = 100.0f + float(x) - float(y);
            }
        aovs.attributes["aaf:consumer"] = std::string("io");
        aaf::io::write_aovs(aovs, path);

        const aaf::AovSet back = aaf::io::read_aovs(path);
        bool ok = back.width() == 3 && back.height() == 2 && back.has_channel("R") && back.has_channel("Z");
        for (int y = 0; ok && y < 2; ++y)
            for (int x = 0; x < 3; ++x)
                ok = ok && back.channel("R")(x, y) == r(x, y) && back.channel("Z")(x, y) == depth(x, y);
        const auto attribute = back.attributes.find("aaf:consumer");
        ok = ok && attribute != back.attributes.end() && std::get<std::string>(attribute->second) == "io";
        if (!ok) {
            std::fprintf(stderr, "io_consumer: FAILED: %s does not read back as written\n", path.c_str());
            return 1;
        }
    } catch (const std::exception &e) {
        std::fprintf(stderr, "io_consumer: FAILED: %s\n", e.what());
        return 1;
    }
    std::printf("io_consumer: ok (%s)\n", path.c_str());
    return 0;
}
