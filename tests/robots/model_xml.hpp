#pragma once
// XML builders of the robot-model tests: a valid one-rod model whose malformed variants change one piece,
// and the check that parsing such a variant throws an InputError naming what is wrong.
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "pcr/core/error.hpp"
#include "pcr/robots/urdf_loader.hpp"

namespace pcr::test {

struct RodXml {
  std::string name = "r0";
  std::string start = R"(<start link="base" xyz="0 0 0" rpy="0 0 0" coupling="clamped"/>)";
  std::string end = R"(<end link="platform" xyz="0 0 0" rpy="0 0 0" coupling="clamped"/>)";
  std::string material = R"(<material youngs_modulus="200e9" shear_modulus="80e9" density="8000"/>)";
  std::string section = R"(<section type="circle" radius="0.001"/>)";
  std::string length = R"(<length value="0.3"/>)";
  std::string extra;
  std::string str() const {
    return "<pcr_rod name=\"" + name + "\">" + start + end + material + section + length + extra +
           "</pcr_rod>\n";
  }
};

inline const std::string kPlatformTree = R"(<link name="base"/><link name="platform"/>
<joint name="float" type="floating"><parent link="base"/><child link="platform"/>
<origin xyz="0 0 0.3" rpy="0 0 0"/></joint>
)";

inline std::string robot(const std::string& body, const std::string& tree = kPlatformTree) {
  return "<?xml version=\"1.0\"?>\n<robot name=\"test\">\n" + tree + body + "</robot>\n";
}

// Asserts that parsing throws InputError whose message contains every part.
inline void check_rejected(const std::string& xml, const std::vector<std::string>& parts) {
  try {
    parse_robot_model(xml, "bad.urdf");
    BOOST_ERROR("no InputError for a model that should contain: " << parts.front() << " ...");
  } catch (const InputError& e) {
    const std::string message = e.what();
    BOOST_TEST_MESSAGE(message);
    for (const std::string& part : parts) {
      BOOST_TEST(message.find(part) != std::string::npos,
                 "message \"" << message << "\" lacks \"" << part << "\"");
    }
  }
}

}  // namespace pcr::test
