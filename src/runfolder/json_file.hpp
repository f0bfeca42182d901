#pragma once
/// The one way revisit writes JSON files (run.json, run_options.json, metrics.json, sessions.json,
/// ...): atomically (core/atomic_file.hpp), and never failing on text that is not UTF-8 (a dataset
/// path with Latin-1 bytes): such bytes are written as U+FFFD. Paths that must be read back exactly
/// go through PutPath/GetPath, which keep their bytes.
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace revisit {

/// Writes `value` indented by 2 with a final newline; invalid UTF-8 in strings becomes U+FFFD.
void WriteJsonFile(const std::filesystem::path& file, const nlohmann::json& value);

/// `value` as text (dump) that never throws on invalid UTF-8 (replaced by U+FFFD).
std::string JsonText(const nlohmann::json& value, int indent = 2);

/// Puts `path` under `key`: the path itself when it is valid UTF-8; otherwise a readable form (invalid
/// bytes as U+FFFD) under `key` and its exact bytes in hex under `key + "_bytes"`.
void PutPath(nlohmann::json& object, const std::string& key, const std::filesystem::path& path);

/// What PutPath put (the exact bytes when they were kept). Throws nlohmann::json exceptions as at().
std::filesystem::path GetPath(const nlohmann::json& object, const std::string& key);

/// True when `text` is valid UTF-8.
bool IsValidUtf8(const std::string& text);

}  // namespace revisit
