#pragma once

#include <string>

namespace aaf {

/// The AOV contract as Markdown tables, generated from the code so the
/// documentation cannot drift from it: libaaf/AOV_CONTRACT.md holds these
/// blocks verbatim (a test checks it; scripts/update_contract_doc.sh rewrites them).

/// Every role (role_table()): key, default channels, units, meaning, and
/// which registered methods read and write it.
std::string roles_markdown();
/// Every registered method: required, optional and written roles, required
/// header attributes, and parameters with defaults, units and ranges.
std::string methods_markdown();
/// Other renderers' names tried for each role (role_synonyms()).
std::string synonyms_markdown();

}  // namespace aaf
