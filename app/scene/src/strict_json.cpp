// JSON for people: a SAX reader that builds the document while keeping the containers it is
// in, so overflowing numbers and duplicate keys can be reported where they are. The JSON path
// is spelled out only for an error message, and nesting is limited to kMaxJsonDepth levels, so
// memory stays linear in the size of the file.
#include "app/scene/strict_json.hpp"

#include <optional>
#include <utility>
#include <vector>

#include "base/errors.hpp"

namespace tumble::app {
namespace {

using nlohmann::json;

/// Line and column (1-based) after the first `bytes` characters of `text`.
std::pair<std::size_t, std::size_t> line_and_column(const std::string& text, std::size_t bytes) {
  std::size_t line = 1, column = 0;
  for (std::size_t i = 0; i < bytes && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 0;
    } else {
      ++column;
    }
  }
  return {line, column == 0 ? 1 : column};
}

/// nlohmann's message without its "[json.exception...] parse error at line L, column C: ".
std::string parse_error_reason(const std::string& what) {
  const std::size_t at = what.find("column ");
  if (at != std::string::npos) {
    const std::size_t colon = what.find(": ", at);
    if (colon != std::string::npos) return what.substr(colon + 2);
  }
  return what;
}

/// Builds the document from SAX events, tracking the path of every container.
class Builder : public nlohmann::json_sax<json> {
 public:
  struct Failure {
    std::optional<std::size_t> position;  ///< bytes read (syntax errors and overflow only)
    std::string path;                     ///< JSON path, empty for syntax errors
    std::string message;
  };

  json root;
  std::optional<Failure> failure;

  bool null() override { return put(nullptr); }
  bool boolean(bool value) override { return put(value); }
  bool number_integer(number_integer_t value) override { return put(value); }
  bool number_unsigned(number_unsigned_t value) override { return put(value); }
  bool number_float(number_float_t value, const string_t&) override { return put(value); }
  bool string(string_t& value) override { return put(std::move(value)); }
  bool binary(binary_t& value) override { return put(json::binary(std::move(value))); }

  bool start_object(std::size_t) override { return open(json::object()); }
  bool start_array(std::size_t) override { return open(json::array()); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& name) override {
    Container& top = stack_.back();
    top.key = name;
    if (top.value->contains(name)) {
      failure = Failure{std::nullopt, next_path(), "duplicate key (each key may appear once)"};
      return false;
    }
    return true;
  }

  bool parse_error(std::size_t position, const std::string& token,
                   const nlohmann::detail::exception& error) override {
    if (error.id == 406 && position >= token.size()) {  // number overflow: point at its start
      failure =
          Failure{position - token.size() + 1, next_path(),
                  "expected a finite number, got " + token + " (beyond the range of a double)"};
    } else {
      failure = Failure{position, "", "malformed JSON: " + parse_error_reason(error.what())};
    }
    return false;
  }

 private:
  struct Container {
    json* value;
    std::string key;  ///< the key of the next member (objects)
  };

  /// The path of the value about to be placed, spelled out from the open containers (only for
  /// error messages: keeping it per container would cost the square of the depth).
  std::string next_path() const {
    std::string path;
    for (const Container& container : stack_) {
      if (container.value->is_array()) {
        // An open container's last element is the one being built; the innermost's next
        // element is the one about to be placed.
        const bool innermost = &container == &stack_.back();
        const std::size_t size = container.value->size();
        path += "[" + std::to_string(innermost ? size : size - 1) + "]";
      } else {
        path += (path.empty() ? "" : ".") + container.key;
      }
    }
    return path;
  }

  /// Places `value` in the innermost container (or at the root) and returns where it went.
  json* place(json value) {
    if (stack_.empty()) {
      root = std::move(value);
      return &root;
    }
    json& parent = *stack_.back().value;
    if (parent.is_array()) {
      parent.push_back(std::move(value));
      return &parent.back();
    }
    json& slot = parent[stack_.back().key];
    slot = std::move(value);
    return &slot;
  }

  bool put(json value) {
    place(std::move(value));
    return true;
  }

  bool open(json container) {
    if (stack_.size() >= kMaxJsonDepth) {
      failure = Failure{
          std::nullopt, next_path(),
          "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels of arrays and objects"};
      return false;
    }
    json* where = place(std::move(container));
    stack_.push_back({where, ""});
    return true;
  }

  bool close() {
    stack_.pop_back();
    return true;
  }

  std::vector<Container> stack_;
};

}  // namespace

json parse_strict_json(const std::string& text, const std::string& source) {
  Builder builder;
  const bool ok = json::sax_parse(text, &builder, json::input_format_t::json, /*strict=*/true,
                                  /*ignore_comments=*/true);
  if (ok && !builder.failure) return std::move(builder.root);
  const Builder::Failure failure =
      builder.failure.value_or(Builder::Failure{std::nullopt, "", "malformed JSON"});
  std::string where = source;
  if (failure.position) {
    const auto [line, column] = line_and_column(text, *failure.position);
    where += ":" + std::to_string(line) + ":" + std::to_string(column);
  }
  if (!failure.path.empty()) where += ": " + failure.path;
  throw tumble::InputError(where + ": " + failure.message);
}

}  // namespace tumble::app
