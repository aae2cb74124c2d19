#include <catch2/catch.hpp>

#include <set>

#include "aaf/core/aov_contract.h"
#include "aaf/core/error.h"
#include "aaf/core/filter_aovs.h"
#include "aaf/core/method_registry.h"

using namespace aaf;

TEST_CASE("Role table has unique keys and channel names", "[contract]") {
    std::set<std::string> keys, channels;
    for (const RoleInfo &info : role_table()) {
        CHECK(keys.insert(info.key).second);
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
