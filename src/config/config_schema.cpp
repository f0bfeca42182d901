#include "config/config_schema.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>

#include "core/error.hpp"

namespace revisit {
namespace {

std::size_t EditDistance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

std::string FormatNumber(double value) {
    std::ostringstream out;
    out << std::setprecision(10) << value;
    return out.str();
}

template <typename T>
T Convert(const YAML::Node& value, const std::string& where, const char* type) {
    try {
        return value.as<T>();
    } catch (const YAML::Exception&) {
        throw ConfigError(where + ": expected " + type + ", got '" + YAML::Dump(value) + "'");
    }
}

}  // namespace

void ConfigSchema::Add(std::string key, Field field, std::string unit, std::string doc, std::optional<Range> range) {
    // Keys are "section.name": the dump writes one YAML map per section.
    if (key.find('.') == std::string::npos || key.find('.') != key.rfind('.') || index_.count(key)) {
        throw ConfigError("internal: bad or duplicate config key '" + key + "'");
    }
    index_[key] = entries_.size();
    entries_.push_back(Entry{std::move(key), std::move(field), std::move(unit), std::move(doc), range});
}

std::string ConfigSchema::ClosestKey(const std::string& key) const {
    std::string best;
    std::size_t best_distance = static_cast<std::size_t>(-1);
    for (const auto& entry : entries_) {
        // Compare with the full key and with its last part, so a misplaced key is still found.
        const std::string leaf = entry.key.substr(entry.key.rfind('.') + 1);
        const std::string key_leaf = key.substr(key.rfind('.') + 1);
        const std::size_t d = std::min(EditDistance(key, entry.key), EditDistance(key_leaf, leaf) + 1);
        if (d < best_distance) {
            best_distance = d;
            best = entry.key;
        }
    }
    return best;
}

void ConfigSchema::ThrowBadChoice(const std::string& key, const std::string& name, const std::string& names) {
    throw ConfigError(key + ": '" + name + "' is not one of: " + names);
}

std::optional<double> ConfigSchema::Number(const std::string& key) const {
    const auto it = index_.find(key);
    if (it == index_.end()) return std::nullopt;
    return std::visit(
        [](auto&& field) -> std::optional<double> {
            using F = std::decay_t<decltype(field)>;
            if constexpr (std::is_same_v<F, double*> || std::is_same_v<F, int*> || std::is_same_v<F, std::uint32_t*> ||
                          std::is_same_v<F, std::size_t*> || std::is_same_v<F, bool*>) {
                return static_cast<double>(*field);
            } else {
                return std::nullopt;
            }
        },
        entries_[it->second].field);
}

void ConfigSchema::SetValue(const Entry& entry, const YAML::Node& value, const std::string& source) {
    const std::string where = source + ": " + entry.key;
    assigned_.insert(entry.key);
    // `--set key=` and `key:` with nothing after it: an empty text, which is what text keys default to.
    if (value.IsNull() && std::holds_alternative<std::string*>(entry.field)) {
        std::get<std::string*>(entry.field)->clear();
        return;
    }
    if (!value.IsScalar()) throw ConfigError(where + ": expected a single value, got '" + YAML::Dump(value) + "'");
    const auto check_range = [&](double v) {
        if (!std::isfinite(v)) throw ConfigError(where + ": value must be finite");
        if (entry.range && (v < entry.range->min || v > entry.range->max)) {
            throw ConfigError(where + ": " + FormatNumber(v) + " is out of range [" + FormatNumber(entry.range->min) +
                              ", " + FormatNumber(entry.range->max) + "]");
        }
    };
    std::visit(
        [&](auto&& field) {
            using F = std::decay_t<decltype(field)>;
            if constexpr (std::is_same_v<F, double*>) {
                const double v = Convert<double>(value, where, "a number");
                check_range(v);
                *field = v;
            } else if constexpr (std::is_same_v<F, int*> || std::is_same_v<F, std::uint32_t*> ||
                                 std::is_same_v<F, std::size_t*>) {
                using T = std::remove_pointer_t<F>;
                const long long v = Convert<long long>(value, where, "an integer");
                check_range(static_cast<double>(v));
                if (v < static_cast<long long>(std::numeric_limits<T>::min()) ||
                    (v > 0 && static_cast<unsigned long long>(v) > static_cast<unsigned long long>(std::numeric_limits<T>::max()))) {
                    throw ConfigError(where + ": " + std::to_string(v) + " does not fit the parameter's type");
                }
                *field = static_cast<T>(v);
            } else if constexpr (std::is_same_v<F, bool*>) {
                *field = Convert<bool>(value, where, "true or false");
            } else if constexpr (std::is_same_v<F, std::string*>) {
                *field = value.Scalar();
            } else {
                try {
                    field.set(value.Scalar());
                } catch (const ConfigError& e) {
                    throw ConfigError(source + ": " + e.what());
                }
            }
        },
        entry.field);
}

void ConfigSchema::Walk(const YAML::Node& node, const std::string& prefix, const std::string& source) {
    for (const auto& item : node) {
        const std::string key = prefix.empty() ? item.first.as<std::string>() : prefix + "." + item.first.as<std::string>();
        const auto it = index_.find(key);
        if (it != index_.end()) {
            SetValue(entries_[it->second], item.second, source);
        } else if (item.second.IsMap()) {
            Walk(item.second, key, source);
        } else {
            throw ConfigError(source + ": unknown key '" + key + "'; did you mean '" + ClosestKey(key) + "'?");
        }
    }
}

void ConfigSchema::Apply(const YAML::Node& root, const std::string& source) {
    if (!root || root.IsNull()) return;
    if (!root.IsMap()) throw ConfigError(source + ": expected a YAML map of sections");
    Walk(root, "", source);
}

void ConfigSchema::ApplyFile(const std::string& file) {
    // A folder opens as a stream and fails later with the C++ library's words: named here instead.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) {
        throw ConfigError(file + ": " + (std::filesystem::is_directory(file, ec) ? "is a folder, not a config file"
                                                                                : "cannot open config file"));
    }
    YAML::Node root;
    try {
        root = YAML::LoadFile(file);
    } catch (const YAML::BadFile&) {
        throw ConfigError(file + ": cannot open config file");
    } catch (const YAML::Exception& e) {
        throw ConfigError(file + ":" + std::to_string(e.mark.line + 1) + ": invalid YAML: " + e.msg);
    } catch (const std::exception& e) {
        throw ConfigError(file + ": cannot read config file: " + e.what());
    }
    try {
        Apply(root, file);
    } catch (const YAML::Exception& e) {  // e.g. a key that is a list: the schema walk cannot name it
        throw ConfigError(file + ":" + std::to_string(e.mark.line + 1) + ": unexpected YAML: " + e.msg);
    }
}

void ConfigSchema::ApplyOverride(const std::string& assignment) {
    const auto equals = assignment.find('=');
    if (equals == std::string::npos || equals == 0) throw ConfigError("--set " + assignment + ": expected key=value");
    const std::string key = assignment.substr(0, equals);
    const auto it = index_.find(key);
    if (it == index_.end()) throw ConfigError("--set: unknown key '" + key + "'; did you mean '" + ClosestKey(key) + "'?");
    YAML::Node value;
    try {
        value = YAML::Load(assignment.substr(equals + 1));
    } catch (const YAML::Exception& e) {
        throw ConfigError("--set " + key + ": invalid value: " + e.msg);
    }
    SetValue(entries_[it->second], value, "--set");
}

namespace {
/// A text value as YAML (double-quoted, escaped by yaml-cpp's emitter): quotes, backslashes, '#',
/// control characters read back as written.
std::string QuotedText(const std::string& text) {
    YAML::Emitter out;
    out << YAML::DoubleQuoted << text;
    return out.c_str();
}
}  // namespace

std::string ConfigSchema::Dump() const {
    std::ostringstream out;
    std::string section;
    for (const auto& entry : entries_) {
        const auto dot = entry.key.find('.');
        const std::string entry_section = entry.key.substr(0, dot);
        if (entry_section != section) {
            section = entry_section;
            out << (out.tellp() > 0 ? "\n" : "") << section << ":\n";
        }
        std::string value = std::visit(
            [](auto&& field) -> std::string {
                using F = std::decay_t<decltype(field)>;
                if constexpr (std::is_same_v<F, double*>) return FormatNumber(*field);
                else if constexpr (std::is_same_v<F, int*> || std::is_same_v<F, std::uint32_t*> ||
                                   std::is_same_v<F, std::size_t*>) return std::to_string(*field);
                else if constexpr (std::is_same_v<F, bool*>) return *field ? "true" : "false";
                else if constexpr (std::is_same_v<F, std::string*>) return QuotedText(*field);
                else return field.get();
            },
            entry.field);
        std::string comment = entry.doc;
        if (!entry.unit.empty()) comment = "[" + entry.unit + "] " + comment;
        if (entry.range) comment += " (range " + FormatNumber(entry.range->min) + " .. " + FormatNumber(entry.range->max) + ")";
        if (const auto* choice = std::get_if<Choice>(&entry.field)) {
            std::string names;
            for (const auto& n : choice->names) names += (names.empty() ? "" : " | ") + n;
            comment += " (" + names + ")";
        }
        out << "  " << entry.key.substr(dot + 1) << ": " << value << "  # " << comment << '\n';
    }
    return out.str();
}

}  // namespace revisit
