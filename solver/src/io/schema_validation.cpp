#include "io/schema_validation.hpp"

#include "rbla/embedded_schemas.hpp"

#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

#include <algorithm>
#include <memory>
#include <mutex>

namespace rbla::io {
namespace {

std::unique_ptr<valijson::Schema> parse_schema(const char* text) {
  const nlohmann::json document = nlohmann::json::parse(text);
  auto schema = std::make_unique<valijson::Schema>();
  valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
  valijson::adapters::NlohmannJsonAdapter adapter(document);
  parser.populateSchema(adapter, *schema);
  return schema;
}

const valijson::Schema& schema_for(SchemaKind kind) {
  static std::once_flag once;
  static std::unique_ptr<valijson::Schema> model_schema;
  static std::unique_ptr<valijson::Schema> result_schema;
  std::call_once(once, [] {
    model_schema = parse_schema(embedded::model_schema);
    result_schema = parse_schema(embedded::result_schema);
  });
  return kind == SchemaKind::Model ? *model_schema : *result_schema;
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
  return specific;
}

}  // namespace rbla::io
