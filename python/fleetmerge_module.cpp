// fleetmerge._fleetmerge: the public C++ API (api/include/fleetmerge/fleetmerge.hpp) for Python,
// with numpy arrays for map cells. python/fleetmerge/__init__.py adds the Pythonic layer (paths
// or Maps, report as a dict, options as keywords).
//
// Arguments are checked here, before any C++ runs on them: an array of the wrong dtype, shape or
// memory layout, a non-finite resolution or origin is a ValueError saying what was expected,
// never a silent conversion and never a crash. The GIL is released while pairs and merges run.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "fleetmerge/fleetmerge.hpp"

namespace py = pybind11;

namespace {

[[noreturn]] void ValueError(const std::string& what) { throw py::value_error(what); }

// One number of an argument; `what` names it in the message: "origin[1]", "initial_pose_sigma[0]".
double NumberFrom(const py::handle& value, const std::string& what) {
  try {
    return value.cast<double>();
  } catch (const py::cast_error&) {
    ValueError(what + " must be a number");
  }
}

// `what` names the argument in messages: "origin", "pose".
fleetmerge::Pose2D PoseFrom(const py::handle& pose, const std::string& what) {
  if (!py::isinstance<py::sequence>(pose) || py::isinstance<py::str>(pose)) {
    ValueError(what + " must be a sequence (x, y, yaw) of 3 finite numbers (metres, radians)");
  }
  const auto seq = py::reinterpret_borrow<py::sequence>(pose);
  if (seq.size() != 3) {
    ValueError(what + " must be (x, y, yaw): 3 numbers, got " + std::to_string(seq.size()));
  }
  double v[3];
  for (int k = 0; k < 3; ++k) {
    v[k] = NumberFrom(seq[k], what + "[" + std::to_string(k) + "]");
    if (!std::isfinite(v[k])) ValueError(what + "[" + std::to_string(k) + "] must be finite");
  }
  return {v[0], v[1], v[2]};
}

fleetmerge::Pose2D OriginFrom(const py::handle& origin) { return PoseFrom(origin, "origin"); }

// initial_pose: None or (x, y, yaw); initial_pose_sigma: None (the defaults) or (metres, radians),
// only with an initial_pose.
void SetInitialPose(fleetmerge::Map& map, const py::object& pose, const py::object& sigma) {
  if (pose.is_none()) {
    if (!sigma.is_none()) {
      ValueError(
          "initial_pose_sigma is the uncertainty of an initial_pose; give initial_pose "
          "(x, y, yaw) too");
    }
    map.clear_initial_pose();
    return;
  }
  const fleetmerge::Pose2D p = PoseFrom(pose, "initial_pose");
  double s[2] = {fleetmerge::Map::kDefaultInitialPoseSigmaM,
                 fleetmerge::Map::kDefaultInitialPoseSigmaRad};
  if (!sigma.is_none()) {
    if (!py::isinstance<py::sequence>(sigma) || py::isinstance<py::str>(sigma) ||
        py::len(sigma) != 2) {
      ValueError("initial_pose_sigma must be (metres, radians): 2 finite numbers > 0");
    }
    const auto seq = py::reinterpret_borrow<py::sequence>(sigma);
    for (int k = 0; k < 2; ++k) {
      s[k] = NumberFrom(seq[k], "initial_pose_sigma[" + std::to_string(k) + "]");
      if (!std::isfinite(s[k]) || !(s[k] > 0.0)) {
        ValueError("initial_pose_sigma[" + std::to_string(k) + "] must be finite and > 0, got " +
                   std::to_string(s[k]));
      }
    }
  }
  map.set_initial_pose(p, s[0], s[1]);
}

// A numpy int8 array, height x width, C-contiguous: OccupancyGrid's data reshaped.
fleetmerge::Map MapFromArray(const py::handle& data, const py::handle& resolution,
                             const py::handle& origin, const std::string& name) {
  if (!py::isinstance<py::array>(data)) {
    ValueError(
        "data must be a numpy array of int8 (height x width, nav_msgs/OccupancyGrid "
        "values), got " +
        std::string(py::str(py::type::of(data))));
  }
  const auto array = py::reinterpret_borrow<py::array>(data);
  const py::dtype dtype = array.dtype();
  if (dtype.kind() != 'i' || dtype.itemsize() != 1) {
    ValueError("data must have dtype int8 (OccupancyGrid cells: -1 unknown, 0..100), got " +
               std::string(py::str(static_cast<const py::handle&>(dtype))) +
               "; convert with numpy.asarray(data, dtype=numpy.int8)");
  }
  if (array.ndim() != 2) {
    ValueError("data must be 2-D (height x width), got " + std::to_string(array.ndim()) +
               " dimension(s); reshape OccupancyGrid data with .reshape(height, width)");
  }
  if (!(array.flags() & py::array::c_style)) {
    ValueError(
        "data must be C-contiguous (row-major, row 0 at the origin); use "
        "numpy.ascontiguousarray(data)");
  }
  double resolution_m = 0.0;
  try {
    resolution_m = resolution.cast<double>();
  } catch (const py::cast_error&) {
    ValueError("resolution must be a number (metres per cell)");
  }
  if (!std::isfinite(resolution_m) || resolution_m <= 0.0) {
    ValueError("resolution must be a finite number > 0 (metres per cell), got " +
               std::string(py::str(resolution)));
  }
  const fleetmerge::Pose2D pose = OriginFrom(origin);
  const auto height = static_cast<std::size_t>(array.shape(0));
  const auto width = static_cast<std::size_t>(array.shape(1));
  if (width == 0 || height == 0) ValueError("data must hold at least one cell");
  std::vector<std::int8_t> cells(width * height);
  std::memcpy(cells.data(), array.data(), cells.size());
  try {
    return fleetmerge::Map(std::move(cells), static_cast<int>(width), static_cast<int>(height),
                           resolution_m, pose, name);
  } catch (const std::invalid_argument& e) {
    ValueError(e.what());
  }
}

py::array_t<std::int8_t> ArrayOf(const fleetmerge::Map& map) {
  py::array_t<std::int8_t> out({map.height(), map.width()});
  std::memcpy(out.mutable_data(), map.data().data(), map.data().size());
  return out;
}

py::tuple TupleOf(const fleetmerge::Pose2D& p) { return py::make_tuple(p.x, p.y, p.yaw); }

// `fixed`: True or False (a numpy bool too), as a job file's `fixed` takes only booleans.
bool FixedFrom(const py::object& fixed) {
  if (!py::isinstance<py::bool_>(fixed) &&
      std::string(py::str(py::type::of(fixed).attr("__name__"))) != "bool_") {
    ValueError("fixed must be True or False, got " + std::string(py::repr(fixed)));
  }
  return fixed.cast<bool>();
}

}  // namespace

PYBIND11_MODULE(_fleetmerge, m) {
  m.doc() = "fleetmerge's C++ library (use the fleetmerge package, not this module)";
  m.attr("__version__") = fleetmerge::Version();

  py::class_<fleetmerge::Map>(
      m, "Map",
      "Map(data, resolution, origin=(0, 0, 0), name='', *, fixed=False, pose=(0, 0, 0),\n"
      "    initial_pose=None, initial_pose_sigma=None)\n\n"
      "An occupancy grid as nav_msgs/OccupancyGrid: data is int8, height x width, -1 unknown,\n"
      "0..100 occupancy, row 0 at the origin; resolution in metres per cell; origin (x, y, yaw)\n"
      "of cell (0, 0)'s outer corner. For merge: fixed=True keeps the map at pose (its frame in\n"
      "the merged frame, exact) and every cell it knows in the merged map; initial_pose (x, y, "
      "yaw) is a known start pose, with\n"
      "initial_pose_sigma (metres, radians; defaults: help(Map.initial_pose_sigma)).")
      .def(py::init([](const py::object& data, const py::object& resolution,
                       const py::object& origin, const std::string& name, const py::object& fixed,
                       const py::object& pose, const py::object& initial_pose,
                       const py::object& initial_pose_sigma) {
             fleetmerge::Map map = MapFromArray(data, resolution, origin, name);
             map.set_fixed(FixedFrom(fixed), PoseFrom(pose, "pose"));
             SetInitialPose(map, initial_pose, initial_pose_sigma);
             return map;
           }),
           py::arg("data"), py::arg("resolution"), py::arg("origin") = py::make_tuple(0, 0, 0),
           py::arg("name") = "", py::kw_only(), py::arg("fixed") = false,
           py::arg("pose") = py::make_tuple(0, 0, 0), py::arg("initial_pose") = py::none(),
           py::arg("initial_pose_sigma") = py::none())
      .def_property_readonly("data", &ArrayOf, "cells, int8, height x width (a copy)")
      .def_property_readonly("resolution", &fleetmerge::Map::resolution)
      .def_property_readonly("origin",
                             [](const fleetmerge::Map& map) { return TupleOf(map.origin()); })
      .def_property_readonly("width", &fleetmerge::Map::width)
      .def_property_readonly("height", &fleetmerge::Map::height)
      .def_property("name", &fleetmerge::Map::name, &fleetmerge::Map::set_name)
      .def_property(
          "fixed", &fleetmerge::Map::fixed,
          [](fleetmerge::Map& map, const py::object& fixed) {
            const bool is_fixed = FixedFrom(fixed);
            map.set_fixed(is_fixed, is_fixed ? map.pose() : fleetmerge::Pose2D{});
          },
          "a fixed (base) map never moves in merge: the merged frame is its frame")
      .def_property(
          "pose", [](const fleetmerge::Map& map) { return TupleOf(map.pose()); },
          [](fleetmerge::Map& map, const py::object& pose) {
            map.set_fixed(map.fixed(), PoseFrom(pose, "pose"));
          },
          "a fixed map's (x, y, yaw): its map frame in the merged frame")
      .def_property(
          "initial_pose",
          [](const fleetmerge::Map& map) -> py::object {
            if (!map.initial_pose()) return py::none();
            return TupleOf(*map.initial_pose());
          },
          [](fleetmerge::Map& map, const py::object& pose) {
            if (pose.is_none()) return map.clear_initial_pose();
            SetInitialPose(
                map, pose,
                py::make_tuple(map.initial_pose_sigma_m(), map.initial_pose_sigma_rad()));
          },
          "a known start pose (x, y, yaw): the map frame in the site (merged) frame, or None")
      .def_property(
          "initial_pose_sigma",
          [](const fleetmerge::Map& map) -> py::object {
            if (!map.initial_pose()) return py::none();  // as initial_pose: no prior, no sigmas
            return py::make_tuple(map.initial_pose_sigma_m(), map.initial_pose_sigma_rad());
          },
          [](fleetmerge::Map& map, const py::object& sigma) {
            if (!map.initial_pose()) {
              ValueError(
                  "initial_pose_sigma is the uncertainty of an initial_pose; set "
                  "initial_pose first");
            }
            SetInitialPose(map, TupleOf(*map.initial_pose()), sigma);
          },
          "the initial pose's (metres, radians) sigmas (default (0.5, 10 deg)), or None without "
          "an initial pose")
      .def("__repr__", [](const fleetmerge::Map& map) {
        return "<fleetmerge.Map '" + map.name() + "' " + std::to_string(map.width()) + "x" +
               std::to_string(map.height()) + " @ " + std::to_string(map.resolution()) + " m>";
      });

  py::class_<fleetmerge::Hypothesis>(m, "Hypothesis")
      .def_readonly("x", &fleetmerge::Hypothesis::x)
      .def_readonly("y", &fleetmerge::Hypothesis::y)
      .def_readonly("yaw", &fleetmerge::Hypothesis::yaw)
      .def_readonly("omega", &fleetmerge::Hypothesis::omega)
      .def_readonly("overlap_cells", &fleetmerge::Hypothesis::overlap_cells)
      .def_readonly("wall_agreement", &fleetmerge::Hypothesis::wall_agreement)
      .def("__repr__", [](const fleetmerge::Hypothesis& h) {
        return "<fleetmerge.Hypothesis x=" + std::to_string(h.x) + " y=" + std::to_string(h.y) +
               " yaw=" + std::to_string(h.yaw) + " omega=" + std::to_string(h.omega) + ">";
      });

  // Also a sequence of its hypotheses (best first): code that reads pair() as a list keeps working.
  py::class_<fleetmerge::PairHypotheses>(m, "PairHypotheses")
      .def_readonly("hypotheses", &fleetmerge::PairHypotheses::hypotheses)
      .def_readonly("margin", &fleetmerge::PairHypotheses::margin)
      .def_readonly("ambiguous", &fleetmerge::PairHypotheses::ambiguous)
      .def("__len__", &fleetmerge::PairHypotheses::size)
      .def("__getitem__",
           [](const fleetmerge::PairHypotheses& p, py::ssize_t k) {
             const auto n = static_cast<py::ssize_t>(p.size());
             if (k < 0) k += n;
             if (k < 0 || k >= n) throw py::index_error("hypothesis index out of range");
             return p.hypotheses[static_cast<std::size_t>(k)];
           })
      .def(
          "__iter__",
          [](const fleetmerge::PairHypotheses& p) {
            return py::make_iterator(p.hypotheses.begin(), p.hypotheses.end());
          },
          py::keep_alive<0, 1>())
      .def("__repr__", [](const fleetmerge::PairHypotheses& p) {
        return "<fleetmerge.PairHypotheses " + std::to_string(p.size()) +
               " hypotheses, margin=" + std::to_string(p.margin) +
               (p.ambiguous ? " ambiguous>" : ">");
      });

  py::class_<fleetmerge::Options>(m, "Options")
      .def(py::init<>())
      .def_readwrite("hypotheses", &fleetmerge::Options::hypotheses)
      .def_readwrite("resolution", &fleetmerge::Options::resolution)
      .def_readwrite("omega_threshold", &fleetmerge::Options::omega_threshold)
      .def_readwrite("min_overlap_cells", &fleetmerge::Options::min_overlap_cells)
      .def_readwrite("min_wall_agreement", &fleetmerge::Options::min_wall_agreement)
      .def_readwrite("min_bridge_wall_agreement", &fleetmerge::Options::min_bridge_wall_agreement)
      .def_readwrite("fusion", &fleetmerge::Options::fusion)
      .def_readwrite("reference", &fleetmerge::Options::reference)
      .def_readwrite("threads", &fleetmerge::Options::threads)
      .def_readwrite("refine", &fleetmerge::Options::refine)
      .def_readwrite("translation", &fleetmerge::Options::translation)
      .def_readwrite("max_map_cells", &fleetmerge::Options::max_map_cells)
      .def_readwrite("octree_band_min", &fleetmerge::Options::octree_band_min)
      .def_readwrite("octree_band_max", &fleetmerge::Options::octree_band_max)
      .def_readwrite("cache_dir", &fleetmerge::Options::cache_dir)
      .def_readwrite("cache_max_mb", &fleetmerge::Options::cache_max_mb)
      // merge(paths, fixed={name: (x, y, yaw)}, initial_poses={name: (x, y, yaw[, m, rad])}):
      // fleetmerge/__init__.py passes each entry here.
      .def("_fix",
           [](fleetmerge::Options& o, const std::string& name, const py::object& pose) {
             o.fixed[name] = PoseFrom(pose, "fixed['" + name + "']");
           })
      .def("_initial_pose",
           [](fleetmerge::Options& o, const std::string& name, const py::object& value) {
             const std::string what = "initial_poses['" + name + "']";
             if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value) ||
                 (py::len(value) != 3 && py::len(value) != 5)) {
               ValueError(what + " must be (x, y, yaw) or (x, y, yaw, metres, radians)");
             }
             const auto seq = py::reinterpret_borrow<py::sequence>(value);
             fleetmerge::InitialPose prior;
             prior.pose = PoseFrom(py::make_tuple(seq[0], seq[1], seq[2]), what);
             if (seq.size() == 5) {
               // Checked (finite, > 0) with the pose by MergeFiles, as Map.initial_pose_sigma.
               prior.sigma_m = NumberFrom(seq[3], what + "[3] (metres)");
               prior.sigma_rad = NumberFrom(seq[4], what + "[4] (radians)");
             }
             o.initial_poses[name] = prior;
           });

  py::class_<fleetmerge::MergeResult>(m, "MergeResult")
      .def_readonly("report_json", &fleetmerge::MergeResult::report_json)
      .def_property_readonly("merged", [](const fleetmerge::MergeResult& r) {
        std::vector<fleetmerge::Map> merged;
        for (const auto& c : r.components) {
          if (c.merged) merged.push_back(*c.merged);
        }
        return merged;
      });

  // Errors: std::invalid_argument -> ValueError, std::runtime_error (the command's messages)
  // -> RuntimeError, by pybind11's standard translation.
  m.def("load_map", &fleetmerge::LoadMap, py::arg("path"),
        py::call_guard<py::gil_scoped_release>());
  m.def("save_map", &fleetmerge::SaveMap, py::arg("map"), py::arg("path"),
        py::call_guard<py::gil_scoped_release>());
  m.def("pair", &fleetmerge::Pair, py::arg("a"), py::arg("b"), py::arg("options"),
        py::call_guard<py::gil_scoped_release>());
  m.def("merge", &fleetmerge::Merge, py::arg("maps"), py::arg("options"), py::arg("out"),
        py::call_guard<py::gil_scoped_release>());
  m.def("merge_files", &fleetmerge::MergeFiles, py::arg("paths"), py::arg("options"),
        py::arg("out"), py::call_guard<py::gil_scoped_release>());
}
