#include <catch2/catch.hpp>

#include <set>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/contract/ratio_layers.h"
#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/methods/maaf6/maaf6_roles.h"
#include "aaf/core/methods/ratio/ratio_roles.h"
#include "aaf/core/util/error.h"

using namespace aaf;

TEST_CASE("Role table has unique keys and channel names", "[contract]") {
    std::set<std::string> keys, channels;
    for (const RoleInfo &info : role_table()) {
        CHECK(keys.insert(info.role.key).second);
        for (const std::string &name : info.channels) CHECK(channels.insert(name).second);
    }
}

TEST_CASE("Channel overrides accept layers, lists, and reject bad specs", "[contract]") {
    ChannelMap map;
    CHECK(map.channel(Role::Visibility) == "shadow.V");
    map.set_override("position=Pw");
    CHECK(map.channels(Role::Position) == std::vector<std::string>{"Pw.X", "Pw.Y", "Pw.Z"});
    map.set_override("normal=n.x,n.y,n.z");
    CHECK(map.channels(Role::Normal) == std::vector<std::string>{"n.x", "n.y", "n.z"});
    map.set_override("beauty=rgb");
    CHECK(map.channels(Role::Beauty) == std::vector<std::string>{"rgb.R", "rgb.G", "rgb.B"});
    map.set_override("d1=dist.light");
    CHECK(map.channel(Role::D1) == "dist.light");
    // A Blender pass under its view layer is a layer too, dot and all.
    map.set_override("position=ViewLayer.Position");
    CHECK(map.channels(Role::Position) ==
          std::vector<std::string>{"ViewLayer.Position.X", "ViewLayer.Position.Y", "ViewLayer.Position.Z"});

    CHECK_THROWS_WITH(map.set_override("nonsense=x"), Catch::Contains("unknown role 'nonsense'"));
    CHECK_THROWS_AS(map.set_override("position=a,b"), Error);
    CHECK_THROWS_AS(map.set_override("d1="), Error);
    CHECK_THROWS_AS(map.set_override("d1"), Error);
}

TEST_CASE("Light attributes round-trip and missing ones are named", "[contract]") {
    AovSet aovs(2, 2);
    LightPlane light = LightPlane::square({1, 4, 2}, {0, -1, 0}, 0.8f);
    light.profile = LightProfile::Uniform;
    write_light_attributes(light, aovs);
    const LightPlane back = read_light_attributes(aovs);
    CHECK(back.center.y == light.center.y);
    CHECK(back.sigma_m == light.sigma_m);
    CHECK(back.profile == LightProfile::Uniform);
    aovs.attributes.erase(attr::kLightSigma);
    CHECK_THROWS_WITH(read_light_attributes(aovs), Catch::Contains(attr::kLightSigma));
    CHECK_THROWS_AS(read_light_attributes(aovs), InputError);  // an input problem: CLI exit 3
}

TEST_CASE("Missing method inputs are reported by role and header attribute", "[contract]") {
    AovSet aovs(2, 2);
    const ChannelMap map;
    const Method &aaf_method = find_method("aaf");
    const MethodInfo &info = aaf_method.info();
    CHECK(missing_inputs(aaf_method, aovs, map).roles == info.roles.required);
    CHECK(missing_inputs(aaf_method, aovs, map).attributes == info.required_attributes);
    for (Role role : info.roles.required)
        for (const std::string &name : map.channels(role)) aovs.add_channel(name);
    CHECK(missing_inputs(aaf_method, aovs, map).roles.empty());
    write_light_attributes(LightPlane{}, aovs);
    CHECK(missing_inputs(aaf_method, aovs, map).empty());
}

TEST_CASE("Renderer names resolve to roles, and an ambiguous layer prefix is not guessed", "[contract]") {
    const ChannelMap map;
    SECTION("Blender: Combined is the beauty even when an AO pass sorts first") {
        AovSet aovs(1, 1);
        for (const char *pass : {"AO", "Combined", "DiffCol"})
            for (const char *c : {"R", "G", "B"})
                aovs.add_channel(std::string("View Layer.") + pass + "." + c);
        aovs.add_channel("View Layer.IndexOB.X");
        const ChannelMap found = map.resolved(aovs);
        CHECK(found.channels(Role::Beauty) == std::vector<std::string>{"View Layer.Combined.R",
                                                                       "View Layer.Combined.G",
                                                                       "View Layer.Combined.B"});
        CHECK(found.channels(Role::Albedo).front() == "View Layer.DiffCol.R");
        CHECK(found.channel(Role::ObjectId) == "View Layer.IndexOB.X");
    }
    SECTION("Arnold and pbrt-v4 names") {
        AovSet aovs(1, 1);
        for (const char *c : {"R", "G", "B"}) {
            aovs.add_channel(std::string("RGBA.") + c);
            aovs.add_channel(std::string("P.") + c);
            aovs.add_channel(std::string("N.") + c);
            aovs.add_channel(std::string("Albedo.") + c);
        }
        const ChannelMap found = map.resolved(aovs);
        CHECK(found.channels(Role::Beauty).front() == "RGBA.R");
        CHECK(found.channels(Role::Position) == std::vector<std::string>{"P.R", "P.G", "P.B"});
        CHECK(found.channels(Role::Normal).back() == "N.B");
        CHECK(found.channels(Role::Albedo).front() == "Albedo.R");
    }
    SECTION("the contract's names under one prefix resolve, under two they stay unresolved") {
        AovSet aovs(1, 1);
        aovs.add_channel("layerA.shadow.V");
        CHECK(map.resolved(aovs).channel(Role::Visibility) == "layerA.shadow.V");
        aovs.add_channel("layerB.shadow.V");
        CHECK(map.resolved(aovs).channel(Role::Visibility) == "shadow.V");
    }
}

TEST_CASE("A role is read only from its own name, a --map, or a renderer synonym, never from another pass",
          "[contract]") {
    const ChannelMap map;
    SECTION("depth is not P.Z, the beauty is not unshadowed.R/G/B") {
        AovSet aovs(1, 1);
        for (const char *c : {"X", "Y", "Z"}) aovs.add_channel(std::string("P.") + c);
        for (const char *c : {"R", "G", "B"}) aovs.add_channel(std::string("unshadowed.") + c);
        aovs.add_channel("shadow.V");
        const ChannelMap found = map.resolved(aovs);
        CHECK(found.channel(Role::Depth) == "Z");
        CHECK(found.channels(Role::Beauty) == std::vector<std::string>{"R", "G", "B"});
        CHECK(found.channels(Role::Unshadowed).front() == "unshadowed.R");
    }
    SECTION("nor when that pass is the whole file") {
        AovSet aovs(1, 1);
        for (const char *c : {"X", "Y", "Z"}) aovs.add_channel(std::string("P.") + c);
        CHECK(map.resolved(aovs).channel(Role::Depth) == "Z");
        AovSet rgb(1, 1);
        for (const char *c : {"R", "G", "B"}) rgb.add_channel(std::string("ViewLayer.unshadowed.") + c);
        CHECK(map.resolved(rgb).channels(Role::Beauty).front() == "R");
    }
    SECTION("a whole file under one view-layer prefix still resolves") {
        AovSet aovs(1, 1);
        for (const char *name : {"Z", "shadow.V", "P.X", "P.Y", "P.Z", "unshadowed.R", "unshadowed.G",
                                 "unshadowed.B", "Combined.R", "Combined.G", "Combined.B"})
            aovs.add_channel(std::string("ViewLayer.") + name);
        const ChannelMap found = map.resolved(aovs);
        CHECK(found.channel(Role::Depth) == "ViewLayer.Z");
        CHECK(found.channel(Role::Visibility) == "ViewLayer.shadow.V");
        CHECK(found.channels(Role::Position).back() == "ViewLayer.P.Z");
        CHECK(found.channels(Role::Beauty).front() == "ViewLayer.Combined.R");
    }
    SECTION("a prefix only some channels share is no view layer") {
        AovSet aovs(1, 1);
        aovs.add_channel("diffuse.R");
        aovs.add_channel("diffuse.G");
        aovs.add_channel("diffuse.B");
        aovs.add_channel("shadow.V");
        CHECK(map.resolved(aovs).channels(Role::Beauty).front() == "R");
    }
}

TEST_CASE("A --map layer replaces the role's layer and keeps only the component suffix", "[contract]") {
    ChannelMap map;
    map.set_override("ratio_u=myU");
    CHECK(map.channels(roles::RatioAnalytic) == std::vector<std::string>{"myU.R", "myU.G", "myU.B"});
    map.set_override("position=Pw");
    CHECK(map.channels(Role::Position) == std::vector<std::string>{"Pw.X", "Pw.Y", "Pw.Z"});
    map.set_override("maaf6_direct=ViewLayer.direct");
    CHECK(map.channels(roles::Maaf6Direct) ==
          std::vector<std::string>{"ViewLayer.direct.R", "ViewLayer.direct.G", "ViewLayer.direct.B"});
    // Every multi-channel role: the layer form gives distinct names, each under the layer.
    for (const RoleInfo &info : role_table()) {
        if (info.channels.size() < 2) continue;
        INFO(info.role.key);
        ChannelMap one;
        one.set_override(std::string(info.role.key) + "=L");
        const std::vector<std::string> &names = one.channels(info.role);
        CHECK(std::set<std::string>(names.begin(), names.end()).size() == names.size());
        for (const std::string &name : names) CHECK(name.rfind("L.", 0) == 0);
    }
}

TEST_CASE("A declared light count is checked against the channels present before it sizes anything",
          "[contract]") {
    std::map<std::string, AttributeValue> attributes;
    CHECK(ratio_light_count(attributes, 10) == 0);
    attributes[attr::kRatioLights] = 2;
    CHECK(ratio_light_count(attributes, 40) == 2);
    for (int count : {1000000, 2147483647}) {
        attributes[attr::kRatioLights] = count;
        CHECK_THROWS_AS(ratio_light_count(attributes, 40), InputError);
        CHECK_THROWS_WITH(ratio_light_count(attributes, 40), Catch::Contains("aaf:ratio:lights") &&
                                                                 Catch::Contains(std::to_string(count)) &&
                                                                 Catch::Contains("40 channels"));
    }
    attributes[attr::kRatioLights] = -1;
    CHECK_THROWS_AS(ratio_light_count(attributes, 40), InputError);
}

TEST_CASE("Blender's Vector pass is read as the contract's motion: x negated, y as it is", "[contract]") {
    // Cycles writes the previous frame's raster position minus this one's, y up
    // (tests/blender/cycles_sequence_test.sh checks it on a rendered sequence).
    CHECK(synonym_scale(Role::Motion, {"ViewLayer.Vector.X", "ViewLayer.Vector.Y"}) ==
          std::vector<float>{-1, 1});
    CHECK(synonym_scale(Role::Motion, {"View Layer.Vector.X", "View Layer.Vector.Y"}) ==
          std::vector<float>{-1, 1});
    CHECK(synonym_scale(Role::Motion, {"motion.X", "motion.Y"}) == std::vector<float>{1, 1});
    CHECK(synonym_scale(Role::Position, {"ViewLayer.Position.X", "ViewLayer.Position.Y",
                                         "ViewLayer.Position.Z"}) == std::vector<float>{1, 1, 1});
}
