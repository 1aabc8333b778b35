#include "servoloop/sim_common/contact_friction.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>

#include <tinyxml2.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/core/logging.hpp"

namespace servoloop::sim_common {
namespace {

// The coefficient in <tag> under `gazebo`, if the element is there.
std::optional<double> readCoefficient(const tinyxml2::XMLElement& gazebo, const char* tag, const std::string& where) {
  const tinyxml2::XMLElement* element = gazebo.FirstChildElement(tag);
  if (element == nullptr) return std::nullopt;
  // <mu1>0.8</mu1>, or the older form Gazebo also reads, <mu1 value="0.8"/>.
  const char* text = element->GetText();
  if (text == nullptr) text = element->Attribute("value");
  const std::string written = text == nullptr ? std::string() : std::string(text);
  const std::size_t first = written.find_first_not_of(" \t\r\n");
  const std::size_t last = written.find_last_not_of(" \t\r\n");
  const std::string trimmed = first == std::string::npos ? std::string() : written.substr(first, last - first + 1);
  char* end = nullptr;
  const double value = trimmed.empty() ? std::nan("") : std::strtod(trimmed.c_str(), &end);
  if (trimmed.empty() || end != trimmed.c_str() + trimmed.size() || !std::isfinite(value) || value < 0.0) {
    throw ConfigError(where + " <" + tag + "> '" + written +
                      "': the Gazebo friction coefficient must be a finite number >= 0 (1 when not given); write "
                      "e.g. <" + tag + ">1.0</" + tag + ">");
  }
  return value;
}

}  // namespace

std::map<std::string, double> urdfLinkFriction(const std::string& urdf_xml, const urdf::ModelInterface& model,
                                               const std::string& source_name) {
  std::map<std::string, double> friction;
  tinyxml2::XMLDocument document;
  if (document.Parse(urdf_xml.c_str(), urdf_xml.size()) != tinyxml2::XML_SUCCESS) return friction;
  const tinyxml2::XMLElement* robot = document.RootElement();
  if (robot == nullptr) return friction;
  for (auto* gazebo = robot->FirstChildElement("gazebo"); gazebo != nullptr;
       gazebo = gazebo->NextSiblingElement("gazebo")) {
    const char* reference = gazebo->Attribute("reference");
    if (reference == nullptr) continue;  // the model's settings, not a link's
    const std::string link = reference;
    const std::string where = source_name + ": <gazebo reference=\"" + link + "\">";
    const std::optional<double> mu1 = readCoefficient(*gazebo, "mu1", where);
    const std::optional<double> mu2 = readCoefficient(*gazebo, "mu2", where);
    if (!mu1 && !mu2) continue;
    if (!model.getLink(link)) {
      logger().warn("{} sets <mu1>/<mu2> but the robot has no link '{}'; they are ignored (name a link)", where, link);
      continue;
    }
    const double first = mu1.value_or(kDefaultContactFriction);
    const double second = mu2.value_or(kDefaultContactFriction);
    const double mu = std::min(first, second);
    if (first != second) {
      logger().info("{}: mu1 {} and mu2 {} differ; contacts are isotropic here, so link '{}' has mu {}", where,
                    first, second, link, mu);
    }
    friction[link] = mu;  // a later <gazebo> block for the same link wins, as in Gazebo
  }
  return friction;
}

double linkFriction(const std::map<std::string, double>& friction, const std::string& link) {
  const auto it = friction.find(link);
  return it == friction.end() ? kDefaultContactFriction : it->second;
}

}  // namespace servoloop::sim_common
