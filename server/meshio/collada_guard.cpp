#include "meshio/collada_guard.h"

#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <system_error>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace rbsim::meshio {
namespace {

using tinyxml2::XMLElement;

Error lineError(const std::string& path, int line, const std::string& text) {
  return Error{path + ":" + std::to_string(line) + ": " + text};
}

// Text from the file, quoted in a message: unprintable bytes replaced and
// length capped.
std::string quoted(std::string_view text) {
  constexpr size_t kMaxShown = 40;
  std::string shown;
  for (size_t i = 0; i < text.size() && i < kMaxShown; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    shown += std::isprint(c) ? static_cast<char>(c) : '?';
  }
  if (text.size() > kMaxShown) shown += "...";
  return "'" + shown + "'";
}

// XML's white space: space, tab, CR and LF. Lists are checked with this and
// nothing wider: assimp 5.2.5 separates numbers by these only, and a
// vertical tab in an index list (white space to std::isspace) makes it
// allocate gigabytes (fuzz_dae_mesh).
bool isXmlSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

std::string_view trimmed(std::string_view text) {
  const auto space = [](char c) { return isXmlSpace(c); };
  while (!text.empty() && space(text.front())) text.remove_prefix(1);
  while (!text.empty() && space(text.back())) text.remove_suffix(1);
  return text;
}

bool isNamed(const XMLElement* element, const char* name) {
  return std::strcmp(element->Name(), name) == 0;
}


// The <node> elements that belong to `element` (its child nodes) and the
// urls of its <instance_node> elements. assimp reads these as direct
// children; looking through any element in between as well can only count
// more, never less.
void collectParts(const XMLElement* element, std::vector<const XMLElement*>& nodes,
                  std::vector<std::string_view>& instanceUrls) {
  for (const XMLElement* child = element->FirstChildElement(); child;
       child = child->NextSiblingElement()) {
    if (isNamed(child, "node")) {
      nodes.push_back(child);
    } else if (isNamed(child, "instance_node")) {
      const char* url = child->Attribute("url");
      instanceUrls.emplace_back(url ? url : "");
    } else {
      collectParts(child, nodes, instanceUrls);  // depth bounded by tinyxml2's element depth limit
    }
  }
}

// The node graph with every <instance_node> followed: how many nodes a node
// becomes once expanded, and how deep it nests, without building it.
class NodeGraph {
 public:
  NodeGraph(const XMLElement* root, const std::string& path) : m_path(path) { index(root); }

  struct Expansion {
    long long nodes = 0;  // saturates just above kMaxColladaNodes
    int depth = 0;
  };

  // `level` is the nesting level of `node` (1 for a visual scene's own nodes).
  Expected<Expansion> expand(const XMLElement* node, int level) {
    if (level > kMaxColladaNodeDepth) return tooDeep(node);
    State& state = m_states[node];
    if (state.done) {
      if (level - 1 + state.expansion.depth > kMaxColladaNodeDepth) return tooDeep(node);
      return state.expansion;
    }
    if (state.visiting) {
      return lineError(m_path, node->GetLineNum(),
                       "node " + nodeName(node) +
                           " contains itself through <instance_node>: a cycle, refused");
    }
    state.visiting = true;
    std::vector<const XMLElement*> children;
    std::vector<std::string_view> urls;
    collectParts(node, children, urls);
    Expansion total{1, 1};
    const auto add = [&](const Expansion& part) {
      total.nodes = std::min(total.nodes + part.nodes, kMaxColladaNodes + 1);
      total.depth = std::max(total.depth, 1 + part.depth);
    };
    for (const XMLElement* child : children) {
      Expected<Expansion> part = expand(child, level + 1);
      if (!part) return part.error();
      add(*part);
    }
    for (std::string_view url : urls) {
      // A url "#x" names the node whose id (or, as assimp also tries, sid
      // or name) is x; where several could be meant, count the largest.
      if (!url.empty() && url.front() == '#') url.remove_prefix(1);
      const auto found = m_byName.find(std::string(url));
      if (found == m_byName.end()) continue;  // assimp reports the unresolved reference
      Expansion largest;
      for (const XMLElement* target : found->second) {
        Expected<Expansion> part = expand(target, level + 1);
        if (!part) return part.error();
        largest.nodes = std::max(largest.nodes, part->nodes);
        largest.depth = std::max(largest.depth, part->depth);
      }
      add(largest);
    }
    // m_states may have rehashed during the recursion: look the state up again.
    State& finished = m_states[node];
    finished.visiting = false;
    finished.done = true;
    finished.expansion = total;
    return total;
  }

 private:
  struct State {
    bool visiting = false;
    bool done = false;
    Expansion expansion;
  };

  void index(const XMLElement* element) {
    for (const XMLElement* child = element->FirstChildElement(); child;
         child = child->NextSiblingElement()) {
      if (isNamed(child, "node")) {
        for (const char* attribute : {"id", "sid", "name"}) {
          if (const char* value = child->Attribute(attribute)) m_byName[value].push_back(child);
        }
      }
      index(child);
    }
  }

  static std::string nodeName(const XMLElement* node) {
    for (const char* attribute : {"id", "name", "sid"}) {
      if (const char* value = node->Attribute(attribute)) return quoted(value);
    }
    return "(unnamed)";
  }

  Error tooDeep(const XMLElement* node) const {
    return lineError(m_path, node->GetLineNum(),
                     "nodes nest deeper than " + std::to_string(kMaxColladaNodeDepth) +
                         " levels (directly or through <instance_node>) at node " +
                         nodeName(node) + "; refused");
  }

  const std::string& m_path;
  std::unordered_map<const XMLElement*, State> m_states;
  std::unordered_map<std::string, std::vector<const XMLElement*>> m_byName;
};

// The index lists (<p>, <vcount>, <v>, <h>, <int_array>): assimp 5.2.5
// reads them without checking what it reads, and a single character that is
// not a digit ("0 2x1", "0.5") makes it append indices until it has
// allocated gigabytes; a minus sign gives an index it does not check.
bool isIndexList(const XMLElement* element) {
  for (const char* name : {"p", "vcount", "v", "h", "int_array"}) {
    if (isNamed(element, name)) return true;
  }
  return false;
}

// The number lists assimp parses as reals: when one fails to parse inside a
// <node>, assimp 5.2.5 throws and leaks the nodes it has built (found by
// fuzz_dae_mesh), so they are checked here first.
bool isRealList(const XMLElement* element) {
  for (const char* name : {"float_array", "matrix", "translate", "rotate", "scale", "lookat", "skew",
                           "bind_shape_matrix"}) {
    if (isNamed(element, name)) return true;
  }
  return false;
}

// How many numbers a node's transform element holds; 0 for other lists.
// assimp 5.2.5 throws on a transform of another length with the nodes it
// built leaked (fuzz_dae_mesh: a <matrix> of 15 numbers).
std::size_t transformArity(const XMLElement* element) {
  if (isNamed(element, "matrix")) return 16;
  if (isNamed(element, "translate") || isNamed(element, "scale")) return 3;
  if (isNamed(element, "rotate")) return 4;
  if (isNamed(element, "lookat")) return 9;
  if (isNamed(element, "skew")) return 7;
  return 0;
}

Expected<bool> checkRealList(const XMLElement* element, const std::string& path) {
  const std::string_view text = element->GetText() ? element->GetText() : "";
  std::size_t numbers = 0;
  for (size_t i = 0; i < text.size();) {
    if (isXmlSpace(text[i])) {
      ++i;
      continue;
    }
    size_t end = i;
    while (end < text.size() && !isXmlSpace(text[end])) ++end;
    std::string_view token = text.substr(i, end - i);
    // xs:double allows one sign; from_chars takes '-' only, and assimp
    // fails (leaking its nodes) on "+-1" (fuzz_dae_mesh).
    if (token.front() == '+' && token.size() > 1 && token[1] != '-' && token[1] != '+') token.remove_prefix(1);
    double value = 0.0;
    const auto result = std::from_chars(token.data(), token.data() + token.size(), value);
    if (result.ec != std::errc() || result.ptr != token.data() + token.size() ||
        !std::isfinite(value)) {
      return lineError(path, element->GetLineNum(),
                       std::string("<") + element->Name() + "> holds " + quoted(text.substr(i, end - i)) +
                           ", which is not a finite number");
    }
    ++numbers;
    i = end;
  }
  const std::size_t arity = transformArity(element);
  if (arity != 0 && numbers != arity) {
    return lineError(path, element->GetLineNum(),
                     std::string("<") + element->Name() + "> holds " + std::to_string(numbers) +
                         " numbers; it takes " + std::to_string(arity));
  }
  return true;
}

// How many values a list holds (separated by XML's white space).
unsigned long long valueCount(const XMLElement* list) {
  const std::string_view text = list && list->GetText() ? list->GetText() : "";
  unsigned long long values = 0;
  for (std::size_t i = 0; i < text.size();) {
    while (i < text.size() && isXmlSpace(text[i])) ++i;
    if (i == text.size()) break;
    ++values;
    while (i < text.size() && !isXmlSpace(text[i])) ++i;
  }
  return values;
}

// A primitive's index lists hold what its count and inputs say: each
// vertex takes one index per input offset; a triangle three vertices, a
// line two, a polylist's polygon its <vcount>. assimp 5.2.5 asserts (and
// aborts, in Debian's build) or reads past its buffers otherwise
// (fuzz_dae_mesh: a <triangles> whose <p> was lost).
Expected<bool> checkIndexCounts(const XMLElement* primitive, const std::string& path) {
  const bool triangles = isNamed(primitive, "triangles"), lines = isNamed(primitive, "lines");
  const bool polylist = isNamed(primitive, "polylist"), polygons = isNamed(primitive, "polygons");
  const bool strips = isNamed(primitive, "linestrips") || isNamed(primitive, "trifans") || isNamed(primitive, "tristrips");
  if (!triangles && !lines && !polylist && !polygons && !strips) return true;
  unsigned long long stride = 1;
  for (const XMLElement* input = primitive->FirstChildElement("input"); input; input = input->NextSiblingElement("input")) {
    const char* offset = input->Attribute("offset");
    const unsigned long long at = offset ? std::strtoull(offset, nullptr, 10) : 0;
    if (at >= 64) return lineError(path, input->GetLineNum(), "<input> has an offset beyond 63; refused");
    stride = std::max(stride, at + 1);
  }
  const char* countText = primitive->Attribute("count");  // there, but for one in vendor data
  const unsigned long long count = countText ? std::strtoull(countText, nullptr, 10) : 0;
  const auto wrong = [&](const XMLElement* list, unsigned long long expected) {
    return lineError(path, list ? list->GetLineNum() : primitive->GetLineNum(),
                     std::string("<") + primitive->Name() + " count=\"" + std::to_string(count) + "\"> with " +
                         std::to_string(stride) + " index(es) per vertex needs " + std::to_string(expected) +
                         " indices in its <p>, which holds " + std::to_string(valueCount(list)));
  };
  const XMLElement* first = primitive->FirstChildElement("p");
  if (triangles || lines) {
    const unsigned long long expected = count * (triangles ? 3 : 2) * stride;
    if (count > 0 && valueCount(first) != expected) return wrong(first, expected);
  } else if (polylist) {
    const XMLElement* vcount = primitive->FirstChildElement("vcount");
    unsigned long long vertices = 0, polygonsListed = 0;
    const std::string_view text = vcount && vcount->GetText() ? vcount->GetText() : "";
    for (std::size_t i = 0; i < text.size();) {
      while (i < text.size() && isXmlSpace(text[i])) ++i;
      if (i == text.size()) break;
      std::size_t end = i;
      while (end < text.size() && !isXmlSpace(text[end])) ++end;
      const unsigned long long n = std::strtoull(std::string(text.substr(i, end - i)).c_str(), nullptr, 10);
      if (n < 3) return lineError(path, vcount->GetLineNum(), "<vcount> lists a polygon of fewer than 3 vertices");
      vertices += n;
      ++polygonsListed;
      i = end;
    }
    if (count > 0 && polygonsListed != count)
      return lineError(path, vcount ? vcount->GetLineNum() : primitive->GetLineNum(),
                       "<polylist count=\"" + std::to_string(count) + "\"> has " + std::to_string(polygonsListed) +
                           " polygons in its <vcount>");
    if (count > 0 && valueCount(first) != vertices * stride) return wrong(first, vertices * stride);
  } else {  // polygons and strips: each list whole vertices, at least a triangle's (a line's)
    const unsigned long long least = (isNamed(primitive, "linestrips") ? 2 : 3) * stride;
    for (const XMLElement* list = first; list; list = list->NextSiblingElement("p")) {
      const unsigned long long values = valueCount(list);
      if (values % stride != 0 || values < least)
        return lineError(path, list->GetLineNum(),
                         "<p> of a <" + std::string(primitive->Name()) + "> holds " + std::to_string(values) +
                             " indices: not whole vertices of " + std::to_string(stride) + ", or fewer than " +
                             std::to_string(least / stride));
    }
  }
  return true;
}

// Every count and stride attribute (float_array, accessor, triangles, ...)
// and the <vcount> lists: assimp reserves memory by them before it reads
// what they count. Each counted value takes at least two bytes of the file
// (a digit and a separator), a triangle three values.
Expected<bool> checkNumbers(const XMLElement* element, std::size_t fileBytes,
                            const std::string& path) {
  for (const XMLElement* child = element->FirstChildElement(); child;
       child = child->NextSiblingElement()) {
    for (const char* attribute : {"count", "stride"}) {
      const char* value = child->Attribute(attribute);
      if (!value) continue;
      const std::string_view text(value);
      const std::size_t largest = isNamed(child, "triangles") ? fileBytes / 6 : fileBytes / 2;
      unsigned long long number = 0;
      const auto result = std::from_chars(text.data(), text.data() + text.size(), number);
      if (result.ec != std::errc() || result.ptr != text.data() + text.size() ||
          number > largest) {
        return lineError(path, child->GetLineNum(),
                         std::string("<") + child->Name() + "> has " + attribute + "=" +
                             quoted(text) + ": not a whole number small enough for a file of " +
                             std::to_string(fileBytes) + " bytes");
      }
    }
    // assimp 5.2.5 is built with its assertions on in Debian: a <polygons>
    // whose count is not its number of <p> aborts the process (found by
    // fuzz_dae_mesh), as may a <triangles> or <polylist> with several.
    // A reference to another file is never followed (the file is untrusted),
    // and assimp 5.2.5 leaks the nodes it built when it meets one.
    if (std::strncmp(child->Name(), "instance_", 9) == 0) {
      const char* url = child->Attribute("url");
      if (url && url[0] != '#') {
        return lineError(path, child->GetLineNum(),
                         std::string("<") + child->Name() + " url=" + quoted(url) +
                             "> refers outside this file; references to other files are not "
                             "followed (mesh files are untrusted input)");
      }
    }
    // Attributes COLLADA requires and assimp 5.2.5 reads without checking
    // (a <float_array> without its count crashes it: fuzz_dae_mesh).
    const auto requireAttribute = [&](const char* attribute) -> std::optional<Error> {
      if (child->Attribute(attribute)) return std::nullopt;
      return lineError(path, child->GetLineNum(),
                       std::string("<") + child->Name() + "> has no " + attribute + "= attribute");
    };
    for (const char* array : {"float_array", "int_array", "bool_array", "Name_array", "IDREF_array", "SIDREF_array"})
      if (isNamed(child, array))
        if (auto missing = requireAttribute("count")) return *missing;
    if (isNamed(child, "accessor"))
      if (auto missing = requireAttribute("count")) return *missing;
    if (isNamed(child, "input"))
      if (auto missing = requireAttribute("semantic")) return *missing;
    // COLLADA requires the count; assimp takes a missing one as 0.
    for (const char* primitives :
         {"polygons", "triangles", "polylist", "lines", "linestrips", "trifans", "tristrips"}) {
      if (isNamed(child, primitives) && !child->Attribute("count")) {
        return lineError(path, child->GetLineNum(),
                         std::string("<") + child->Name() + "> has no count= attribute");
      }
    }
    if (isNamed(child, "polygons") || isNamed(child, "triangles") || isNamed(child, "polylist")) {
      long long lists = 0;
      for (const XMLElement* list = child->FirstChildElement("p"); list;
           list = list->NextSiblingElement("p")) {
        ++lists;
      }
      const char* declared = child->Attribute("count");
      const bool none = std::string_view(declared) == "0";
      if (isNamed(child, "polygons") ? std::to_string(lists) != declared : lists != (none ? 0 : 1)) {
        return lineError(path, child->GetLineNum(),
                         std::string("<") + child->Name() + "> has " + std::to_string(lists) +
                             " <p> lists, which its count= does not allow (one per polygon of "
                             "<polygons>, one in all otherwise)");
      }
    }
    // A list is text alone: tinyxml2's GetText() sees only what comes
    // before an element inside it, where assimp reads on (an <input> inside
    // a <p> overflowed a buffer in assimp: fuzz_dae_mesh).
    if ((isRealList(child) || isIndexList(child)) && child->FirstChildElement() != nullptr) {
      return lineError(path, child->GetLineNum(),
                       std::string("<") + child->Name() + "> holds an element <" +
                           child->FirstChildElement()->Name() + ">; a list holds numbers only");
    }
    if (isRealList(child)) {
      Expected<bool> reals = checkRealList(child, path);
      if (!reals) return reals;
    }
    if (isIndexList(child)) {
      const std::string_view text = child->GetText() ? child->GetText() : "";
      unsigned long long total = 0;
      for (size_t i = 0; i < text.size();) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (isXmlSpace(static_cast<char>(c))) {
          ++i;
          continue;
        }
        unsigned long long number = 0;
        const auto result = std::from_chars(text.data() + i, text.data() + text.size(), number);
        const size_t end = static_cast<size_t>(result.ptr - text.data());
        if (result.ec != std::errc() ||
            (end < text.size() && !isXmlSpace(text[end]))) {
          return lineError(path, child->GetLineNum(),
                           std::string("<") + child->Name() + "> holds " +
                               quoted(text.substr(i, std::min<size_t>(text.size() - i, 12))) +
                               ": it must hold whole numbers (indices) only");
        }
        total += std::min<unsigned long long>(number, fileBytes);
        i = end;
      }
      if (isNamed(child, "vcount") && total > fileBytes / 2) {
        return lineError(path, child->GetLineNum(),
                         "<vcount> adds up to more vertices than a file of " +
                             std::to_string(fileBytes) + " bytes can index");
      }
    }
    Expected<bool> inner = checkNumbers(child, fileBytes, path);
    if (!inner) return inner;
  }
  return true;
}

Expected<ColladaAsset> readAsset(const XMLElement* root, const std::string& path) {
  ColladaAsset asset;
  const XMLElement* info = root->FirstChildElement("asset");
  if (!info) return asset;
  if (const XMLElement* unit = info->FirstChildElement("unit")) {
    if (const char* value = unit->Attribute("meter")) {
      const std::string_view text = trimmed(value);
      double metres = 0.0;
      const auto result = std::from_chars(text.data(), text.data() + text.size(), metres);
      if (result.ec != std::errc() || result.ptr != text.data() + text.size() ||
          !std::isfinite(metres) || metres <= 0.0) {
        return lineError(path, unit->GetLineNum(),
                         "<unit meter=" + quoted(value) + "> is not a positive finite number");
      }
      asset.metresPerUnit = metres;
    }
  }
  if (const XMLElement* up = info->FirstChildElement("up_axis")) {
    const std::string_view text = trimmed(up->GetText() ? up->GetText() : "");
    if (text == "X_UP") {
      asset.up = UpAxis::kX;
    } else if (text == "Y_UP") {
      asset.up = UpAxis::kY;
    } else if (text == "Z_UP") {
      asset.up = UpAxis::kZ;
    } else {
      return lineError(path, up->GetLineNum(),
                       "<up_axis> is " + quoted(text) + ", not X_UP, Y_UP or Z_UP");
    }
  }
  return asset;
}

std::size_t occurrences(std::string_view text, std::string_view word) {
  std::size_t count = 0;
  for (std::size_t at = text.find(word); at != std::string_view::npos;
       at = text.find(word, at + word.size())) {
    ++count;
  }
  return count;
}

}  // namespace

// Every reference inside the file must name an element of it: an
// <instance_...>'s url, an <input>'s or <accessor>'s source, an
// <instance_material>'s target, each "#id" of an element's id (or, as
// assimp also looks them up, its sid). assimp 5.2.5 throws on a missing or
// dangling one with what it had built leaked (fuzz_dae_mesh: an
// <instance_geometry> without its url).
// The elements a static mesh file is made of: its asset, geometry, scene
// graph, and the materials, effects, images, cameras and lights exporters
// write beside them. Anything else is refused before assimp reads the file:
// assimp 5.2.5 mishandles elements it does not expect (a misspelt
// <instance_geometry> inside a <node> makes it allocate 2 GiB: found by
// fuzz_dae_mesh). What an <extra> or a profile's own <technique> holds is
// vendor data assimp passes over, and is not looked into.
bool isMeshFileElement(const XMLElement* element) {
  static const std::unordered_set<std::string_view> kNames = {
      // the document and its asset
      "COLLADA", "asset", "contributor", "author", "author_email", "author_website", "authoring_tool", "comments",
      "copyright", "source_data", "created", "modified", "keywords", "revision", "subject", "title", "unit",
      "up_axis", "coverage", "geographic_location", "longitude", "latitude", "altitude", "extra", "technique",
      // libraries
      "library_geometries", "library_visual_scenes", "library_nodes", "library_materials", "library_effects",
      "library_images", "library_cameras", "library_lights", "library_controllers", "library_animations",
      // geometry
      "geometry", "mesh", "source", "float_array", "int_array", "bool_array", "Name_array", "IDREF_array",
      "SIDREF_array", "technique_common", "accessor", "param", "vertices", "input", "triangles", "polylist",
      "polygons", "lines", "linestrips", "trifans", "tristrips", "p", "vcount", "ph", "h",
      // the scene graph
      "visual_scene", "node", "matrix", "translate", "rotate", "scale", "lookat", "skew", "instance_geometry",
      "instance_node", "instance_camera", "instance_light", "bind_material", "instance_material",
      "bind_vertex_input", "bind", "scene", "instance_visual_scene",
      // materials, effects and images
      "material", "instance_effect", "setparam", "effect", "profile_COMMON", "newparam", "surface", "sampler2D",
      "init_from", "format", "minfilter", "magfilter", "mipfilter", "wrap_s", "wrap_t", "phong", "lambert",
      "blinn", "constant", "emission", "ambient", "diffuse", "specular", "shininess", "reflective",
      "reflectivity", "transparent", "transparency", "index_of_refraction", "color", "float", "float2",
      "float3", "float4", "texture", "image", "ref", "hex",
      // cameras and lights
      "camera", "optics", "perspective", "orthographic", "xfov", "yfov", "xmag", "ymag", "aspect_ratio",
      "znear", "zfar", "light", "directional", "point", "spot", "constant_attenuation", "linear_attenuation",
      "quadratic_attenuation", "falloff_angle", "falloff_exponent"};
  return kNames.count(element->Name()) > 0;
}

// Where the document's parts may stand: the libraries and the scene only in
// <COLLADA>, an <asset> holding only what describes the asset (a file whose
// <asset> held its libraries made assimp leak: fuzz_dae_mesh).
std::optional<std::string> misplacedReason(const XMLElement* element) {
  const XMLElement* parent = element->Parent() ? element->Parent()->ToElement() : nullptr;
  const std::string_view name = element->Name();
  if ((name.rfind("library_", 0) == 0 || name == "scene") && (parent == nullptr || !isNamed(parent, "COLLADA")))
    return "stands outside <COLLADA>'s top level";
  if (parent != nullptr && isNamed(parent, "asset")) {
    static const std::unordered_set<std::string_view> kAssetParts = {
        "contributor", "created",  "modified", "keywords", "revision", "subject",
        "title",       "unit",     "up_axis",  "coverage", "extra"};
    if (!kAssetParts.count(name)) return "stands inside an <asset>, which describes the file only";
  }
  return std::nullopt;
}

Expected<bool> checkElementNames(const XMLElement* root, const std::string& path) {
  std::unordered_set<std::string_view> ids;
  std::vector<const XMLElement*> pending{root};
  while (!pending.empty()) {
    const XMLElement* element = pending.back();
    pending.pop_back();
    if (!isMeshFileElement(element)) {
      return lineError(path, element->GetLineNum(),
                       "<" + std::string(element->Name()) +
                           "> is not an element of a static COLLADA mesh file (animations, skins and "
                           "other content are not read); refused");
    }
    if (std::optional<std::string> why = misplacedReason(element))
      return lineError(path, element->GetLineNum(), "<" + std::string(element->Name()) + "> " + *why + "; refused");
    // An id names one element of the document (COLLADA requires it).
    if (const char* id = element->Attribute("id"); id && !ids.insert(id).second)
      return lineError(path, element->GetLineNum(),
                       "<" + std::string(element->Name()) + " id=" + quoted(id) +
                           ">: the id is already another element's; refused");
    const bool vendorData =
        isNamed(element, "extra") || (isNamed(element, "technique") && element->Attribute("profile") != nullptr);
    if (vendorData) continue;
    for (const XMLElement* child = element->FirstChildElement(); child; child = child->NextSiblingElement())
      pending.push_back(child);
  }
  return true;
}

Expected<bool> checkReferences(const XMLElement* root, const std::string& path) {
  std::unordered_set<std::string_view> names;
  std::vector<const XMLElement*> pending{root};
  while (!pending.empty()) {
    const XMLElement* element = pending.back();
    pending.pop_back();
    for (const char* attribute : {"id", "sid"})
      if (const char* value = element->Attribute(attribute)) names.insert(value);
    for (const XMLElement* child = element->FirstChildElement(); child; child = child->NextSiblingElement())
      pending.push_back(child);
  }
  pending.assign(1, root);
  while (!pending.empty()) {
    const XMLElement* element = pending.back();
    pending.pop_back();
    const char* attribute = nullptr;
    if (std::strncmp(element->Name(), "instance_", 9) == 0) attribute = isNamed(element, "instance_material") ? "target" : "url";
    if (isNamed(element, "input") || isNamed(element, "accessor")) attribute = "source";
    if (attribute != nullptr) {
      const char* value = element->Attribute(attribute);
      const std::string_view reference = value ? value : "";
      if (reference.size() < 2 || reference.front() != '#' || !names.count(reference.substr(1))) {
        return lineError(path, element->GetLineNum(),
                         std::string("<") + element->Name() + "> " + attribute + "=" +
                             (value ? quoted(reference) : std::string("(missing)")) +
                             " names no element of this file (references to other files are not "
                             "followed: mesh files are untrusted input)");
      }
    }
    if (isNamed(element, "extra") || (isNamed(element, "technique") && element->Attribute("profile") != nullptr))
      continue;  // vendor data, as checkElementNames
    for (const XMLElement* child = element->FirstChildElement(); child; child = child->NextSiblingElement())
      pending.push_back(child);
  }
  return true;
}

// The arrays hold what their count says (at least one value), and an
// accessor reads within its array: assimp 5.2.5 dereferences a null array
// on a count of 0 (fuzz_dae_mesh) and trusts the accessor's numbers.
Expected<bool> checkArrays(const XMLElement* root, const std::string& path) {
  std::unordered_map<std::string_view, unsigned long long> arrayCount;
  std::vector<const XMLElement*> accessors;
  std::vector<const XMLElement*> pending{root};
  while (!pending.empty()) {
    const XMLElement* element = pending.back();
    pending.pop_back();
    if (std::string_view(element->Name()).size() > 6 &&
        std::string_view(element->Name()).substr(std::string_view(element->Name()).size() - 6) == "_array") {
      // checkNumbers made count a whole number that is there.
      const char* countText = element->Attribute("count");
      const unsigned long long count = countText ? std::strtoull(countText, nullptr, 10) : 0;
      const std::string_view text = element->GetText() ? element->GetText() : "";
      unsigned long long values = 0;
      for (std::size_t i = 0; i < text.size();) {
        while (i < text.size() && isXmlSpace(text[i])) ++i;
        if (i == text.size()) break;
        ++values;
        while (i < text.size() && !isXmlSpace(text[i])) ++i;
      }
      if (count == 0 || values != count) {
        return lineError(path, element->GetLineNum(),
                         std::string("<") + element->Name() + "> has count=" + std::to_string(count) + " but holds " +
                             std::to_string(values) + " values" + (count == 0 ? " (an array holds at least one)" : ""));
      }
      if (const char* id = element->Attribute("id")) arrayCount[id] = count;
    }
    if (isNamed(element, "accessor")) accessors.push_back(element);
    if (isNamed(element, "extra") || (isNamed(element, "technique") && element->Attribute("profile") != nullptr))
      continue;  // vendor data, as checkElementNames
    for (const XMLElement* child = element->FirstChildElement(); child; child = child->NextSiblingElement())
      pending.push_back(child);
  }
  for (const XMLElement* accessor : accessors) {
    const std::string_view source = accessor->Attribute("source") ? accessor->Attribute("source") : "";
    const auto array = arrayCount.find(source.empty() ? source : source.substr(1));
    const char* countText = accessor->Attribute("count");
    const unsigned long long count = countText ? std::strtoull(countText, nullptr, 10) : 0;
    const unsigned long long stride = accessor->Attribute("stride") ? std::strtoull(accessor->Attribute("stride"), nullptr, 10) : 1;
    const unsigned long long offset = accessor->Attribute("offset") ? std::strtoull(accessor->Attribute("offset"), nullptr, 10) : 0;
    // Its params are read within each stride (assimp 5.2.5 runs on for
    // seconds allocating when three params share a stride of 1: fuzz_dae_mesh).
    unsigned long long params = 0;
    for (const XMLElement* param = accessor->FirstChildElement("param"); param; param = param->NextSiblingElement("param"))
      ++params;
    if (array == arrayCount.end() || stride == 0 || count == 0 || offset > array->second ||
        (array->second - offset) / stride < count || params > stride) {
      return lineError(path, accessor->GetLineNum(),
                       "<accessor source=" + quoted(source) + " count=" + std::to_string(count) + " stride=" +
                           std::to_string(stride) + "> with " + std::to_string(params) +
                           " params does not read within an array of the file");
    }
  }
  return true;
}

Expected<ColladaAsset> checkColladaDocument(std::string_view text, const std::string& path) {
  // tinyxml2 would end the text at a NUL where assimp's parser goes on, and
  // a document type declaration is read differently by the two; COLLADA
  // needs neither.
  if (text.find('\0') != std::string_view::npos) {
    return Error{path + ": contains a NUL byte: not a text COLLADA file"};
  }
  if (text.find("<!DOCTYPE") != std::string_view::npos) {
    return Error{path + ": has a <!DOCTYPE> declaration, which COLLADA does not use; refused"};
  }
  tinyxml2::XMLDocument document;
  if (document.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    const char* reason = document.ErrorStr();
    return lineError(path, document.ErrorLineNum(),
                     std::string("not well-formed XML (") + (reason ? reason : "no reason given") +
                         ")");
  }
  const XMLElement* root = document.RootElement();
  if (!root || !isNamed(root, "COLLADA")) {
    return Error{path + ": not a COLLADA document (its root element is " +
                 (root ? quoted(root->Name()) : std::string("missing")) + ", not COLLADA)"};
  }
  Expected<bool> counts = checkNumbers(root, text.size(), path);
  if (!counts) return counts.error();

  if (Expected<bool> names = checkElementNames(root, path); !names) return names.error();
  if (Expected<bool> references = checkReferences(root, path); !references) return references.error();
  if (Expected<bool> arrays = checkArrays(root, path); !arrays) return arrays.error();
  // After the lists' own checks above (whole numbers, text alone).
  for (std::vector<const XMLElement*> pending{root}; !pending.empty();) {
    const XMLElement* element = pending.back();
    pending.pop_back();
    if (Expected<bool> indices = checkIndexCounts(element, path); !indices) return indices.error();
    for (const XMLElement* child = element->FirstChildElement(); child; child = child->NextSiblingElement())
      pending.push_back(child);
  }

  NodeGraph graph(root, path);
  std::size_t instanceElements = 0;
  long long sceneNodes = 0;
  std::vector<const XMLElement*> scenes;
  // Visual scenes sit in <library_visual_scenes>; looking everywhere can only
  // count more.
  std::vector<const XMLElement*> pending{root};
  while (!pending.empty()) {
    const XMLElement* element = pending.back();
    pending.pop_back();
    for (const XMLElement* child = element->FirstChildElement(); child;
         child = child->NextSiblingElement()) {
      if (isNamed(child, "visual_scene")) scenes.push_back(child);
      if (isNamed(child, "instance_node")) ++instanceElements;
      pending.push_back(child);
    }
  }
  // tinyxml2 and assimp's own XML parser must see the same instances, or the
  // check above would not be about the graph assimp builds.
  if (occurrences(text, "<instance_node") != instanceElements) {
    return Error{path + ": '<instance_node' appears where it is not an element (in a comment or "
                        "text?); refused, since the node graph could not be checked"};
  }
  for (const XMLElement* scene : scenes) {
    std::vector<const XMLElement*> nodes;
    std::vector<std::string_view> urls;
    collectParts(scene, nodes, urls);
    for (const XMLElement* node : nodes) {
      Expected<NodeGraph::Expansion> expansion = graph.expand(node, 1);
      if (!expansion) return expansion.error();
      sceneNodes = std::min(sceneNodes + expansion->nodes, kMaxColladaNodes + 1);
    }
    if (!urls.empty()) {
      return lineError(path, scene->GetLineNum(),
                       "<instance_node> directly in a <visual_scene> (outside any <node>) is "
                       "not COLLADA; refused");
    }
  }
  // A dangling <instance_visual_scene> makes assimp 5.2.5 throw with the
  // nodes it built leaked (found by fuzz_dae_mesh).
  for (const XMLElement* scene = root->FirstChildElement("scene"); scene;
       scene = scene->NextSiblingElement("scene")) {
    for (const XMLElement* instance = scene->FirstChildElement("instance_visual_scene"); instance;
         instance = instance->NextSiblingElement("instance_visual_scene")) {
      std::string_view url = instance->Attribute("url") ? instance->Attribute("url") : "";
      if (!url.empty() && url.front() == '#') url.remove_prefix(1);
      const bool found = std::any_of(scenes.begin(), scenes.end(), [&](const XMLElement* visual) {
        const char* id = visual->Attribute("id");
        return id && url == id;
      });
      if (!found) {
        return lineError(path, instance->GetLineNum(),
                         "<instance_visual_scene url=" + quoted(url) +
                             "> names no <visual_scene> of the file");
      }
    }
  }
  if (sceneNodes > kMaxColladaNodes) {
    return Error{path + ": the visual scenes have more than " + std::to_string(kMaxColladaNodes) +
                 " nodes with every <instance_node> expanded; larger scenes are rejected (mesh "
                 "files are untrusted input)"};
  }
  return readAsset(root, path);
}

}  // namespace rbsim::meshio
