// camdyn — SceneError, the error of bad user input: a scene file, a --set override, a cam
// spec, a lift table. It names the file, line, key, value and the rule broken.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace camdyn {

/// Bad user input. what() is "FILE:LINE: key 'KEY' = VALUE: RULE" (line omitted if unknown).
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string file, int line, std::string key, std::string value, std::string rule)
      : std::runtime_error(message(file, line, key, value, rule)),
        file_(std::move(file)),
        key_(std::move(key)),
        value_(std::move(value)),
        rule_(std::move(rule)),
        line_(line) {}
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& key() const { return key_; }
  const std::string& value() const { return value_; }
  const std::string& rule() const { return rule_; }

 private:
  static std::string message(const std::string& file, int line, const std::string& key, const std::string& value,
                             const std::string& rule) {
    std::string m = file;
    if (line > 0) m += ":" + std::to_string(line);
    m += ": ";
    if (!key.empty()) m += "key '" + key + "' = " + value + ": ";
    m += rule;
    return m;
  }
  std::string file_, key_, value_, rule_;
  int line_;
};

}  // namespace camdyn
