#include "scene_builder.hpp"

#include <map>

#include <tinyxml2.h>
#include <urdf_model/model.h>

#include "servoloop/core/errors.hpp"
#include "servoloop/description/robot_model.hpp"

namespace servoloop::view {

using nlohmann::json;

namespace {

json origin(const urdf::Pose& pose) {
  double roll = 0, pitch = 0, yaw = 0;
  pose.rotation.getRPY(roll, pitch, yaw);
  return {{"xyz", {pose.position.x, pose.position.y, pose.position.z}}, {"rpy", {roll, pitch, yaw}}};
}

std::string meshFormat(const std::string& filename) {
  std::string extension = std::filesystem::path(filename).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".stl") return "stl";
  if (extension == ".dae") return "dae";
  if (extension == ".obj") return "obj";
  return "other";
}

json geometry(const urdf::Geometry& shape, const std::string& link, StaticFiles& files,
              std::vector<std::string>& warnings, const std::string& model) {
  switch (shape.type) {
    case urdf::Geometry::BOX: {
      const auto& box = static_cast<const urdf::Box&>(shape);
      return {{"type", "box"}, {"size", {box.dim.x, box.dim.y, box.dim.z}}};
    }
    case urdf::Geometry::CYLINDER: {
      const auto& cylinder = static_cast<const urdf::Cylinder&>(shape);
      return {{"type", "cylinder"}, {"radius", cylinder.radius}, {"length", cylinder.length}};
    }
    case urdf::Geometry::SPHERE:
      return {{"type", "sphere"}, {"radius", static_cast<const urdf::Sphere&>(shape).radius}};
    case urdf::Geometry::MESH: {
      const auto& mesh = static_cast<const urdf::Mesh&>(shape);
      std::string url = files.meshUrl(mesh.filename);
      if (url.empty()) {
        warnings.push_back("model '" + model + "', link '" + link + "': mesh '" + mesh.filename +
                           "' is not there; the link is drawn from its collision shapes");
        url = "/missing/" + std::filesystem::path(mesh.filename).filename().string();
      }
      return {{"type", "mesh"},
              {"url", url},
              {"format", meshFormat(mesh.filename)},
              {"scale", {mesh.scale.x, mesh.scale.y, mesh.scale.z}}};
    }
  }
  return nullptr;
}

// <gazebo reference="LINK"><material>Gazebo/...</material>: the colour
// Gazebo draws a link in when its visuals name no URDF material.
std::map<std::string, std::vector<double>> gazeboColors(const std::string& urdf) {
  std::map<std::string, std::vector<double>> colors;
  tinyxml2::XMLDocument document;
  if (document.Parse(urdf.c_str(), urdf.size()) != tinyxml2::XML_SUCCESS) return colors;
  const tinyxml2::XMLElement* robot = document.FirstChildElement("robot");
  if (robot == nullptr) return colors;
  for (const auto* gazebo = robot->FirstChildElement("gazebo"); gazebo != nullptr;
       gazebo = gazebo->NextSiblingElement("gazebo")) {
    const char* reference = gazebo->Attribute("reference");
    const tinyxml2::XMLElement* material = gazebo->FirstChildElement("material");
    if (reference == nullptr || material == nullptr || material->GetText() == nullptr) continue;
    std::vector<double> color = gazeboMaterialColor(material->GetText());
    if (!color.empty()) colors[reference] = std::move(color);
  }
  return colors;
}

json visualJson(const urdf::Pose& pose, const urdf::Geometry& shape, const urdf::Material* material,
                const std::vector<double>* fallback_color, const std::string& link, StaticFiles& files,
                std::vector<std::string>& warnings, const std::string& model) {
  json color = nullptr;
  if (material != nullptr && material->texture_filename.empty()) {
    color = {material->color.r, material->color.g, material->color.b, material->color.a};
  } else if (fallback_color != nullptr) {
    color = *fallback_color;
  }
  return {{"origin", origin(pose)}, {"geometry", geometry(shape, link, files, warnings, model)}, {"color", color}};
}

}  // namespace

std::vector<double> gazeboMaterialColor(const std::string& name) {
  // The ambient/diffuse colours of Gazebo's gazebo.material script.
  static const std::map<std::string, std::vector<double>> kColors = {
      {"Gazebo/Grey", {0.7, 0.7, 0.7, 1}},          {"Gazebo/DarkGrey", {0.175, 0.175, 0.175, 1}},
      {"Gazebo/LightGrey", {0.9, 0.9, 0.9, 1}},     {"Gazebo/White", {1, 1, 1, 1}},
      {"Gazebo/Black", {0, 0, 0, 1}},               {"Gazebo/Red", {1, 0, 0, 1}},
      {"Gazebo/Green", {0, 1, 0, 1}},               {"Gazebo/Blue", {0, 0, 1, 1}},
      {"Gazebo/Yellow", {1, 1, 0, 1}},              {"Gazebo/Orange", {1, 0.5088, 0.0468, 1}},
      {"Gazebo/Purple", {1, 0, 1, 1}},              {"Gazebo/Turquoise", {0, 1, 1, 1}},
      {"Gazebo/Gold", {0.8, 0.64, 0, 1}},           {"Gazebo/Indigo", {0.33, 0, 0.5, 1}},
      {"Gazebo/SkyBlue", {0.53, 0.81, 0.92, 1}},    {"Gazebo/Wood", {0.7, 0.5, 0.3, 1}},
      {"Gazebo/ZincYellow", {0.9725, 0.9529, 0.2078, 1}}, {"Gazebo/RedBright", {0.87, 0.26, 0.07, 1}},
  };
  const auto it = kColors.find(name);
  return it == kColors.end() ? std::vector<double>{} : it->second;
}

json buildScene(const std::vector<SceneModel>& models, bool ground_plane, StaticFiles& files,
                std::vector<std::string>& warnings) {
  json out_models = json::array();
  for (const SceneModel& model : models) {
    std::shared_ptr<const urdf::ModelInterface> urdf;
    try {
      urdf = parseRobotModel(model.urdf, model.path);
    } catch (const std::exception& error) {
      warnings.push_back("model '" + model.ns + "' is not shown: " + error.what());
      continue;
    }
    const std::map<std::string, std::vector<double>> gazebo = gazeboColors(model.urdf);
    json links = json::array();
    for (const auto& [name, link] : urdf->links_) {
      const auto gazebo_color = gazebo.find(name);
      const std::vector<double>* fallback = gazebo_color == gazebo.end() ? nullptr : &gazebo_color->second;
      json visuals = json::array();
      for (const auto& visual : link->visual_array) {
        if (!visual || !visual->geometry) continue;
        visuals.push_back(
            visualJson(visual->origin, *visual->geometry, visual->material.get(), fallback, name, files, warnings, model.ns));
      }
      json collisions = json::array();
      for (const auto& collision : link->collision_array) {
        if (!collision || !collision->geometry) continue;
        collisions.push_back(
            visualJson(collision->origin, *collision->geometry, nullptr, nullptr, name, files, warnings, model.ns));
      }
      links.push_back({{"name", name}, {"visuals", std::move(visuals)}, {"collisions", std::move(collisions)}});
    }
    json joints = json::array();
    for (const auto& [name, joint] : urdf->joints_) {
      joints.push_back({{"name", name},
                        {"type", jointTypeName(joint->type)},
                        {"parent", joint->parent_link_name},
                        {"child", joint->child_link_name},
                        {"origin", origin(joint->parent_to_joint_origin_transform)},
                        {"axis", {joint->axis.x, joint->axis.y, joint->axis.z}}});
    }
    out_models.push_back({{"name", model.name},
                          {"ns", model.ns},
                          {"root", urdf->getRoot() ? urdf->getRoot()->name : std::string()},
                          {"joint_names", model.joint_names},
                          {"links", std::move(links)},
                          {"joints", std::move(joints)}});
  }
  return {{"type", "scene"}, {"ground_plane", ground_plane}, {"models", std::move(out_models)}};
}

}  // namespace servoloop::view
