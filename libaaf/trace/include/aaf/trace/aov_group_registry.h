#pragma once

#include <initializer_list>
#include <map>
#include <string>
#include <vector>

#include "aaf/core/contract/aov_contract.h"
#include "aaf/core/framework/parameters.h"

namespace aaf::trace {

/// What an AOV group of the tracer (`aaf render --aovs`) declares: the one
/// place its name, channels, roles and settings are said. Each group is an
/// accumulator (libaaf/trace/aov_group.h) that returns its declaration; the
/// `--aovs` option and its help, the group options of `aaf render`, the
/// provenance, `aaf info`'s recipes, libaaf/AOV_CONTRACT.md's group table and
/// the property tests are made from the registered declarations.
struct AovGroupInfo {
    std::string name;      ///< as `--aovs` spells it: lower-case letters, digits, _ or -
    std::string contents;  ///< its channels, in words
    /// The roles whose channels it writes (aov_contract.h); empty for a group
    /// whose channels are the tracer's own state (progress).
    std::vector<Role> roles;
    /// Its own settings (RenderSettings::group_parameters), each an option of
    /// `aaf render` spelled as ParameterInfo::option_name(); snake_case names
    /// unique over every group.
    std::vector<ParameterInfo> parameters;
    /// Why a render with it cannot be resumed ("they trace their own
    /// samples"); empty when it can.
    std::string not_resumable_because;
};

/// Every registered group's declaration, in the order their channels are
/// written: the built-in ones (libaaf/trace/aov_group.cpp), then those
/// registered with AovGroupRegistration (aov_group.h). The beauty, which
/// every render writes, is not a group.
const std::vector<AovGroupInfo> &aov_group_table();
/// The group called `name`; throws aaf::Error listing the known names.
const AovGroupInfo &find_aov_group(const std::string &name);

/// A set of registered AOV groups, by name, kept in aov_group_table()'s order
/// (so that equal sets compare and print equal).
class AovGroups {
  public:
    AovGroups() = default;
    /// The groups called `names`; throws aaf::Error for a name no group has.
    AovGroups(std::initializer_list<std::string> names);
    explicit AovGroups(const std::vector<std::string> &names);

    /// Every registered group: what `--aovs all` renders.
    static AovGroups every();

    bool contains(const std::string &group) const;
    /// Whether every group of `other` is in this set.
    bool contains(const AovGroups &other) const;
    bool empty() const { return names_.empty(); }
    /// The names in aov_group_table()'s order.
    const std::vector<std::string> &names() const { return names_; }
    /// The names comma-separated, as `--aovs` reads them ("shadow,position"); "" for none.
    std::string text() const;

    AovGroups &insert(const std::string &group);
    AovGroups &operator|=(const AovGroups &other);
    friend AovGroups operator|(AovGroups a, const AovGroups &b) { return a |= b; }
    /// The groups of this set that are not in `other`.
    AovGroups without(const AovGroups &other) const;

    bool operator==(const AovGroups &other) const { return names_ == other.names_; }
    bool operator!=(const AovGroups &other) const { return names_ != other.names_; }

  private:
    std::vector<std::string> names_;
};

/// The values of the groups' own parameters (AovGroupInfo::parameters), each
/// at its declared default until set.
class AovGroupParameters {
  public:
    /// The values of group `group`'s parameters. Throws aaf::Error for a
    /// group that is not registered.
    const ParameterSet &of(const std::string &group) const;
    /// The same, to set (ParameterSet::set checks the name and the range).
    ParameterSet &of(const std::string &group);

  private:
    std::map<std::string, ParameterSet> values_;  ///< the groups given values; others are at their defaults
};

/// Parses a comma-separated list of `--aovs` entries: "all" (every
/// registered group), a registered method's name (method_registry.h: the
/// groups it reads, aov_groups_for_method) and a group's name (the group
/// with what its readers read, aov_groups_with_readers); a name that is both
/// a method's and a group's is read as the method's. Throws aaf::Error naming
/// an unknown entry.
AovGroups parse_aov_groups(const std::string &list);
/// The group `group` and the groups every method reading one of its own
/// roles (one no other group shares: not in shared_roles()) reads, so that
/// `--aovs isg` feeds isg-shadow, isg-glossy and isg-dof; `--aovs shadow`,
/// whose roles are shared, is the shadow group alone. Throws aaf::Error for
/// an unknown group.
AovGroups aov_groups_with_readers(const std::string &group);
/// The groups that write any of `roles` (aov_contract.h), e.g. those a
/// method's declared inputs need; the progress group writes no role.
AovGroups aov_groups_writing(const std::vector<Role> &roles);
/// The groups that write the required inputs of the registered method
/// `method` (its declaration is the one place that says what it reads);
/// throws aaf::Error for an unknown method.
AovGroups aov_groups_for_method(const std::string &method);
/// The groups as a Markdown table (name, channels, roles, the methods whose
/// `--aovs METHOD` includes it), a generated block of libaaf/AOV_CONTRACT.md.
std::string aov_groups_markdown();

}  // namespace aaf::trace
