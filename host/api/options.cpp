// clmesh — Triangle's switch letters as Options, and their validation.
#include "clmesh/options.hpp"

#include "clmesh/errors.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>

namespace clmesh {

namespace {

const char *const kSupported =
    "-p -r -c -O -A -D -Y -B -q -a -S -z -e -n -v -g -o2 -N -E -P -I -j -Q "
    "-V -C -h (-X -i -F -l -s accepted without effect)";

// Triangle's switches that clmesh does not implement yet, with what they do.
const char *unsupported_switch(char letter) {
  switch (letter) {
  case 'u':
    return "a user-defined triangle sizing function compiled into Triangle "
           "(triunsuitable()); clmesh takes it as a library callback (Options::unsuitable) or "
           "as a sizing field (--size-field)";
  default:
    return nullptr;
  }
}

// Triangle's choices of arithmetic and algorithm: clmesh's predicates are
// always exact and its algorithms are GPU-DT, GPU-CDT and GPU-QM(-V), so
// these letters are accepted and change nothing.
bool without_effect(char letter) {
  return letter == 'X' || letter == 'i' || letter == 'F' || letter == 'l' || letter == 's';
}

// The number that follows a switch letter at text[i + 1...] (Triangle's -q30,
// -a0.01, -S100, -a1e-3), advancing i past it; empty when none follows.
std::string switch_number(const std::string &text, std::size_t &i) {
  auto digit = [&](std::size_t k) {
    return k < text.size() && std::isdigit(static_cast<unsigned char>(text[k]));
  };
  std::size_t end = i + 1;
  while (end < text.size()) {
    const char c = text[end];
    const bool exponent = (c == 'e' || c == 'E') &&
                          (digit(end + 1) || (end + 1 < text.size() && text[end + 1] == '-'));
    if (!digit(end) && c != '.' && !exponent)
      break;
    end += exponent && text[end + 1] == '-' ? 2 : 1;
  }
  std::string number = text.substr(i + 1, end - i - 1);
  i = end - 1;
  return number;
}

double switch_value(const std::string &number, char letter) {
  char *end = nullptr;
  const double value = std::strtod(number.c_str(), &end);
  if (number.empty() || *end != '\0' || !std::isfinite(value))
    throw OptionError(std::string("-") + letter + ": " + quote(number) + " is not a number");
  return value;
}

} // namespace

const char *supported_switches() { return kSupported; }

void parse_switches(const std::string &switches, Options &options) {
  char unsupported = 0; // refused once every letter is known to be a switch
  for (std::size_t i = switches.rfind('-', 0) == 0 ? 1 : 0; i < switches.size(); ++i) {
    const char letter = switches[i];
    switch (letter) {
    case 'q': {
      options.quality = true;
      const std::string number = switch_number(switches, i);
      options.min_angle = number.empty() ? 20 : switch_value(number, 'q');
      break;
    }
    case 'a': {
      const std::string number = switch_number(switches, i);
      if (number.empty()) { // Triangle: per-region (or, with -r, per-triangle) areas
        options.regional_areas = true;
        break;
      }
      options.max_area = switch_value(number, 'a');
      if (*options.max_area <= 0)
        throw OptionError("-a: the maximum area must be positive");
      break;
    }
    case 'S': {
      const std::string number = switch_number(switches, i);
      const double value = number.empty() ? 0 : switch_value(number, 'S');
      if (value < 0 || value > 1e18)
        throw OptionError("-S: " + quote(number) + " is not a number of points");
      options.max_steiner = static_cast<long>(value);
      break;
    }
    case 'p':
      options.pslg = true;
      break;
    case 'r':
      options.refine = true;
      break;
    case 'c':
      options.convex_hull = true;
      break;
    case 'O':
      options.ignore_holes = true;
      break;
    case 'A':
      options.regional_attributes = true;
      break;
    case 'D':
      options.conforming_delaunay = true;
      break;
    case 'Y':
      options.no_steiner_on_segments = std::min(options.no_steiner_on_segments + 1, 2);
      break;
    case 'B':
      options.no_boundary_markers = true;
      break;
    case 'z':
      options.zero_based = true;
      break;
    case 'e':
      options.edges = true;
      break;
    case 'n':
      options.neighbors = true;
      break;
    case 'N':
      options.no_node_file = true;
      break;
    case 'E':
      options.no_ele_file = true;
      break;
    case 'I':
      options.no_iteration_number = true;
      break;
    case 'j':
      options.jettison = true;
      break;
    case 'Q':
      options.quiet = true;
      break;
    case 'V':
      ++options.verbose;
      break;
    case 'C':
      options.check = true;
      break;
    case 'h':
      options.help = true;
      break;
    case 'P':
      options.no_poly_file = true;
      break;
    case 'g':
      options.off_file = true;
      break;
    case 'v':
      options.voronoi = true;
      break;
    case 'o':
      // Triangle's only order is 2: -o2.
      if (i + 1 >= switches.size() || switches[i + 1] != '2')
        throw OptionError("-o takes the order 2 (-o2: second-order, six-node triangles) in " +
                          quote(switches));
      options.second_order = true;
      ++i;
      break;
    default:
      if (without_effect(letter)) {
        if (options.no_effect_switches.find(letter) == std::string::npos)
          options.no_effect_switches += letter;
        break;
      }
      if (unsupported_switch(letter)) {
        if (!unsupported)
          unsupported = letter;
        break;
      }
      throw OptionError("unknown switch -" + printable(std::string(1, letter)) + " in " +
                        quote(switches) + "; valid switches: " + kSupported);
    }
  }
  if (unsupported)
    throw OptionError(std::string("switch -") + unsupported + " (" +
                      unsupported_switch(unsupported) + ") is not supported yet; clmesh supports " +
                      kSupported);
}

Options parse_switches(const std::string &switches) {
  Options options;
  parse_switches(switches, options);
  return options;
}

void validate(const Options &options) {
  if (options.regional_areas && !options.pslg && !options.refine)
    throw OptionError("-a without a number applies the maximum areas of a .poly file's regions "
                      "(-p) or of an .area file's triangles (-r): it needs -p or -r");
  if (options.size_field)
    validate(*options.size_field);
  if (options.quality && !(options.min_angle >= 0 && options.min_angle <= 45))
    throw OptionError("the minimum angle (-q) must be between 0 and 45 degrees");
  if (options.max_area && !(*options.max_area > 0))
    throw OptionError("-a: the maximum area must be positive");
  if (options.max_steiner && *options.max_steiner < 0)
    throw OptionError("-S: the number of Steiner points cannot be negative");
  const Tuning &tuning = options.tuning;
  if (tuning.grid && (*tuning.grid < 2 || *tuning.grid > 8192))
    throw OptionError("the Voronoi grid must be between 2 and 8192");
  if (tuning.work_group && *tuning.work_group < 1)
    throw OptionError("the work-group size must be at least 1");
  if (tuning.filter_rings != 2 && tuning.filter_rings != 3)
    throw OptionError("the insertion filter looks at 2 or 3 rings of triangles");
  if (tuning.filter_distance_rings < 0 || tuning.filter_distance_rings > 1)
    throw OptionError("the insertion filter looks 0 or 1 ring further for dependent pairs");
  if (tuning.election_rings < 0 || tuning.election_rings > 2)
    throw OptionError("the election looks at 0, 1 or 2 rings of triangles");
  if (tuning.filter_near != 0 && !(tuning.filter_near >= 1))
    throw OptionError("the insertion filter's nearness is 0 (any distance) or at least 1");
}

} // namespace clmesh
