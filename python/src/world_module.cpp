// The `servoloop._servoloop` extension module: World (python_world.hpp) for
// Python, values crossing as JSON (numbers, strings, lists, dicts) and joint
// states as numpy arrays. The GIL is released while a World steps or resets,
// so Worlds in several Python threads run in parallel.
#include <cstdint>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "python_world.hpp"
#include "servoloop/core/errors.hpp"

namespace py = pybind11;

namespace servoloop::python {
namespace {

// Python value -> JSON through Python's own json module (exact for floats).
nlohmann::json toJson(const py::handle& value) {
  const py::object dumps = py::module_::import("json").attr("dumps");
  return nlohmann::json::parse(dumps(value, py::arg("allow_nan") = false).cast<std::string>());
}

// JSON -> Python objects directly (no text in between): numbers keep their
// type (a NaN stays a float NaN), strings are decoded as UTF-8 with any
// invalid byte replaced.
py::object fromJson(const nlohmann::json& value) {
  using Type = nlohmann::json::value_t;
  switch (value.type()) {
    case Type::boolean:
      return py::bool_(value.get<bool>());
    case Type::number_integer:
      return py::int_(value.get<std::int64_t>());
    case Type::number_unsigned:
      return py::int_(value.get<std::uint64_t>());
    case Type::number_float:
      return py::float_(value.get<double>());
    case Type::string: {
      const std::string& text = value.get_ref<const std::string&>();
      return py::reinterpret_steal<py::object>(
          PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "replace"));
    }
    case Type::array: {
      py::list list(value.size());
      std::size_t index = 0;
      for (const nlohmann::json& item : value) list[index++] = fromJson(item);
      return list;
    }
    case Type::object: {
      py::dict dict;
      for (const auto& [key, item] : value.items()) {
        dict[py::reinterpret_steal<py::object>(
            PyUnicode_DecodeUTF8(key.data(), static_cast<Py_ssize_t>(key.size()), "replace"))] = fromJson(item);
      }
      return dict;
    }
    default:  // null, and nothing else a message holds
      return py::none();
  }
}

py::array_t<double> array(const std::vector<double>& values) {
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

}  // namespace
}  // namespace servoloop::python

PYBIND11_MODULE(_servoloop, module) {
  using servoloop::python::World;
  using servoloop::python::WorldOptions;
  module.doc() = "servoloop: ros_control-style robot control, simulated in-process";

  // servoloop.Error (a RuntimeError) and servoloop.ConfigError (an Error),
  // with the command line's messages.
  static py::exception<servoloop::Error> error(module, "Error", PyExc_RuntimeError);
  static py::exception<servoloop::ConfigError> config_error(module, "ConfigError", error.ptr());
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const servoloop::ConfigError& e) {
      config_error(e.what());
    } catch (const servoloop::Error& e) {
      error(e.what());
    }
  });

  py::class_<World>(module, "World", R"(A world of robots from a launch file, run in this process.

It starts paused at time 0 with the launch file's controllers running; step()
and step_cycles() advance it, reset() brings it back to its start.)")
      .def(py::init([](const std::string& launch_file, std::optional<std::string> backend, py::object params,
                       const std::string& log_level) {
             WorldOptions options;
             options.backend = std::move(backend);
             options.log_level = log_level;
             if (!params.is_none()) {
               for (const auto& [name, value] : params.cast<py::dict>()) {
                 options.params[py::str(name).cast<std::string>()] =
                     servoloop::python::toJson(value).dump();
               }
             }
             py::gil_scoped_release release;
             return std::make_unique<World>(launch_file, options);
           }),
           py::arg("launch_file"), py::arg("backend") = py::none(), py::arg("params") = py::none(),
           py::arg("log_level") = "warn",
           "launch_file: a servoloop launch file (.launch.yaml or ROS .launch); backend: bullet, mujoco or mock "
           "instead of the file's; params: {full parameter name: value} set after the launch file's parameter "
           "files, before the controllers load; log_level: the node's log level (trace .. off)")
      .def("reset", &World::reset, py::call_guard<py::gil_scoped_release>(),
           "Every robot and object back at its start, controllers restarted (reloaded when set_param changed "
           "theirs), time 0")
      .def("step", &World::step, py::arg("seconds"), py::call_guard<py::gil_scoped_release>(),
           "Run `seconds` of simulated time (whole physics steps); returns the steps run")
      .def("step_cycles", &World::stepCycles, py::arg("n"), py::call_guard<py::gil_scoped_release>(),
           "Run n physics steps (with the control cycles on them); returns the steps run")
      .def_property_readonly("time", &World::time, "Simulated time, s")
      .def_property_readonly("time_step", &World::timeStep, "One physics step, s")
      .def_property_readonly("namespaces", &World::namespaces, "The robots' namespaces")
      .def_property_readonly("topics", &World::topics, "Every robot's topics: {name: message type}")
      .def(
          "publish",
          [](World& world, const std::string& topic, const py::object& value, const std::string& type) {
            world.publish(topic, servoloop::python::toJson(value), type);
          },
          py::arg("topic"), py::arg("value"), py::arg("type") = "",
          "Publish on a robot's topic: a number (std_msgs/Float64), a list (Float64MultiArray) or a dict of the "
          "message's fields; type as `servoloop topic pub` takes it, default the topic's own")
      .def(
          "subscribe",
          [](World& world, const std::string& topic) { return servoloop::python::fromJson(world.subscribe(topic)); },
          py::arg("topic"),
          "The messages on `topic` since the last call, as dicts {stamp, type, msg}; the first call subscribes")
      .def(
          "joint_state",
          [](const World& world, const std::string& ns) {
            const servoloop::python::JointStates states = world.jointState(ns);
            py::dict result;
            result["name"] = states.name;
            result["position"] = servoloop::python::array(states.position);
            result["velocity"] = servoloop::python::array(states.velocity);
            result["effort"] = servoloop::python::array(states.effort);
            return result;
          },
          py::arg("ns") = "",
          "A robot's joints: {name, position, velocity, effort} (numpy arrays); ns may be left out when the "
          "world has one robot")
      .def(
          "model_state",
          [](const World& world, const std::string& name) {
            return servoloop::python::fromJson(world.modelState(name));
          },
          py::arg("name"), "A model's pose and twist in the world frame (Gazebo's get_model_state)")
      .def(
          "set_model_state",
          [](World& world, const std::string& name, const py::object& pose, const py::object& twist) {
            nlohmann::json request = {{"op", "model.set_state"}, {"model", name}};
            if (!pose.is_none()) request["pose"] = servoloop::python::toJson(pose);
            if (!twist.is_none()) request["twist"] = servoloop::python::toJson(twist);
            nlohmann::json state;
            {
              py::gil_scoped_release release;
              state = world.setModelState(request);
            }
            return servoloop::python::fromJson(state);
          },
          py::arg("name"), py::arg("pose") = py::none(), py::arg("twist") = py::none(),
          "Teleport a floating model and/or set its velocity (Gazebo's set_model_state): pose {position, "
          "orientation} and twist {linear, angular} as model_state gives them, world frame; what is not given "
          "stays. Returns the new state")
      .def(
          "set_param",
          [](World& world, const std::string& name, const py::object& value) {
            world.setParam(name, servoloop::python::toJson(value).dump());
          },
          py::arg("name"), py::arg("value"),
          "Set a parameter; a controller's takes effect at the next reset (the controller is reloaded)")
      .def(
          "get_param",
          [](const World& world, const std::string& name) { return servoloop::python::fromJson(world.getParam(name)); },
          py::arg("name"), "A parameter's value, or a namespace's as a dict")
      .def("close", &World::close, py::call_guard<py::gil_scoped_release>(), "Stop the world")
      .def("__enter__", [](World& world) -> World& { return world; })
      .def("__exit__", [](World& world, const py::args&) {
        py::gil_scoped_release release;
        world.close();
      });
}
