#include "io/schema_validation.hpp"

#include "io/printable.hpp"
#include "rbla/embedded_schemas.hpp"

#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>

namespace rbla::io {
namespace {

std::unique_ptr<valijson::Schema> parse_schema(const nlohmann::json& document) {
  auto schema = std::make_unique<valijson::Schema>();
  valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
  valijson::adapters::NlohmannJsonAdapter adapter(document);
  parser.populateSchema(adapter, *schema);
  return schema;
}

struct Schemas {
  nlohmann::json model_document, result_document;
  std::unique_ptr<valijson::Schema> model, result;
};

const Schemas& schemas() {
  static std::once_flag once;
  static Schemas all;
  std::call_once(once, [] {
    all.model_document = nlohmann::json::parse(embedded::model_schema);
    all.result_document = nlohmann::json::parse(embedded::result_schema);
    all.model = parse_schema(all.model_document);
    all.result = parse_schema(all.result_document);
  });
  return all;
}

const valijson::Schema& schema_for(SchemaKind kind) {
  return kind == SchemaKind::Model ? *schemas().model : *schemas().result;
}

/// The subschema that applies at `pointer` of a document, following properties, items and local
/// $refs ("#/definitions/x"); null when the schema has none there.
const nlohmann::json* subschema_at(const nlohmann::json& root, const nlohmann::json::json_pointer& pointer) {
  const nlohmann::json* at = &root;
  auto resolve = [&](const nlohmann::json* s) {
    for (int hops = 0; s && s->is_object() && s->contains("$ref") && hops < 8; ++hops) {
      const std::string ref = (*s)["$ref"].get<std::string>();
      if (ref.rfind("#", 0) != 0) return static_cast<const nlohmann::json*>(nullptr);
      const nlohmann::json::json_pointer target(ref.substr(1));
      s = root.contains(target) ? &root[target] : nullptr;
    }
    return s;
  };
  at = resolve(at);
  // json_pointer has no front(): collect the tokens from the back.
  std::vector<std::string> tokens;
  for (nlohmann::json::json_pointer rest = pointer; !rest.empty(); rest.pop_back()) tokens.insert(tokens.begin(), rest.back());
  for (const std::string& token : tokens) {
    if (!at || !at->is_object()) return nullptr;
    if (at->contains("properties") && (*at)["properties"].contains(token)) at = &(*at)["properties"][token];
    else if (at->contains("items")) at = &(*at)["items"];
    else return nullptr;
    at = resolve(at);
  }
  return at;
}

std::string type_name(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::boolean: return "a boolean";
    case nlohmann::json::value_t::string: return "a string";
    case nlohmann::json::value_t::array: return "an array";
    case nlohmann::json::value_t::object: return "an object";
    default: return "the number " + printable(value.dump(), 40);
  }
}

/// "Value type not permitted by 'type' constraint." says neither what was expected nor what was
/// found; the schema and the document know both.
std::string type_message(const nlohmann::json& document, const nlohmann::json& schema_root,
                         const nlohmann::json::json_pointer& where) {
  const nlohmann::json* schema = subschema_at(schema_root, where);
  if (!document.contains(where) || !schema || !schema->contains("type")) return {};
  const nlohmann::json& value = document[where];
  std::string expected;
  const nlohmann::json& type = (*schema)["type"];
  for (const auto& one : type.is_array() ? type : nlohmann::json::array({type})) {
    const std::string name = one.get<std::string>();
    if (!expected.empty()) expected += " or ";
    expected += name == "integer" ? "an integer" : name == "array" ? "an array" : name == "object" ? "an object" : "a " + name;
  }
  std::string message = "expected " + expected + ", found " + type_name(value);
  if (value.is_number_float() && expected == "an integer" && std::trunc(value.get<double>()) == value.get<double>()) {
    message += " (beyond the integers a double holds exactly, 2^53)";
  }
  return message;
}

/// valijson names an unknown property only in its message, at the object's place; the issue
/// belongs at the property itself.
bool unknown_property(model::InputIssue& issue) {
  const std::string marker = "'additionalProperties' constraints: '";
  const auto at = issue.message.find(marker);
  const auto end = issue.message.rfind('\'');
  if (at == std::string::npos || end == std::string::npos || end < at + marker.size()) return false;
  const std::string name = issue.message.substr(at + marker.size(), end - at - marker.size());
  issue.pointer += "/" + model::pointer_token(name);
  issue.message = "unknown property (the schema has no '" + printable(name, 60) +
                  "' here; names are case-sensitive)";
  return true;
}

/// Messages that say what was expected and what was found.
void explain(std::vector<model::InputIssue>& issues, const nlohmann::json& document, SchemaKind kind) {
  const nlohmann::json& schema_root = kind == SchemaKind::Model ? schemas().model_document : schemas().result_document;
  for (model::InputIssue& issue : issues) {
    if (unknown_property(issue)) continue;
    if (issue.message.rfind("Value type not permitted", 0) == 0) {
      try {
        const std::string better = type_message(document, schema_root, nlohmann::json::json_pointer(issue.pointer));
        if (!better.empty()) issue.message = better;
      } catch (const nlohmann::json::exception&) {
        // A pointer nlohmann cannot follow keeps valijson's own message.
      }
    }
    issue.message = printable(issue.message, 1000);
  }
}

/// valijson reports the path as {"<root>", "[blocks]", "[3]", ...}; turn it into "/blocks/3".
std::string to_pointer(const std::vector<std::string>& context) {
  std::string pointer;
  for (const std::string& part : context) {
    if (part == "<root>") continue;
    std::string token = part;
    if (token.size() >= 2 && token.front() == '[' && token.back() == ']') {
      token = token.substr(1, token.size() - 2);
    }
    pointer += "/" + model::pointer_token(token);
  }
  return pointer;
}

bool is_prefix_pointer(const std::string& prefix, const std::string& pointer) {
  return pointer.size() > prefix.size() && pointer.compare(0, prefix.size(), prefix) == 0 &&
         pointer[prefix.size()] == '/';
}

}  // namespace

std::vector<model::InputIssue> validate_against_schema(const nlohmann::json& document, SchemaKind kind,
                                                       std::size_t max_issues) {
  valijson::Validator validator;
  valijson::ValidationResults results;
  valijson::adapters::NlohmannJsonAdapter adapter(document);
  if (validator.validate(schema_for(kind), adapter, &results)) return {};

  std::vector<model::InputIssue> all;
  valijson::ValidationResults::Error error;
  while (results.popError(error)) all.push_back({to_pointer(error.context), error.description});

  // valijson also reports every ancestor of a failing place ("Failed to validate item #3 ...");
  // drop those summaries where a deeper issue says what was expected.
  std::vector<model::InputIssue> specific;
  for (const model::InputIssue& issue : all) {
    const bool is_summary = issue.message.rfind("Failed to validate", 0) == 0;
    const bool has_deeper = is_summary && std::any_of(all.begin(), all.end(), [&](const model::InputIssue& other) {
      return is_prefix_pointer(issue.pointer, other.pointer) ||
             (issue.pointer.empty() && !other.pointer.empty()) ||
             (other.pointer == issue.pointer && other.message.rfind("Failed to validate", 0) != 0);
    });
    const bool duplicate = std::any_of(specific.begin(), specific.end(), [&](const model::InputIssue& kept) {
      return kept.pointer == issue.pointer && kept.message == issue.message;
    });
    if (!has_deeper && !duplicate) specific.push_back(issue);
  }
  if (specific.empty()) specific = all;
  if (specific.size() > max_issues) specific.resize(max_issues);
  explain(specific, document, kind);
  return specific;
}

}  // namespace rbla::io
