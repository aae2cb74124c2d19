#pragma once

#include <cstdint>
#include <string>

#include "aaf/trace/render.h"
#include "scene_description.h"

namespace aaf::trace {

/// 64-bit FNV-1a (Fowler-Noll-Vo) over the bytes fed to it: deterministic,
/// dependency-free and plenty to tell an edited scene from the one rendered
/// (not a cryptographic digest).
class Fnv1a {
  public:
    void add_bytes(const void *data, std::size_t size);
    void add(float v) { add_bytes(&v, sizeof v); }
    void add(double v) { add_bytes(&v, sizeof v); }
    void add(std::int64_t v) { add_bytes(&v, sizeof v); }
    void add(Vec3 v) {
        add(v.x);
        add(v.y);
        add(v.z);
    }
    std::uint64_t value() const { return state_; }

  private:
    std::uint64_t state_ = 0xcbf29ce484222325ull;  // the FNV-1a 64-bit offset basis
};

/// Hash of everything that decides a render's shadow samples: the scene as
/// rendered (camera at the frame, every mesh's vertices, indices, id and
/// material, every light's geometry, profile and emission) and the settings
/// that shape the samples (size, seed, frame, falloff). The target spp, the
/// AOV groups and the thread count are left out: a resumed render may change
/// them. Floats enter as their bytes, so the hash is exact, not tolerant.
std::uint64_t scene_hash(const SceneDescription &scene, const RenderSettings &settings);

/// `hash` as 16 lowercase hex digits (the `aaf:scene_hash` attribute).
std::string hash_to_hex(std::uint64_t hash);

}  // namespace aaf::trace
