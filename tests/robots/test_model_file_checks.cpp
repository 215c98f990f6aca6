// Model loader, the checks below the pcr elements: the text of a model file must be UTF-8 XML characters
// before any parser reads it, and every <inertial> is read by pcr (urdfdom logs a malformed one and
// drops it, which lost the platform mass silently). Each case changes one piece of a valid model and
// expects pcr's own message: file, line (and column for the text), element, attribute and value. The
// expected line numbers are counted in the XML text of the case itself.
#define BOOST_TEST_MODULE model_file_checks
#include <boost/test/unit_test.hpp>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "model_xml.hpp"
#include "pcr/core/error.hpp"
#include "pcr/robots/urdf_loader.hpp"

using namespace pcr;
using test::check_rejected;

namespace {

// A platform on one clamped-clamped rod: the smallest model that loads (its platform is held).
const std::string kRod = R"(<pcr_rod name="r0">
<start link="base" coupling="clamped"/><end link="platform" coupling="clamped"/>
<material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>
<section type="circle" radius="0.001"/><length value="0.3"/></pcr_rod>
)";

// The model with `inertial` as the platform link's content and `base` as the base link's.
std::string model_with(const std::string& inertial, const std::string& base = "") {
  return "<?xml version=\"1.0\"?>\n<robot name=\"test\">\n<link name=\"base\">" + base +
         "</link>\n<link name=\"platform\">\n" + inertial +
         "</link>\n<joint name=\"float\" type=\"floating\"><parent link=\"base\"/>"
         "<child link=\"platform\"/>\n<origin xyz=\"0 0 0.3\"/></joint>\n" +
         kRod + "</robot>\n";
}

std::string inertial(const std::string& origin, const std::string& mass, const std::string& inertia) {
  return "<inertial>\n" + origin + "\n" + mass + "\n" + inertia + "\n</inertial>\n";
}
const std::string kOrigin = R"(<origin xyz="0 0 0.01" rpy="0 0 0"/>)";
const std::string kMass = R"(<mass value="0.05"/>)";
const std::string kInertia = R"(<inertia ixx="1e-5" ixy="0" ixz="0" iyy="1e-5" iyz="0" izz="2e-5"/>)";

// "bad.urdf:<line>:" for the first line of xml that contains needle (lines counted from 1).
std::string at_line_of(const std::string& xml, const std::string& needle) {
  const std::size_t position = xml.find(needle);
  BOOST_REQUIRE_MESSAGE(position != std::string::npos, "no \"" << needle << "\" in the case");
  int line = 1;
  for (std::size_t i = 0; i < position; ++i) line += xml[i] == '\n' ? 1 : 0;
  return "bad.urdf:" + std::to_string(line) + ":";
}

}  // namespace

// ------------------------------------------------------------------------------------------- inertial
BOOST_AUTO_TEST_CASE(a_valid_inertial_gives_the_platform_mass_and_centre) {
  const RobotModel m = parse_robot_model(model_with(inertial(kOrigin, kMass, kInertia)), "good.urdf");
  BOOST_TEST(m.platforms().size() == 1u);
  BOOST_TEST(m.platforms()[0].mass == 0.05);  // the decimal literal of the file, parsed exactly alike
  BOOST_TEST((m.platforms()[0].center_of_mass - Vec3(0, 0, 0.01)).norm() == 0.0);
  // <origin> is optional (URDF): the centre of mass is then the link origin.
  const RobotModel no_origin = parse_robot_model(model_with(inertial("", kMass, kInertia)), "good.urdf");
  BOOST_TEST(no_origin.platforms()[0].center_of_mass.norm() == 0.0);
  BOOST_TEST(no_origin.platforms()[0].mass == 0.05);
}

BOOST_AUTO_TEST_CASE(every_malformed_mass_is_rejected) {
  for (const std::string value : {"nan", "NaN", "inf", "-inf", "abc", "1e400", "0.1kg", "0.1 0.2", ""}) {
    const std::string xml = model_with(inertial(kOrigin, "<mass value=\"" + value + "\"/>", kInertia));
    check_rejected(xml, {at_line_of(xml, "<mass"), "link 'platform' <inertial> <mass>", "'value'",
                         "\"" + value + "\"", "not a finite number"});
  }
  for (const std::string value : {"-0.1", "-1e-300"}) {
    const std::string xml = model_with(inertial(kOrigin, "<mass value=\"" + value + "\"/>", kInertia));
    check_rejected(xml, {at_line_of(xml, "<mass"), "link 'platform' <inertial> <mass>", "'value'",
                         "\"" + value + "\"", "non-negative"});
  }
  const std::string no_value = model_with(inertial(kOrigin, "<mass/>", kInertia));
  check_rejected(no_value, {at_line_of(no_value, "<mass"), "<inertial> <mass>", "missing attribute 'value'"});
  const std::string no_mass = model_with(inertial(kOrigin, "", kInertia));
  check_rejected(no_mass,
                 {at_line_of(no_mass, "<inertial>"), "link 'platform' <inertial>", "missing element <mass>"});
  const std::string two_masses = model_with(inertial(kOrigin, kMass + kMass, kInertia));
  check_rejected(two_masses, {"link 'platform' <inertial>", "<mass> given more than once"});
}

BOOST_AUTO_TEST_CASE(every_malformed_centre_of_mass_is_rejected) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"xyz", "nan 0 0"}, {"xyz", "0 abc 0"}, {"xyz", "0 0 1e400"}, {"xyz", "0 0"},
      {"rpy", "0 nan 0"}, {"rpy", "0 0 inf"}, {"rpy", "x y z"},     {"xyz", ""}};
  for (const auto& [attribute, value] : cases) {
    const std::string origin = "<origin " + attribute + "=\"" + value + "\"/>";
    const std::string xml = model_with(inertial(origin, kMass, kInertia));
    check_rejected(xml, {at_line_of(xml, "<origin " + attribute), "link 'platform' <inertial> <origin>",
                         "'" + attribute + "'", "\"" + value + "\""});
  }
}

BOOST_AUTO_TEST_CASE(every_malformed_inertia_is_rejected) {
  // The tensor is not used (statics), but a malformed one is still an error, not a value dropped.
  for (const std::string entry : {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}) {
    for (const std::string value : {"nan", "1e400", "abc", ""}) {
      std::string inertia = kInertia;
      const std::size_t at = inertia.find(entry + "=\"");
      const std::size_t end = inertia.find('"', at + entry.size() + 2);
      inertia.replace(at, end + 1 - at, entry + "=\"" + value + "\"");
      const std::string xml = model_with(inertial(kOrigin, kMass, inertia));
      check_rejected(xml, {at_line_of(xml, "<inertia "), "link 'platform' <inertial> <inertia>",
                           "'" + entry + "'", "\"" + value + "\"", "not a finite number"});
    }
  }
  const std::string no_izz =
      model_with(inertial(kOrigin, kMass, R"(<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0"/>)"));
  check_rejected(no_izz, {"<inertial> <inertia>", "missing attribute 'izz'"});
  const std::string no_inertia = model_with(inertial(kOrigin, kMass, ""));
  check_rejected(no_inertia, {"link 'platform' <inertial>", "missing element <inertia>"});
}

BOOST_AUTO_TEST_CASE(inertials_are_checked_on_every_link) {
  // The base's mass is not used (the world carries it), but a malformed value there is an error too.
  const std::string bad_base = inertial(kOrigin, R"(<mass value="nan"/>)", kInertia);
  const std::string xml = model_with(inertial(kOrigin, kMass, kInertia), bad_base);
  check_rejected(xml, {at_line_of(xml, "<mass value=\"nan"), "link 'base' <inertial> <mass>", "\"nan\""});
  const std::string twice = inertial(kOrigin, kMass, kInertia);
  check_rejected(model_with(twice + twice), {"link 'platform'", "<inertial> given more than once"});
  // A well-formed base inertial loads and leaves the platform's mass alone.
  const RobotModel m = parse_robot_model(model_with(inertial("", kMass, kInertia), twice), "good.urdf");
  BOOST_TEST(m.platforms()[0].mass == 0.05);
}

// ----------------------------------------------------------------------------------------------- text
BOOST_AUTO_TEST_CASE(a_file_ending_inside_a_utf8_sequence_is_rejected_before_parsing) {
  // The input libFuzzer found (tests/data/fuzz_corpus/crash_truncated_utf8_attribute.urdf): TinyXML
  // stepped over the lone lead byte 0xE9 by 3 bytes, past the end of the text. Column 14 is the
  // character after `<robot name="`.
  const std::string attribute = "<?xml version=\"1.0\"?>\n<robot name=\"\xE9";
  check_rejected(attribute, {"bad.urdf:2:14:", "0xE9", "cut off by the end of the file"});
  const std::string text = "<?xml version=\"1.0\"?>\n<robot name=\"r\">\xE9\xA9";
  check_rejected(text, {"bad.urdf:2:17:", "3-byte", "0xE9", "cut off by the end of the file"});
  // The same through load_robot_model: the message names the path.
  const std::string path = "model_file_checks_truncated.urdf";
  {
    std::ofstream file(path, std::ios::binary);
    file << attribute;
  }
  try {
    load_robot_model(path);
    BOOST_ERROR("no InputError for " << path);
  } catch (const InputError& e) {
    BOOST_TEST(std::string(e.what()).find(path + ":2:14:") != std::string::npos, e.what());
  }
  std::remove(path.c_str());
}

BOOST_AUTO_TEST_CASE(every_malformed_utf8_sequence_is_rejected_with_its_position) {
  // Each byte string replaces the character X in `<robot name="aXb">` (line 2, column 15); the
  // expected verdicts follow RFC 3629 (section 4's table of well-formed byte sequences).
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"\x80", "0x80 is a UTF-8 continuation byte without a lead byte"},
      {"\xC0\xAF", "0xC0 never occurs in UTF-8"},
      {"\xF8\x88\x80\x80\x80", "0xF8 never occurs in UTF-8"},
      {"\xFF", "0xFF never occurs in UTF-8"},
      {"\xE9\x41", "the 3-byte UTF-8 sequence that starts with byte 0xE9 is cut off: byte 0x41"},
      {"\xE0\x80\xAF", "overlong UTF-8 encoding of U+002F"},
      {"\xF0\x8F\xBF\xBF", "overlong UTF-8 encoding of U+FFFF"},
      {"\xED\xA0\x80", "U+D800 is a UTF-16 surrogate"},
      {"\xF4\x90\x80\x80", "U+110000 lies beyond U+10FFFF"},
      {std::string(1, '\0'), "NUL byte"},
      {"\x01", "character U+0001 is not allowed in XML 1.0"},
      {"\x1B", "character U+001B is not allowed in XML 1.0"},
      {"\xEF\xBF\xBE", "character U+FFFE is not allowed in XML 1.0"},
  };
  for (const auto& [bytes, verdict] : cases) {
    const std::string xml = model_with(inertial(kOrigin, kMass, kInertia));
    const std::string bad =
        "<?xml version=\"1.0\"?>\n<robot name=\"a" + bytes + "b\">" + xml.substr(xml.find('\n', 30));
    check_rejected(bad, {"bad.urdf:2:15:", verdict});
  }
  // Columns count characters, not bytes: two 2-byte characters before the bad byte.
  check_rejected("<?xml version=\"1.0\"?>\n<!-- \xC3\xA9\xC3\xA9 \x01 -->", {"bad.urdf:2:9:", "U+0001"});
}

BOOST_AUTO_TEST_CASE(well_formed_utf8_loads) {
  // A byte-order mark, 2-, 3- and 4-byte characters (U+00E9, U+20AC, U+1F600) in comments and names,
  // tab, CR LF: all XML 1.0 characters, so the model loads as without them.
  const std::string xml = model_with(inertial(kOrigin, kMass, kInertia));
  const std::string decorated = "\xEF\xBB\xBF" + xml.substr(0, xml.find("<robot")) +
                                "<!-- caf\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80\t-->\r\n" +
                                xml.substr(xml.find("<robot"));
  const RobotModel m = parse_robot_model(decorated, "good.urdf");
  BOOST_TEST(m.platforms()[0].mass == 0.05);
  BOOST_TEST(m.rods().size() == 1u);
}
