// Sweep files (sweep_file.hpp): base scene + fixed keys + varied keys + seeds → member scenes.
#include "fragmpm/pipeline/sweep_file.hpp"

#include <toml++/toml.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/scene_override.hpp"
#include "scene/scene_toml.hpp"

namespace fragmpm::pipeline {

namespace fs = std::filesystem;
using scene_detail::Section;

namespace {

int line_of(const toml::node& n) {
  return static_cast<int>(n.source().begin.line);
}

std::string read_text(const std::string& path, const std::string& from_file, int from_line,
                      const std::string& from_key) {
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw SceneError(from_file, from_line, from_key, "expected a file, got the directory " + path);
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw SceneError(from_file, from_line, from_key,
                     "cannot open " + path + ": " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

toml::table parse_toml(const std::string& text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw SceneError(path, static_cast<int>(e.source().begin.line), "",
                     "TOML syntax error: " + std::string(e.description()));
  }
}

/// How a value appears in the manifest and in messages: strings without quotes.
std::string value_text(const toml::node& n) {
  if (const auto* s = n.as_string()) return s->get();
  std::ostringstream os;
  if (const auto* a = n.as_array())
    os << *a;
  else if (const auto* t = n.as_table())
    os << *t;
  else
    n.visit([&](const auto& v) { os << v; });
  return os.str();
}

/// A seed list: "A..B" (inclusive), an integer array, or one integer.
std::vector<long long> read_seeds(const Section& top) {
  const toml::node* n = top.find("seeds");
  std::vector<long long> seeds;
  auto fail = [&](const std::string& what) {
    top.fail("seeds", "expected " + what + ", got " + scene_detail::describe(*n));
  };
  if (const auto* s = n->as_string()) {
    const std::string& t = s->get();
    const std::size_t dots = t.find("..");
    long long a = 0, b = 0;
    std::size_t used_a = 0, used_b = 0;
    try {
      if (dots == std::string::npos) throw std::invalid_argument("");
      a = std::stoll(t.substr(0, dots), &used_a);
      b = std::stoll(t.substr(dots + 2), &used_b);
    } catch (const std::exception&) {
      fail("a range \"FIRST..LAST\" of seeds (e.g. \"1..32\")");
    }
    if (used_a != dots || used_b != t.size() - dots - 2)
      fail("a range \"FIRST..LAST\" of seeds (e.g. \"1..32\")");
    if (b < a) fail("a non-empty range FIRST..LAST with FIRST <= LAST");
    if (a < 0) fail("seeds >= 0");
    for (long long k = a; k <= b; ++k) seeds.push_back(k);
  } else if (const auto* arr = n->as_array()) {
    if (arr->empty()) fail("a non-empty list of seeds");
    for (const toml::node& e : *arr) {
      const auto* i = e.as_integer();
      if (!i || i->get() < 0) fail("a list of integer seeds >= 0");
      seeds.push_back(i->get());
    }
  } else if (const auto* i = n->as_integer()) {
    if (i->get() < 0) fail("a seed >= 0");
    seeds.push_back(i->get());
  } else {
    fail("a range \"FIRST..LAST\", a list of integers or one integer");
  }
  return seeds;
}

bool is_file_key(std::string_view path) {
  const std::size_t dot = path.rfind('.');
  const std::string_view last = dot == std::string_view::npos ? path : path.substr(dot + 1);
  return path.rfind("bodies[", 0) == 0 && (last == "image" || last == "grains");
}

/// Turns a relative image or grain-file path (relative to `from_dir`) into an absolute one.
toml::value<std::string> absolute_file(const toml::node& n, const fs::path& from_dir) {
  const std::string p = n.as_string()->get();
  const fs::path path(p);
  return toml::value<std::string>(
      (path.is_absolute() ? path : fs::absolute(from_dir / path)).lexically_normal().string());
}

/// Every body's image or grain file, relative to the member's folder (where `fragmpm run` reads
/// the member scene from).
void relativise_files(toml::table& scene, const fs::path& member_dir) {
  auto* bodies = scene["bodies"].as_array();
  if (!bodies) return;
  for (toml::node& b : *bodies) {
    auto* t = b.as_table();
    if (!t) continue;
    for (const char* key : {"image", "grains"}) {
      auto* s = t->get_as<std::string>(key);
      if (!s || !fs::path(s->get()).is_absolute()) continue;
      *s = fs::path(s->get()).lexically_relative(member_dir).string();
    }
  }
}

std::string member_name(std::size_t index, std::size_t count) {
  std::string digits = std::to_string(index + 1);
  const std::size_t width = std::max<std::size_t>(4, std::to_string(count).size());
  return std::string(width - std::min(width, digits.size()), '0') + digits;
}

struct Override {
  std::string key;
  int line = 0;
  std::vector<const toml::node*> values;  ///< one for [set], the list for [vary]
};

}  // namespace

std::string describe_member(const SweepSpec& spec, const SweepMember& member) {
  std::string out;
  for (std::size_t a = 0; a < spec.axes.size(); ++a)
    out += (out.empty() ? "" : ", ") + spec.axes[a].key + " = " +
           spec.axes[a].values[member.choice[a]];
  return out.empty() ? "the base scene" : out;
}

SweepSpec read_sweep(const std::string& path, const std::string& output_dir, bool compile) {
  SweepSpec spec;
  spec.path = path;
  spec.text = read_text(path, path, 0, "");
  const toml::table sweep = parse_toml(spec.text, path);
  const Section top(sweep, "", path);
  top.allow_only({"scene", "seeds", "seed_keys", "set", "vary", "analyze"});
  const fs::path sweep_dir = fs::absolute(fs::path(path)).parent_path();

  const std::string scene_value = top.string("scene");
  spec.base_scene =
      (fs::path(scene_value).is_absolute() ? fs::path(scene_value) : sweep_dir / scene_value)
          .lexically_normal()
          .string();
  const std::string base_text =
      read_text(spec.base_scene, path, top.line_of("scene"), top.key("scene"));
  toml::table base = parse_toml(base_text, spec.base_scene);
  const fs::path base_dir = fs::absolute(fs::path(spec.base_scene)).parent_path();
  if (auto* bodies = base["bodies"].as_array())
    for (toml::node& b : *bodies)
      if (auto* t = b.as_table())
        for (const char* key : {"image", "grains"})
          if (const toml::node* f = t->get(key); f && f->is_string())
            t->insert_or_assign(key, absolute_file(*f, base_dir));

  auto apply = [&](toml::table& scene, const std::string& key, int line, const toml::node& v) {
    try {
      if (is_file_key(key) && v.is_string())
        set_scene_key(scene, key, absolute_file(v, sweep_dir));
      else
        set_scene_key(scene, key, v);
    } catch (const KeyPathError& e) {
      throw SceneError(path, line, key, std::string("unknown key path: ") + e.what());
    }
  };

  if (auto set = top.optional_table("set")) {
    for (auto&& [k, v] : *sweep["set"].as_table()) apply(base, std::string(k.str()), line_of(v), v);
  }

  std::vector<Override> varied;
  if (auto vary = top.optional_table("vary")) {
    for (auto&& [k, v] : *sweep["vary"].as_table()) {
      const std::string key(k.str());
      const auto* list = v.as_array();
      if (!list)
        vary->fail(key,
                   "expected a list of values for the members, got " + scene_detail::describe(v));
      if (list->empty()) vary->fail(key, "expected a non-empty list of values, got []");
      Override o{key, line_of(v), {}};
      SweepAxis axis{key, o.line, {}};
      for (const toml::node& e : *list) {
        o.values.push_back(&e);
        axis.values.push_back(value_text(e));
      }
      // A key path that does not lead into the scene is refused here, once, not per member.
      toml::table probe = base;
      apply(probe, key, o.line, *o.values.front());
      varied.push_back(std::move(o));
      spec.axes.push_back(std::move(axis));
    }
  }

  std::vector<long long> seeds;
  std::vector<std::string> seed_keys;
  int seeds_line = 0;
  if (top.has("seeds")) {
    seeds = read_seeds(top);
    seeds_line = top.line_of("seeds");
    if (top.has("seed_keys")) {
      seed_keys = top.string_list("seed_keys");
      if (seed_keys.empty()) top.expected("seed_keys", "a non-empty list of key paths");
      for (const std::string& k : seed_keys) {
        toml::table probe = base;
        apply(probe, k, top.line_of("seed_keys"), toml::value<int64_t>(0));
      }
    } else {
      if (const auto* materials = base["materials"].as_array())
        for (std::size_t m = 0; m < materials->size(); ++m)
          if (const auto* t = materials->get(m)->as_table(); t && t->get("weibull"))
            seed_keys.push_back("materials[" + std::to_string(m) + "].weibull.seed");
      if (seed_keys.empty())
        top.fail("seeds",
                 "the scene has no material with a weibull table to seed: add one to the base "
                 "scene or under [set], or name the keys in seed_keys");
    }
    SweepAxis axis{"seed", seeds_line, {}};
    for (long long s : seeds) axis.values.push_back(std::to_string(s));
    spec.axes.push_back(std::move(axis));
  }

  if (auto a = top.optional_table("analyze")) {
    a->allow_only({"at", "at_displacement", "min_particles", "d_mask"});
    if (a->has("at")) spec.analysis.at = a->string_list("at");
    if (a->has("at_displacement"))
      spec.analysis.at_displacement = a->string_list("at_displacement");
    spec.analysis.min_particles =
        static_cast<int>(a->optional_integer("min_particles").value_or(4));
    if (spec.analysis.min_particles < 1) a->expected("min_particles", "an integer >= 1");
    spec.analysis.d_mask = a->optional_number("d_mask").value_or(0.99);
    if (!(spec.analysis.d_mask > 0.0 && spec.analysis.d_mask <= 1.0))
      a->expected("d_mask", "a damage threshold 0 < d_mask <= 1");
  }

  // The grid of members, the last axis (the seed) varying fastest.
  std::size_t count = 1;
  for (const SweepAxis& axis : spec.axes) count *= axis.values.size();
  const fs::path out_abs = fs::absolute(fs::path(output_dir)).lexically_normal();
  std::optional<SceneError> base_error;
  bool base_checked = false;
  for (std::size_t m = 0; m < count; ++m) {
    SweepMember member;
    member.name = member_name(m, count);
    member.choice.resize(spec.axes.size());
    std::size_t rest = m;
    for (std::size_t a = spec.axes.size(); a-- > 0;) {
      member.choice[a] = rest % spec.axes[a].values.size();
      rest /= spec.axes[a].values.size();
    }
    toml::table scene = base;
    for (std::size_t v = 0; v < varied.size(); ++v)
      apply(scene, varied[v].key, varied[v].line, *varied[v].values[member.choice[v]]);
    if (!seeds.empty())
      for (const std::string& k : seed_keys)
        apply(scene, k, seeds_line, toml::value<int64_t>(seeds[member.choice.back()]));
    const fs::path member_dir = out_abs / member.name;
    relativise_files(scene, member_dir);
    std::ostringstream text;
    text << "# member " << member.name << " of the sweep " << fs::absolute(path).string() << ": "
         << describe_member(spec, member) << "\n"
         << scene << "\n";
    member.scene_text = text.str();
    if (compile) {
      try {
        (void)parse_scene(member.scene_text, (member_dir / "scene.toml").string());
      } catch (const SceneError& e) {
        // Which value made the member bad: the varied key the error is about, else the seed,
        // else (when the base scene compiles as written) the member's first varied value.
        auto about = [&](const std::string& key) {
          return e.key == key || e.key.rfind(key + ".", 0) == 0 || e.key.rfind(key + "[", 0) == 0;
        };
        const std::string detail = "member " + member.name + " (" + describe_member(spec, member) +
                                   ") does not compile: " + e.what();
        for (std::size_t v = 0; v < varied.size(); ++v)
          if (about(varied[v].key)) throw SceneError(path, varied[v].line, varied[v].key, detail);
        for (const std::string& k : seed_keys)
          if (about(k)) throw SceneError(path, seeds_line, k, detail);
        if (!base_checked) {
          base_checked = true;
          try {
            (void)parse_scene(base_text, spec.base_scene);
          } catch (const SceneError& b) {
            base_error = b;
          }
        }
        if (base_error) throw *base_error;
        if (!varied.empty()) throw SceneError(path, varied[0].line, varied[0].key, detail);
        if (!seeds.empty()) throw SceneError(path, seeds_line, "seeds", detail);
        throw SceneError(path, top.line_of("scene"), "scene", detail);
      }
    }
    spec.members.push_back(std::move(member));
  }
  return spec;
}

}  // namespace fragmpm::pipeline
