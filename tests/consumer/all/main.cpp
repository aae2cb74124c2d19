// Renders a tiny frame of an installed scene file with the installed tracer.
#include <cstdio>
#include <exception>

#include "aaf/core/contract/aov_set.h"
#include "aaf/trace/render.h"

int main(int argc, char **argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: all_consumer SCENE.json\n");
        return 2;
    }
    try {
        aaf::trace::RenderSettings settings;
        settings.width = 8;
        settings.height = 6;
        settings.spp = 1;
        const aaf::AovSet aovs = aaf::trace::render_scene(argv[1], settings);
        if (aovs.width() != 8 || aovs.height() != 6 || aovs.channel_names().empty()) {
            std::fprintf(stderr, "all_consumer: FAILED: render_scene returned %dx%d\n", aovs.width(),
                         aovs.height());
            return 1;
        }
        std::printf("all_consumer: ok (%zu channels)\n", aovs.channel_names().size());
    } catch (const std::exception &e) {
        std::fprintf(stderr, "all_consumer: FAILED: %s\n", e.what());
        return 1;
    }
    return 0;
}
