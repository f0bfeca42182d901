#pragma once
/// The one place where YAML becomes config structs: every parameter is registered once with its key,
/// unit, range and documentation; files and `--set key=value` overrides are checked against it.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace revisit {

class ConfigSchema {
  public:
    struct Range {
        double min = 0.0;
        double max = 0.0;
    };
    /// An enum parameter: the names users write and how to read/write the field.
    struct Choice {
        std::vector<std::string> names;
        std::function<std::string()> get;
        std::function<void(const std::string&)> set;
    };
    using Field = std::variant<double*, int*, std::uint32_t*, std::size_t*, bool*, std::string*, Choice>;

    struct Entry {
        std::string key;      ///< dotted, e.g. "odometry.max_range"
        Field field;
        std::string unit;     ///< e.g. "m", "deg", "" for counts and flags
        std::string doc;      ///< one line: meaning and the source of the default
        std::optional<Range> range;
    };

    void Add(std::string key, Field field, std::string unit, std::string doc, std::optional<Range> range = {});

    /// Template helper for enums: `names` in the order of `values`.
    template <typename E>
    void AddEnum(std::string key, E* field, std::vector<std::pair<std::string, E>> choices, std::string doc) {
        Choice choice;
        for (const auto& c : choices) choice.names.push_back(c.first);
        choice.get = [field, choices] {
            for (const auto& c : choices) {
                if (c.second == *field) return c.first;
            }
            return std::string("?");
        };
        choice.set = [key, field, choices](const std::string& name) {
            std::string names;
            for (const auto& c : choices) {
                if (c.first == name) {
                    *field = c.second;
                    return;
                }
                names += (names.empty() ? "" : ", ") + c.first;
            }
            ThrowBadChoice(key, name, names);
        };
        Add(std::move(key), std::move(choice), "", std::move(doc));
    }

    /// Applies a YAML document (nested maps). Throws ConfigError naming `source`, the key and the
    /// problem: an unknown key (with the closest valid one), a wrong type, or a value out of range.
    void Apply(const YAML::Node& root, const std::string& source);
    void ApplyFile(const std::string& file);
    /// `key=value` from the command line; the value is parsed as YAML (so `true`, `0.5`, `paper`).
    void ApplyOverride(const std::string& assignment);

    /// The full resolved configuration as commented YAML (unit, range and doc per key).
    std::string Dump() const;
    const std::vector<Entry>& entries() const { return entries_; }

    /// The valid key closest to `key` by edit distance (for "did you mean").
    std::string ClosestKey(const std::string& key) const;

    /// Keys given a value by a file or an override so far (what automatic settings must not change).
    const std::set<std::string>& assigned() const { return assigned_; }
    /// The current value of a numeric or boolean key as a number (nullopt for strings, enums, unknown keys).
    std::optional<double> Number(const std::string& key) const;

  private:
    [[noreturn]] static void ThrowBadChoice(const std::string& key, const std::string& name, const std::string& names);
    void SetValue(const Entry& entry, const YAML::Node& value, const std::string& source);
    void Walk(const YAML::Node& node, const std::string& prefix, const std::string& source);

    std::vector<Entry> entries_;
    std::map<std::string, std::size_t> index_;
    std::set<std::string> assigned_;
};

}  // namespace revisit
