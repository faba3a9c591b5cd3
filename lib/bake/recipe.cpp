#include "lib/bake/recipe.h"

#include <fnmatch.h>
#include <glob.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>

// Header-only, errors as values: no exception leaves the parser
// (toml::parse_result).
#define TOML_HEADER_ONLY 1
#define TOML_EXCEPTIONS 0
#include <toml++/toml.h>

#include "lib/simplify/simplify.h"

namespace lodbake {
namespace {

enum class Kind { kBool, kInt, kFloat, kString, kStrings, kFloats };

// One option of a step: its type, default (null: unset, the library's
// default applies) and allowed range or values.
struct KeySpec {
  const char* key;
  Kind kind;
  nlohmann::json fallback;
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  std::vector<std::string> choices = {};
  bool open_low = false;  // low itself is not allowed
};

const double kInf = std::numeric_limits<double>::infinity();

const std::map<std::string, std::vector<KeySpec>>& step_specs() {
  static const std::map<std::string, std::vector<KeySpec>> specs = {
      {"pack", {{"quantize", Kind::kInt, 0, 0, 30}}},
      {"simplify",
       {{"ratio", Kind::kFloat, nullptr, 0, 1, {}, true},
        {"triangles", Kind::kInt, nullptr, 0, kInf},
        {"error", Kind::kFloat, nullptr, 0, kInf},
        {"placement", Kind::kString, "half", 0, 0, {"half", "optimal"}},
        {"boundary_weight", Kind::kFloat, 10.0, 0, kInf},
        {"lock_border", Kind::kBool, false},
        {"max_normal_change", Kind::kFloat, 150.0, 0, 180},
        {"permissive", Kind::kBool, false},
        {"seam_release", Kind::kFloat, kDefaultSeamRelease, 0, kInf},
        {"height_guard", Kind::kBool, false},
        {"height_guard_factor", Kind::kFloat, nullptr, 0, kInf, {}, true},
        {"quantize", Kind::kInt, 0, 0, 30},
        {"normal_weight", Kind::kFloat, 0.3, 0, kInf},
        {"uv_weight", Kind::kFloat, 5.0, 0, kInf},
        {"color_weight", Kind::kFloat, 1.0, 0, kInf},
        {"tangent_weight", Kind::kFloat, 0.1, 0, kInf}}},
      {"lods",
       {{"ratios", Kind::kFloats, nlohmann::json::array({0.5, 0.25, 0.1}), 0, 1, {}, true},
        {"errors", Kind::kFloats, nullptr, 0, kInf},
        {"format", Kind::kString, "glb", 0, 0, {"glb", "obj", "ply", "off"}},
        {"boundary_weight", Kind::kFloat, 10.0, 0, kInf},
        {"lock_border", Kind::kBool, false},
        {"max_normal_change", Kind::kFloat, 150.0, 0, 180},
        {"permissive", Kind::kBool, false},
        {"seam_release", Kind::kFloat, kDefaultSeamRelease, 0, kInf}}},
      {"hierarchy",
       {{"sections",
         Kind::kStrings,
         nlohmann::json::array({"vhie", "dage", "vtre"}),
         0,
         0,
         {"vhie", "dage", "vtre"}},
        {"boundary_weight", Kind::kFloat, 10.0, 0, kInf},
        {"max_normal_change", Kind::kFloat, 150.0, 0, 180, {}, true}}},
      {"fan",
       {{"ratio", Kind::kFloat, nullptr, 0, 1, {}, true},
        {"vertices", Kind::kInt, nullptr, 0, kInf},
        {"error", Kind::kFloat, nullptr, 0, kInf},
        {"degree_weight", Kind::kFloat, 0.0},
        {"boundary_weight", Kind::kFloat, 10.0, 0, kInf},
        {"max_normal_change", Kind::kFloat, 90.0, 0, 180}}},
      {"strips", {{"strips_only", Kind::kBool, false}}},
      {"package",
       {{"from",
         Kind::kStrings,
         nlohmann::json::array({"simplify", "hierarchy", "fan"}),
         0,
         0,
         {"pack", "simplify", "hierarchy", "fan", "strips"}},
        {"compact", Kind::kBool, true},
        {"draco", Kind::kBool, false},
        {"qp", Kind::kInt, 14, 1, 24},
        {"cl", Kind::kInt, 7, 0, 10},
        {"quantize", Kind::kInt, 0, 0, 30},
        {"error_bits", Kind::kInt, 0, 0, 24}}},
  };
  return specs;
}

const std::vector<std::string> kRepairPolicies = {"default", "repair", "strict"};
// Per-input placeholders of the output templates (a var may not shadow one).
const std::set<std::string> kPlaceholders = {"name", "stem",  "ext",   "dir",
                                             "step", "level", "format"};

Status error_at(const toml::node& node, const std::string& key, const std::string& message) {
  return Status(ErrorKind::kInvalidInput,
                "line " + std::to_string(node.source().begin.line) + ": " + key + ": " + message);
}

const char* kind_name(Kind kind) {
  switch (kind) {
    case Kind::kBool:
      return "true or false";
    case Kind::kInt:
      return "an integer";
    case Kind::kFloat:
      return "a number";
    case Kind::kString:
      return "a string";
    case Kind::kStrings:
      return "an array of strings";
    case Kind::kFloats:
      return "an array of numbers";
  }
  return "";
}

std::string range_text(const KeySpec& spec) {
  if (!spec.choices.empty()) {
    std::string text = "one of";
    for (const std::string& c : spec.choices)
      text += " '" + c + "'";
    return text;
  }
  std::string text = spec.open_low ? "above " : "at least ";
  text += nlohmann::json(spec.low).dump();
  if (spec.high != kInf) text += " and at most " + nlohmann::json(spec.high).dump();
  return text;
}

// A number of a node, integers included; false when it is not one.
bool number_of(const toml::node& node, double* value) {
  if (const auto* i = node.as_integer()) {
    *value = static_cast<double>(i->get());
    return true;
  }
  if (const auto* f = node.as_floating_point()) {
    *value = f->get();
    return true;
  }
  return false;
}

bool in_range(const KeySpec& spec, double v) {
  if (!std::isfinite(v)) return false;
  return (spec.open_low ? v > spec.low : v >= spec.low) && v <= spec.high;
}

// Checks one option against its spec and converts it to JSON.
Result<nlohmann::json> option_value(const KeySpec& spec, const toml::node& node,
                                    const std::string& key) {
  const std::string wrong = std::string("must be ") + kind_name(spec.kind);
  double number = 0;
  switch (spec.kind) {
    case Kind::kBool:
      if (const auto* b = node.as_boolean()) return nlohmann::json(b->get());
      return error_at(node, key, wrong);
    case Kind::kInt: {
      const auto* i = node.as_integer();
      if (i == nullptr) return error_at(node, key, wrong);
      if (!in_range(spec, static_cast<double>(i->get())))
        return error_at(node, key, "must be " + range_text(spec));
      return nlohmann::json(i->get());
    }
    case Kind::kFloat:
      if (!number_of(node, &number)) return error_at(node, key, wrong);
      if (!in_range(spec, number)) return error_at(node, key, "must be " + range_text(spec));
      return nlohmann::json(number);
    case Kind::kString: {
      const auto* s = node.as_string();
      if (s == nullptr) return error_at(node, key, wrong);
      if (std::find(spec.choices.begin(), spec.choices.end(), s->get()) == spec.choices.end())
        return error_at(node, key, "must be " + range_text(spec) + ", not '" + s->get() + "'");
      return nlohmann::json(s->get());
    }
    case Kind::kStrings:
    case Kind::kFloats: {
      const auto* array = node.as_array();
      if (array == nullptr || array->empty()) return error_at(node, key, wrong + ", not empty");
      nlohmann::json out = nlohmann::json::array();
      for (const toml::node& item : *array) {
        if (spec.kind == Kind::kFloats) {
          if (!number_of(item, &number)) return error_at(item, key, wrong);
          if (!in_range(spec, number))
            return error_at(item, key, "each must be " + range_text(spec));
          if (std::find(out.begin(), out.end(), nlohmann::json(number)) != out.end())
            return error_at(item, key, "lists " + nlohmann::json(number).dump() + " twice");
          out.push_back(number);
        } else {
          const auto* s = item.as_string();
          if (s == nullptr) return error_at(item, key, wrong);
          if (std::find(spec.choices.begin(), spec.choices.end(), s->get()) == spec.choices.end())
            return error_at(item, key,
                            "each must be " + range_text(spec) + ", not '" + s->get() + "'");
          if (std::find(out.begin(), out.end(), nlohmann::json(s->get())) != out.end())
            return error_at(item, key, "lists '" + s->get() + "' twice");
          out.push_back(s->get());
        }
      }
      return out;
    }
  }
  return error_at(node, key, wrong);
}

// A [steps] table (top level or an override's): every step known, every
// option known and valid.
Result<nlohmann::json> parse_steps(const toml::table& steps, const std::string& prefix) {
  nlohmann::json out = nlohmann::json::object();
  for (auto&& [name, node] : steps) {
    const std::string step_key = prefix + "." + std::string(name.str());
    auto spec = step_specs().find(std::string(name.str()));
    if (spec == step_specs().end())
      return error_at(node, step_key,
                      "unknown step (pack, simplify, lods, hierarchy, fan, strips, package)");
    const toml::table* options = node.as_table();
    if (options == nullptr) return error_at(node, step_key, "must be a table");
    nlohmann::json values = nlohmann::json::object();
    for (auto&& [key, value] : *options) {
      const std::string option_key = step_key + "." + std::string(key.str());
      auto found = std::find_if(spec->second.begin(), spec->second.end(),
                                [&](const KeySpec& s) { return key.str() == s.key; });
      if (found == spec->second.end()) return error_at(value, option_key, "unknown key");
      LODBAKE_ASSIGN_OR_RETURN(values[found->key], option_value(*found, value, option_key));
    }
    if (values.contains("ratios") && values.contains("errors"))
      return error_at(node, step_key, "give ratios or errors, not both");
    out[std::string(name.str())] = values;
  }
  return out;
}

Result<std::string> string_at(const toml::node& node, const std::string& key) {
  const auto* s = node.as_string();
  if (s == nullptr) return error_at(node, key, "must be a string");
  return s->get();
}

Result<std::vector<std::string>> strings_at(const toml::node& node, const std::string& key) {
  const auto* array = node.as_array();
  if (array == nullptr) return error_at(node, key, "must be an array of strings");
  std::vector<std::string> out;
  for (const toml::node& item : *array) {
    LODBAKE_ASSIGN_OR_RETURN(std::string s, string_at(item, key));
    out.push_back(std::move(s));
  }
  return out;
}

Result<std::string> repair_at(const toml::node& node, const std::string& key) {
  LODBAKE_ASSIGN_OR_RETURN(std::string policy, string_at(node, key));
  if (std::find(kRepairPolicies.begin(), kRepairPolicies.end(), policy) == kRepairPolicies.end())
    return error_at(node, key, "must be 'default', 'repair' or 'strict', not '" + policy + "'");
  return policy;
}

// Replaces {NAME} for every NAME in `values`; other placeholders stay.
std::string substitute(const std::string& text, const std::map<std::string, std::string>& values) {
  std::string out;
  for (size_t i = 0; i < text.size();) {
    const size_t close = text[i] == '{' ? text.find('}', i) : std::string::npos;
    if (close != std::string::npos) {
      auto found = values.find(text.substr(i + 1, close - i - 1));
      if (found != values.end()) {
        out += found->second;
        i = close + 1;
        continue;
      }
    }
    out += text[i++];
  }
  return out;
}

// The first {NAME} of `text` not in `allowed`, or empty.
std::string unknown_placeholder(const std::string& text, const std::set<std::string>& allowed) {
  for (size_t open = text.find('{'); open != std::string::npos; open = text.find('{', open + 1)) {
    const size_t close = text.find('}', open);
    if (close == std::string::npos) return text.substr(open);
    const std::string name = text.substr(open + 1, close - open - 1);
    if (allowed.count(name) == 0) return "{" + name + "}";
  }
  return "";
}

Status check_template(const toml::node& node, const std::string& key, const std::string& text,
                      const std::set<std::string>& allowed) {
  const std::string unknown = unknown_placeholder(text, allowed);
  if (!unknown.empty()) return error_at(node, key, "unknown placeholder " + unknown);
  if (text.empty()) return error_at(node, key, "must not be empty");
  return Status::ok();
}

}  // namespace

const std::vector<std::string>& bake_step_names() {
  static const std::vector<std::string> names = {"pack", "simplify", "lods",   "hierarchy",
                                                 "fan",  "strips",   "package"};
  return names;
}

Result<Recipe> parse_recipe(const std::string& file, const std::string& text,
                            const std::map<std::string, std::string>& set) {
  toml::parse_result parsed = toml::parse(text, file);
  if (!parsed) {
    const toml::parse_error& e = parsed.error();
    return Status(ErrorKind::kInvalidInput, "line " + std::to_string(e.source().begin.line) + ": " +
                                                std::string(e.description()));
  }
  const toml::table& root = parsed.table();
  Recipe recipe;
  recipe.file = file;
  const size_t slash = file.find_last_of('/');
  recipe.folder = slash == std::string::npos ? "." : file.substr(0, slash);
  if (recipe.folder.empty()) recipe.folder = "/";
  recipe.output = "{name}/{step}.lbk";
  recipe.lods_output = "{name}/lod{level}.{format}";
  recipe.steps = nlohmann::json::object();
  const toml::node* inputs_node = nullptr;
  const toml::node* output_node = nullptr;
  const toml::node* lods_node = nullptr;
  std::vector<std::pair<const toml::table*, std::string>> override_tables;
  for (auto&& [name, node] : root) {
    const std::string key(name.str());
    if (key == "version") {
      const auto* v = node.as_integer();
      if (v == nullptr || v->get() != 1) return error_at(node, key, "must be 1");
    } else if (key == "repair") {
      LODBAKE_ASSIGN_OR_RETURN(recipe.repair, repair_at(node, key));
    } else if (key == "vars") {
      const toml::table* vars = node.as_table();
      if (vars == nullptr) return error_at(node, key, "must be a table");
      for (auto&& [var, value] : *vars) {
        const std::string var_key = "vars." + std::string(var.str());
        if (kPlaceholders.count(std::string(var.str())) != 0)
          return error_at(value, var_key, "is an output placeholder; name the variable otherwise");
        LODBAKE_ASSIGN_OR_RETURN(recipe.vars[std::string(var.str())], string_at(value, var_key));
      }
    } else if (key == "inputs") {
      const toml::table* table = node.as_table();
      if (table == nullptr) return error_at(node, key, "must be a table");
      inputs_node = &node;
      for (auto&& [sub, value] : *table) {
        const std::string sub_key = "inputs." + std::string(sub.str());
        if (sub.str() == "globs") {
          LODBAKE_ASSIGN_OR_RETURN(recipe.globs, strings_at(value, sub_key));
        } else if (sub.str() == "exclude") {
          LODBAKE_ASSIGN_OR_RETURN(recipe.excludes, strings_at(value, sub_key));
        } else {
          return error_at(value, sub_key, "unknown key");
        }
      }
    } else if (key == "output") {
      const toml::table* table = node.as_table();
      if (table == nullptr) return error_at(node, key, "must be a table");
      for (auto&& [sub, value] : *table) {
        const std::string sub_key = "output." + std::string(sub.str());
        if (sub.str() == "path") {
          LODBAKE_ASSIGN_OR_RETURN(recipe.output, string_at(value, sub_key));
          output_node = &value;
        } else if (sub.str() == "lods") {
          LODBAKE_ASSIGN_OR_RETURN(recipe.lods_output, string_at(value, sub_key));
          lods_node = &value;
        } else {
          return error_at(value, sub_key, "unknown key");
        }
      }
    } else if (key == "steps") {
      const toml::table* table = node.as_table();
      if (table == nullptr) return error_at(node, key, "must be a table");
      LODBAKE_ASSIGN_OR_RETURN(recipe.steps, parse_steps(*table, "steps"));
    } else if (key == "override") {
      const toml::array* array = node.as_array();
      if (array == nullptr || !array->is_array_of_tables())
        return error_at(node, key, "must be an array of tables ([[override]])");
      for (size_t i = 0; i < array->size(); ++i)
        override_tables.emplace_back(array->get(i)->as_table(),
                                     "override[" + std::to_string(i) + "]");
    } else {
      return error_at(node, key, "unknown key");
    }
  }
  if (inputs_node == nullptr || recipe.globs.empty())
    return Status(ErrorKind::kInvalidInput, "line 1: inputs.globs: missing (the inputs to bake)");
  if (recipe.steps.empty())
    return Status(ErrorKind::kInvalidInput, "line 1: steps: missing (no step to run)");
  for (const auto& [name, value] : set)
    recipe.vars[name] = value;
  std::set<std::string> vars;
  for (const auto& [name, value] : recipe.vars)
    vars.insert(name);
  for (std::vector<std::string>* list : {&recipe.globs, &recipe.excludes}) {
    for (std::string& glob : *list) {
      const std::string unknown = unknown_placeholder(glob, vars);
      if (!unknown.empty())
        return error_at(
            *inputs_node, "inputs",
            "unknown variable " + unknown + " in '" + glob + "' (give it in [vars] or --set)");
      glob = substitute(glob, recipe.vars);
      if (glob.front() != '/' && recipe.folder != ".") glob = recipe.folder + "/" + glob;
    }
  }
  std::set<std::string> allowed = kPlaceholders;
  allowed.insert(vars.begin(), vars.end());
  LODBAKE_RETURN_IF_ERROR(
      check_template(output_node ? *output_node : root, "output.path", recipe.output, allowed));
  LODBAKE_RETURN_IF_ERROR(
      check_template(lods_node ? *lods_node : root, "output.lods", recipe.lods_output, allowed));
  recipe.output = substitute(recipe.output, recipe.vars);
  recipe.lods_output = substitute(recipe.lods_output, recipe.vars);
  if (recipe.steps.contains("lods") && recipe.lods_output.find("{level}") == std::string::npos)
    return error_at(lods_node ? *lods_node : root, "output.lods",
                    "must contain {level} (one file per level)");

  for (const auto& [table, prefix] : override_tables) {
    RecipeOverride o;
    o.settings = nlohmann::json::object();
    for (auto&& [sub, value] : *table) {
      const std::string sub_key = prefix + "." + std::string(sub.str());
      if (sub.str() == "glob") {
        LODBAKE_ASSIGN_OR_RETURN(o.glob, string_at(value, sub_key));
        o.glob = substitute(o.glob, recipe.vars);
      } else if (sub.str() == "repair") {
        LODBAKE_ASSIGN_OR_RETURN(std::string policy, repair_at(value, sub_key));
        o.settings["repair"] = policy;
      } else if (sub.str() == "skip") {
        LODBAKE_ASSIGN_OR_RETURN(std::vector<std::string> skip, strings_at(value, sub_key));
        for (const std::string& step : skip)
          if (!recipe.steps.contains(step))
            return error_at(value, sub_key, "'" + step + "' is not a step of this recipe");
        o.settings["skip"] = skip;
      } else if (sub.str() == "steps") {
        const toml::table* steps = value.as_table();
        if (steps == nullptr) return error_at(value, sub_key, "must be a table");
        LODBAKE_ASSIGN_OR_RETURN(nlohmann::json parsed_steps, parse_steps(*steps, sub_key));
        for (const auto& [step, options] : parsed_steps.items())
          if (!recipe.steps.contains(step))
            return error_at(value, sub_key + "." + step,
                            "is not a step of this recipe (add it to [steps])");
        o.settings["steps"] = parsed_steps;
      } else {
        return error_at(value, sub_key, "unknown key");
      }
    }
    if (o.glob.empty()) return error_at(*table, prefix + ".glob", "missing");
    recipe.overrides.push_back(std::move(o));
  }
  return recipe;
}

namespace {

// A folder glob(3) could not read for another reason than not existing (a
// missing folder is only a glob that matches nothing).
thread_local int glob_error = 0;
int on_glob_error(const char*, int error) {
  if (error != ENOENT && error != ENOTDIR) glob_error = error;
  return 0;
}

}  // namespace

Result<std::vector<std::string>> expand_inputs(const Recipe& recipe,
                                               std::vector<std::string>* warnings) {
  std::set<std::string> found;
  for (const std::string& pattern : recipe.globs) {
    glob_t matches{};
    glob_error = 0;
    const int code = glob(pattern.c_str(), 0, on_glob_error, &matches);
    if (glob_error != 0 || (code != 0 && code != GLOB_NOMATCH)) {
      globfree(&matches);
      return Status(ErrorKind::kIo, "inputs.globs: '" + pattern + "': cannot read a folder: " +
                                        std::strerror(glob_error != 0 ? glob_error : EIO));
    }
    if (code == GLOB_NOMATCH) {
      warnings->push_back("inputs.globs: '" + pattern + "' matches no file");
    } else {
      for (size_t i = 0; i < matches.gl_pathc; ++i)
        found.insert(matches.gl_pathv[i]);
    }
    globfree(&matches);
  }
  std::vector<std::string> inputs;
  for (const std::string& path : found) {
    const bool excluded =
        std::any_of(recipe.excludes.begin(), recipe.excludes.end(),
                    [&](const std::string& e) { return fnmatch(e.c_str(), path.c_str(), 0) == 0; });
    if (!excluded) inputs.push_back(path);
  }
  return inputs;
}

namespace {

// The {name}, {stem}, {ext} and {dir} of an input.
std::map<std::string, std::string> input_placeholders(const std::string& input) {
  const size_t slash = input.find_last_of('/');
  const std::string name = slash == std::string::npos ? input : input.substr(slash + 1);
  const std::string folder = slash == std::string::npos ? "." : input.substr(0, slash);
  const size_t folder_slash = folder.find_last_of('/');
  const size_t dot = name.find_last_of('.');
  return {{"name", name},
          {"stem", dot == std::string::npos || dot == 0 ? name : name.substr(0, dot)},
          {"ext", dot == std::string::npos ? "" : name.substr(dot + 1)},
          {"dir", folder_slash == std::string::npos ? folder : folder.substr(folder_slash + 1)}};
}

}  // namespace

Result<InputPlan> plan_input(const Recipe& recipe, const std::string& input) {
  nlohmann::json steps = recipe.steps;
  std::string repair = recipe.repair;
  std::set<std::string> skipped;
  for (const RecipeOverride& o : recipe.overrides) {
    if (fnmatch(o.glob.c_str(), input.c_str(), 0) != 0) continue;
    if (o.settings.contains("repair")) repair = o.settings["repair"].get<std::string>();
    if (o.settings.contains("skip"))
      for (const nlohmann::json& step : o.settings["skip"])
        skipped.insert(step.get<std::string>());
    if (o.settings.contains("steps"))
      for (const auto& [step, options] : o.settings["steps"].items())
        steps[step].update(options);
  }
  InputPlan plan;
  plan.input = input;
  std::map<std::string, std::string> values = input_placeholders(input);
  for (const std::string& step : bake_step_names()) {
    if (!steps.contains(step) || skipped.count(step) != 0) continue;
    StepPlan s;
    s.step = step;
    s.options = nlohmann::json::object();
    for (const KeySpec& spec : step_specs().at(step))
      s.options[spec.key] = steps[step].value(spec.key, spec.fallback);
    s.options["repair"] = repair;
    values["step"] = step;
    if (step == "lods") {
      // A chain by errors (set last, by an override) replaces the ratios.
      if (!s.options["errors"].is_null()) s.options["ratios"] = nullptr;
      const nlohmann::json& levels =
          s.options["errors"].is_null() ? s.options["ratios"] : s.options["errors"];
      values["format"] = s.options["format"].get<std::string>();
      for (size_t level = 0; level < levels.size(); ++level) {
        values["level"] = std::to_string(level);
        s.outputs.push_back(substitute(recipe.lods_output, values));
      }
    } else {
      s.outputs.push_back(substitute(recipe.output, values));
    }
    if (step == "package") {
      // The listed steps that run for this input, in step order.
      nlohmann::json from = nlohmann::json::array();
      for (const StepPlan& earlier : plan.steps) {
        const nlohmann::json& listed = s.options["from"];
        if (std::find(listed.begin(), listed.end(), earlier.step) != listed.end())
          from.push_back(earlier.step);
      }
      if (from.empty())
        return Status(
            ErrorKind::kInvalidInput,
            "steps.package.from: none of " + s.options["from"].dump() + " runs for this input");
      s.options["from"] = from;
    }
    plan.steps.push_back(std::move(s));
  }
  return plan;
}

Result<std::vector<InputPlan>> plan_inputs(const Recipe& recipe,
                                           const std::vector<std::string>& inputs) {
  std::vector<InputPlan> plans;
  std::map<std::string, std::string> owner;  // output -> "input (step)"
  for (const std::string& input : inputs) {
    Result<InputPlan> plan = plan_input(recipe, input);
    if (!plan.is_ok()) return Status(plan.status().kind(), input + ": " + plan.status().message());
    for (const StepPlan& step : plan.value().steps) {
      for (const std::string& output : step.outputs) {
        const std::string who = input + " (" + step.step + ")";
        auto [it, added] = owner.emplace(output, who);
        if (!added)
          return Status(ErrorKind::kInvalidInput,
                        "output.path: '" + output + "' is the output of both " + it->second +
                            " and " + who + "; use {name}, {dir} or {step} in the template");
      }
    }
    plans.push_back(std::move(plan).value());
  }
  return plans;
}

}  // namespace lodbake
