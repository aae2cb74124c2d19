// libaaf/AOV_CONTRACT.md's tables are generated from the code (roles,
// methods, synonyms, tracer groups): this test fails when the document and
// the code differ. scripts/update_contract_doc.sh runs it with
// AAF_UPDATE_CONTRACT_DOC=1 to rewrite the blocks instead.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "aaf/core/framework/contract_markdown.h"
#include "aaf/trace/render.h"

namespace {

const std::string kDocument = std::string(AAF_SOURCE_DIR) + "/libaaf/AOV_CONTRACT.md";

std::string begin_marker(const std::string &name) {
    return "<!-- BEGIN GENERATED " + name + " (scripts/update_contract_doc.sh) -->\n";
}

std::string end_marker(const std::string &name) {
    return "<!-- END GENERATED " + name + " -->\n";
}

/// Where block `name`'s content lies in `text`: [first, second).
std::pair<std::size_t, std::size_t> block_range(const std::string &text, const std::string &name) {
    const std::size_t begin = text.find(begin_marker(name));
    const std::size_t end = text.find(end_marker(name));
    REQUIRE(begin != std::string::npos);
    REQUIRE(end != std::string::npos);
    REQUIRE(begin < end);
    return {begin + begin_marker(name).size(), end};
}

}  // namespace

TEST_CASE("AOV_CONTRACT.md holds the contract as the code declares it", "[contract][doc]") {
    const std::vector<std::pair<std::string, std::string>> blocks = {
        {"synonyms", aaf::synonyms_markdown()},
        {"roles", aaf::roles_markdown()},
        {"methods", aaf::methods_markdown()},
        {"groups", aaf::trace::aov_groups_markdown()},
    };
    std::stringstream read;
    read << std::ifstream(kDocument).rdbuf();
    std::string text = read.str();
    REQUIRE_FALSE(text.empty());
    const bool update = std::getenv("AAF_UPDATE_CONTRACT_DOC") != nullptr;
    for (const auto &[name, generated] : blocks) {
        INFO("block '" << name << "' of " << kDocument << ": run scripts/update_contract_doc.sh");
        const auto [first, last] = block_range(text, name);
        if (update)
            text.replace(first, last - first, generated);
        else
            CHECK(text.substr(first, last - first) == generated);
    }
    if (update) std::ofstream(kDocument) << text;
}

TEST_CASE("The generated contract names every role and every registered method", "[contract][doc]") {
    const std::string roles = aaf::roles_markdown();
    // Visibility is read by both visibility filters, and by the others that correct the beauty with it.
    CHECK_THAT(roles, Catch::Contains("| `visibility` | `shadow.V` |") &&
                          Catch::Contains("the unoccluded fraction) | `aaf`, `gaussian`, `maaf (optional)`, "
                                          "`isg-shadow (optional)` | - |\n"));
    CHECK_THAT(roles,
               Catch::Contains("filtered visibility | - | `aaf`, `gaussian`, `maaf`, `isg-shadow` |\n"));
    const std::string methods = aaf::methods_markdown();
    CHECK_THAT(methods, Catch::Contains("### `aaf filter aaf`") &&
                            Catch::Contains("### `aaf filter gaussian`") &&
                            Catch::Contains("| `--mu` | 2 | - | > 0 |"));
    CHECK_THAT(aaf::trace::aov_groups_markdown(),
               Catch::Contains("| `shadow` |") && Catch::Contains("`aaf`, `gaussian`"));
}
