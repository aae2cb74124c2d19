// Properties every registered method must have, run over the registry as
// pbrt-v4's filters_test.cpp runs over its filters: a method added in one
// file (see toy_box_blur.cpp) is tested without a line here.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "aaf/core/framework/filter_aovs.h"
#include "aaf/core/framework/method_registry.h"
#include "aaf/core/util/error.h"
#include "aaf/trace/render.h"

using namespace aaf;

namespace {

/// A small render with every AOV the tracer writes; roles it cannot write
/// get a plausible constant, so a future method with its own AOVs still runs.
const AovSet &realistic_input() {
    static const AovSet aovs = [] {
        trace::RenderSettings settings;
        settings.width = 40;
        settings.height = 30;
        settings.spp = 4;
        settings.aovs = trace::AovGroups::every();  // every registered group, a plug-in's too
        AovSet rendered = trace::render_scene("grids", settings);
        for (const RoleInfo &role : role_table())
            for (const std::string &name : role.channels)
                if (!rendered.has_channel(name)) rendered.add_channel(name, 0.5f);
        return rendered;
    }();
    return aovs;
}

std::vector<Role> input_roles(const MethodInfo &info) {
    std::vector<Role> roles = info.roles.required;
    roles.insert(roles.end(), info.roles.optional.begin(), info.roles.optional.end());
    return roles;
}

AovSet run_method(const Method &method, const AovSet &input, int threads = 0) {
    AovSet out;
    // Lets a 1- or 2-core machine still run 3 workers.
    const tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 4);
    tbb::task_arena arena(threads == 0 ? tbb::task_arena::automatic : threads);
    arena.execute([&] { out = filter_aovs(method, input, ChannelMap{}, method.default_parameters()); });
    return out;
}

bool same_bytes(const AovSet::Plane &a, const AovSet::Plane &b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

const AovSet::Plane &plane(const AovSet &aovs, const std::string &name) {
    return aovs.plane(aovs.index_of(name));
}

/// Channels `method` may write: its output roles and, when it composes a beauty, the kept noisy beauty.
std::set<std::string> writable_channels(const MethodInfo &info) {
    std::set<std::string> names;
    for (Role role : info.roles.outputs) {
        for (const std::string &name : role_info(role).channels) names.insert(name);
        if (role == Role::Beauty)
            for (const std::string &name : role_info(Role::NoisyBeauty).channels) names.insert(name);
    }
    return names;
}

}  // namespace

TEST_CASE("Every method: the registry holds the built-ins and the test plug-in, with valid declarations",
          "[methods]") {
    std::set<std::string> names;
    for (const Method *method : methods()) {
        const MethodInfo &info = method->info();
        INFO(info.name);
        CHECK(names.insert(info.name).second);
        CHECK_FALSE(info.summary.empty());
        CHECK_FALSE(info.roles.outputs.empty());
        for (const auto &pair : info.roles.filtered) {
            CHECK(std::count(info.roles.outputs.begin(), info.roles.outputs.end(), pair.second) == 1);
            const std::vector<Role> inputs = input_roles(info);
            CHECK(std::count(inputs.begin(), inputs.end(), pair.first) == 1);
        }
        const ParameterSet defaults = method->default_parameters();  // throws if a default is invalid
        for (const ParameterInfo &p : info.parameters) CHECK(defaults.text(p.name) != "");
        // A delegate is another registered method, with parameters it has and values it takes.
        for (const MethodDelegate &delegate : info.delegates) {
            CHECK(delegate.method != info.name);
            CHECK_FALSE(delegate.why.empty());
            CHECK_NOTHROW(delegate_command(delegate));
        }
    }
    CHECK(names.count("aaf") == 1);
    CHECK(names.count("gaussian") == 1);
    CHECK(names.count("toy_box") == 1);
    CHECK_THROWS_WITH(find_method("nonesuch"), Catch::Contains("aaf") && Catch::Contains("toy_box"));
}

namespace {

/// A method that only declares roles, to test what registration accepts.
class DeclaringMethod final : public Method {
  public:
    DeclaringMethod(std::string name, std::vector<RoleInfo> declared) {
        info_.name = std::move(name);
        info_.roles.declared = std::move(declared);
        info_.roles.outputs = {Role::FilteredVisibility};
    }
    const MethodInfo &info() const override { return info_; }
    void run(const MethodImages &, const ParameterSet &, Progress &) const override {}

  private:
    MethodInfo info_;
};

}  // namespace

TEST_CASE("Every role is declared once: a method declaring a taken or malformed key is refused",
          "[methods]") {
    const std::size_t before = methods().size(), roles = role_table().size();
    const auto declare = [](const char *key) {
        return std::make_unique<DeclaringMethod>(
            "declares_" + std::string(key[0] ? "x" : "empty"),
            std::vector<RoleInfo>{{Role{key}, {"declared.V"}, "", "a test role"}});
    };
    CHECK_THROWS_WITH(MethodRegistration(declare("visibility")),
                      Catch::Contains("'visibility'") && Catch::Contains("already declared"));  // shared
    CHECK_THROWS_WITH(MethodRegistration(declare("maaf_wedge")),
                      Catch::Contains("already declared"));  // maaf's own
    CHECK_THROWS_WITH(MethodRegistration(declare("toy_hit")),
                      Catch::Contains("already declared"));  // a plug-in's
    CHECK_THROWS_WITH(MethodRegistration(declare("Bad-Key")), Catch::Contains("lower-case"));
    CHECK_THROWS_WITH(MethodRegistration(declare("")), Catch::Contains("lower-case"));
    // Nothing refused was registered.
    CHECK(methods().size() == before);
    CHECK(role_table().size() == roles);
    // Each built-in role is declared by the shared contract or by the one method that owns it.
    std::set<std::string> keys;
    for (const RoleInfo &info : role_table()) CHECK(keys.insert(info.role.key).second);
    CHECK(role_info(Role{"toy_hit"}).channels == std::vector<std::string>{"toy.hit"});
    CHECK_THROWS_WITH(role_info(Role{"nonesuch"}), Catch::Contains("'nonesuch'"));
}

TEST_CASE("Every method: a constant input stays that constant", "[methods]") {
    for (const Method *method : methods()) {
        const MethodInfo &info = method->info();
        for (const auto &[from, to] : info.roles.filtered) {
            INFO(info.name << ": " << from.key << " -> " << to.key);
            AovSet input = realistic_input();
            const float constant = 0.3725f;
            for (const std::string &name : role_info(from).channels) {
                PlaneView view = input.channel(name);
                std::fill(view.data, view.data + input.pixel_count(), constant);
            }
            const AovSet out = run_method(*method, input);
            for (const std::string &name : role_info(to).channels) {
                float worst = 0;
                for (float v : plane(out, name)) worst = std::max(worst, std::abs(v - constant));
                CHECK(worst <= 2e-6f * constant);
            }
        }
    }
}

TEST_CASE("Every method: 1 and 3 threads give identical bytes", "[methods]") {
    for (const Method *method : methods()) {
        INFO(method->info().name);
        const AovSet one = run_method(*method, realistic_input(), 1);
        const AovSet three = run_method(*method, realistic_input(), 3);
        REQUIRE(one.channel_names() == three.channel_names());
        for (std::size_t c = 0; c < one.channel_names().size(); ++c) {
            INFO(one.channel_names()[c]);
            CHECK(same_bytes(one.plane(c), three.plane(c)));
        }
    }
}

TEST_CASE("Every method: nothing is written outside its output roles", "[methods]") {
    const AovSet &input = realistic_input();
    for (const Method *method : methods()) {
        INFO(method->info().name);
        const std::set<std::string> writable = writable_channels(method->info());
        const AovSet out = run_method(*method, input);
        for (const std::string &name : out.channel_names()) {
            INFO(name);
            if (writable.count(name)) continue;
            REQUIRE(input.has_channel(name));  // no channel appears that is not an output
            CHECK(same_bytes(plane(out, name), plane(input, name)));
        }
        for (const std::string &name : input.channel_names())
            CHECK(out.has_channel(name));  // nothing dropped
        // Every attribute is kept, but what the tracer's beauty held once the beauty is filtered.
        std::map<std::string, AttributeValue> expected = input.attributes;
        const std::vector<Role> &outputs = method->info().roles.outputs;
        if (std::find(outputs.begin(), outputs.end(), Role::Beauty) != outputs.end())
            expected.erase(attr::kBeauty);
        CHECK(out.attributes == expected);
    }
}

TEST_CASE("Every method that composes a beauty keeps the input's as the noisy beauty, moved, not copied",
          "[methods]") {
    const std::vector<std::string> &beauty = role_info(Role::Beauty).channels;
    const std::vector<std::string> &noisy = role_info(Role::NoisyBeauty).channels;
    REQUIRE(beauty.size() == noisy.size());
    for (const Method *method : methods()) {
        const std::vector<Role> &outputs = method->info().roles.outputs;
        if (std::find(outputs.begin(), outputs.end(), Role::Beauty) == outputs.end()) continue;
        INFO(method->info().name);
        AovSet input = realistic_input();
        std::vector<const float *> storage;
        for (const std::string &name : beauty) storage.push_back(plane(input, name).data());
        const AovSet out = filter_aovs(*method, std::move(input), ChannelMap{}, method->default_parameters());
        for (std::size_t c = 0; c < beauty.size(); ++c) {
            INFO(noisy[c]);
            CHECK(same_bytes(plane(out, noisy[c]), plane(realistic_input(), beauty[c])));
            CHECK(plane(out, noisy[c]).data() == storage[c]);  // the input's plane itself: no copy
            CHECK(plane(out, beauty[c]).data() != storage[c]);
        }
    }
}

TEST_CASE("Every method: a NaN or infinite input stays in its own pixel", "[methods]") {
    const AovSet &clean = realistic_input();
    const int bad_x = 20, bad_y = 22;  // on the ground, inside the grids' shadows
    const float bad_values[] = {std::nanf(""), INFINITY, -INFINITY};
    for (const Method *method : methods()) {
        const AovSet reference = run_method(*method, clean);
        for (Role role : input_roles(method->info())) {
            // Every channel of the role gets a bad value and the role's first
            // channel gets all three: a role's channels go through the same
            // code, and maaf6's 200-odd sum channels times three values took
            // most of the suite's time under the sanitizers.
            std::vector<std::pair<std::string, float>> cases;
            const std::vector<std::string> &channels = role_info(role).channels;
            for (std::size_t c = 0; c < channels.size(); ++c) {
                if (c == 0)
                    for (float bad : bad_values) cases.emplace_back(channels[c], bad);
                else
                    cases.emplace_back(channels[c], bad_values[c % 3]);
            }
            for (const auto &[name, bad] : cases) {
                INFO(method->info().name << ": " << name << " = " << bad);
                AovSet input = clean;
                input.channel(name)(bad_x, bad_y) = bad;
                const AovSet out = run_method(*method, input);
                for (const std::string &written : writable_channels(method->info())) {
                    if (!out.has_channel(written)) continue;
                    const ConstPlaneView before = reference.channel(written), after = out.channel(written);
                    int spread = 0;
                    for (int y = 0; y < out.height(); ++y)
                        for (int x = 0; x < out.width(); ++x)
                            if ((x != bad_x || y != bad_y) && std::isfinite(before(x, y)) &&
                                !std::isfinite(after(x, y)))
                                ++spread;
                    CHECK(spread == 0);
                }
            }
        }
    }
}

TEST_CASE("Every method: unknown or out-of-range parameters give a one-line error", "[methods]") {
    auto one_line_error = [](const std::function<void()> &call, const std::string &mention) {
        try {
            call();
        } catch (const Error &e) {
            const std::string message = e.what();
            CHECK(message.find('\n') == std::string::npos);
            CHECK_THAT(message, Catch::Contains(mention));
            return;
        }
        FAIL("no error for " << mention);
    };
    for (const Method *method : methods()) {
        const MethodInfo &info = method->info();
        INFO(info.name);
        ParameterSet parameters = method->default_parameters();
        one_line_error([&] { parameters.set("no_such_parameter", std::string("1")); }, "no_such_parameter");
        for (const ParameterInfo &p : info.parameters) {
            INFO(p.name);
            if (p.type == ParameterType::Bool || p.type == ParameterType::Choice) {
                one_line_error([&] { parameters.set(p.name, std::string("not-a-value")); }, p.name);
                continue;
            }
            one_line_error([&] { parameters.set(p.name, std::string("abc")); }, p.name);
            if (std::isfinite(p.min)) one_line_error([&] { parameters.set(p.name, p.min - 1); }, p.name);
            if (std::isfinite(p.max)) one_line_error([&] { parameters.set(p.name, p.max + 1); }, p.name);
            if (p.type == ParameterType::Int)
                one_line_error([&] { parameters.set(p.name, p.min + 0.5); }, p.name);
        }
        CHECK(parameters.infos().size() == info.parameters.size());  // failed sets changed nothing
        for (const ParameterInfo &p : info.parameters)
            CHECK(parameters.text(p.name) == method->default_parameters().text(p.name));
    }
}

TEST_CASE("Every method: progress rises to 1, and a monitor that says stop cancels the run", "[methods]") {
    for (const Method *method : methods()) {
        INFO(method->info().name);
        std::vector<double> reported;
        filter_aovs(*method, realistic_input(), ChannelMap{}, method->default_parameters(), [&](double f) {
            reported.push_back(f);
            return true;
        });
        REQUIRE(reported.size() >= 2);
        CHECK(std::is_sorted(reported.begin(), reported.end()));
        CHECK(reported.front() == 0.0);
        CHECK(reported.back() == 1.0);
        CHECK_THROWS_AS(filter_aovs(*method, realistic_input(), ChannelMap{}, method->default_parameters(),
                                    [](double) { return false; }),
                        Cancelled);
    }
}

TEST_CASE("Every method: a missing required input is named in a one-line input error", "[methods]") {
    for (const Method *method : methods()) {
        const MethodInfo &info = method->info();
        for (Role role : info.roles.required) {
            INFO(info.name << ": " << role.key);
            const AovSet &full = realistic_input();
            AovSet input(full.width(), full.height());
            input.attributes = full.attributes;
            std::vector<std::string> drop = role_info(role).channels;
            // Without the roles only its delegates need: a render they could filter is handed to them.
            for (const MethodDelegate &delegate : info.delegates)
                for (Role other : find_method(delegate.method).info().roles.required)
                    if (std::find(info.roles.required.begin(), info.roles.required.end(), other) ==
                        info.roles.required.end())
                        drop.insert(drop.end(), role_info(other).channels.begin(),
                                    role_info(other).channels.end());
            for (std::size_t c = 0; c < full.channel_names().size(); ++c)
                if (std::find(drop.begin(), drop.end(), full.channel_names()[c]) == drop.end())
                    std::copy(full.plane(c).begin(), full.plane(c).end(),
                              input.add_channel(full.channel_names()[c]).data);
            CHECK_THROWS_AS(run_method(*method, input), InputError);
            CHECK_THROWS_WITH(run_method(*method, input), Catch::Contains(std::string("'") + role.key + "'"));
        }
    }
}

TEST_CASE(
    "Every method with a delegate: a render made for the delegate gives the delegate's output, byte for byte",
    "[methods]") {
    for (const Method *method : methods()) {
        const MethodInfo &info = method->info();
        for (const MethodDelegate &delegate : info.delegates) {
            INFO(info.name << " -> " << delegate.method);
            const Method &other = find_method(delegate.method);
            // Without the roles only `method` needs: the render is the delegate's. A delegate that
            // needs every role `method` does could never be chosen (a declaration to fix).
            std::vector<std::string> drop;
            for (Role role : info.roles.required)
                if (std::find(other.info().roles.required.begin(), other.info().roles.required.end(), role) ==
                    other.info().roles.required.end())
                    drop.insert(drop.end(), role_info(role).channels.begin(), role_info(role).channels.end());
            REQUIRE_FALSE(drop.empty());
            const AovSet &full = realistic_input();
            AovSet input(full.width(), full.height());
            input.attributes = full.attributes;
            for (std::size_t c = 0; c < full.channel_names().size(); ++c)
                if (std::find(drop.begin(), drop.end(), full.channel_names()[c]) == drop.end())
                    std::copy(full.plane(c).begin(), full.plane(c).end(),
                              input.add_channel(full.channel_names()[c]).data);

            ParameterSet parameters = other.default_parameters();
            for (const auto &[name, value] : delegate.parameters) parameters.set(name, value);
            const AovSet handed = run_method(*method, input);
            const AovSet direct = filter_aovs(other, input, ChannelMap{}, parameters);
            REQUIRE(handed.channel_names() == direct.channel_names());
            for (const std::string &name : handed.channel_names()) {
                INFO(name);
                CHECK(same_bytes(plane(handed, name), plane(direct, name)));
            }
        }
    }
}

TEST_CASE("Every method: a finite input gives a finite output, or an input error naming the channel",
          "[methods]") {
    // 3e38 is finite, near float's largest; single-precision products and sums of it overflow.
    const AovSet &clean = realistic_input();
    for (const Method *method : methods()) {
        const AovSet reference = run_method(*method, clean);
        for (Role role : input_roles(method->info())) {
            if (role == Role::ObjectId || role == Role::Motion) continue;  // ids and motion are not summed
            INFO(method->info().name << ": " << role.key << " = 3e38");
            AovSet input = clean;
            for (const std::string &name : role_info(role).channels) {
                PlaneView view = input.channel(name);
                std::fill(view.data, view.data + input.pixel_count(), 3e38f);
            }
            try {
                const AovSet out = run_method(*method, input);
                for (const std::string &written : writable_channels(method->info())) {
                    if (!out.has_channel(written)) continue;
                    const ConstPlaneView before = reference.channel(written), after = out.channel(written);
                    int overflowed = 0;
                    for (int y = 0; y < out.height(); ++y)
                        for (int x = 0; x < out.width(); ++x)
                            if (std::isfinite(before(x, y)) && !std::isfinite(after(x, y))) ++overflowed;
                    INFO(written);
                    CHECK(overflowed == 0);
                }
            } catch (const InputError &e) {
                const std::string message = e.what();
                bool names_channel = false;
                for (const std::string &name : role_info(role).channels)
                    names_channel = names_channel || message.find("'" + name + "'") != std::string::npos;
                INFO(message);
                CHECK(names_channel);
                CHECK(message.find('\n') == std::string::npos);
            }
        }
    }
}
