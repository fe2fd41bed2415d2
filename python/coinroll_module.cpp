// coinroll._coinroll: the C++ API (include/coinroll/coinroll.h) for the Python package beside it
// (python/coinroll/__init__.py), which turns its tuples into tables and documents the calls.
// Every call that runs a simulation or draws does so with the GIL released. Drawing and sweeping
// run on a thread of their own while the calling thread keeps running Python's signal handlers:
// Ctrl-C then stops the work through the library's cancel flag, and no signal handler of ours is
// ever installed.

#include <coinroll/coinroll.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <atomic>
#include <chrono>
#include <exception>
#include <future>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace py = pybind11;
using namespace pybind11::literals;

namespace {

// How long a Ctrl-C may wait to be noticed while the work runs.
constexpr std::chrono::milliseconds kSignalPollInterval{50};

// Runs work(cancel) on a thread of its own, the GIL released (a thread's start, tens of
// microseconds, is nothing beside a picture, a clip or a sweep). When a Python signal handler raises
// (Ctrl-C's KeyboardInterrupt, or any exception a user's handler raises), the work is cancelled,
// waited for, and that exception is raised in its place; Python threads run meanwhile.
// Signal handlers run only on Python's main thread: a call from another thread is not
// interruptible, as a time.sleep there is not.
template <class Work>
auto interruptible(Work work) -> decltype(work(nullptr)) {
  std::atomic<bool> cancel{false};
  std::packaged_task<decltype(work(nullptr))()> task([&] { return work(&cancel); });
  auto result = task.get_future();
  bool raised = false;
  {
    const py::gil_scoped_release released;
    const std::jthread worker(std::move(task));  // joined before the GIL is taken back
    while (result.wait_for(kSignalPollInterval) != std::future_status::ready) {
      const py::gil_scoped_acquire held;
      if (PyErr_CheckSignals() != 0) {
        raised = true;
        cancel = true;
        break;
      }
    }
  }
  if (raised) throw py::error_already_set();
  return result.get();
}

// A numpy array that takes over `values`' buffer: the vector lives on in the array's base
// capsule, so the numbers are never copied.
template <class T>
py::array_t<T> arrayOwning(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto owner = std::make_unique<std::vector<T>>(std::move(values));
  T* data = owner->data();
  const py::capsule base(owner.get(), [](void* vector) { delete static_cast<std::vector<T>*>(vector); });
  owner.release();
  return py::array_t<T>(std::move(shape), data, base);
}

// A table's column, read-only as the Table it goes into is documented to be: the run's numbers,
// which an edit would silently make disagree with the CSV of the same run.
py::array_t<double> readOnlyColumn(std::vector<double>&& values) {
  const auto rows = static_cast<py::ssize_t>(values.size());
  py::array_t<double> column = arrayOwning(std::move(values), {rows});
  column.attr("setflags")("write"_a = false);
  return column;
}

py::list arraysOwning(std::vector<std::vector<double>>&& columns) {
  py::list arrays;
  for (std::vector<double>& column : columns) arrays.append(readOnlyColumn(std::move(column)));
  return arrays;
}

// On the calling thread, the GIL released, and so not cut short by Ctrl-C (its KeyboardInterrupt is
// raised when the run returns): handed to a thread of its own, the run waited for two wake-ups, which on
// the loaded 2-core machine cost 11-30 % of a 10 s toy run (bench/python_overhead.py, whose budget
// is 5 %). The examples' runs take at most 1.2 s.
py::tuple simulate(const coinroll::Scene& scene, double sampleDt) {
  coinroll::Columns columns = [&] {
    const py::gil_scoped_release released;
    return coinroll::simulate(scene, sampleDt);
  }();
  return py::make_tuple(columns.names, arraysOwning(std::move(columns.values)), columns.end.event, columns.end.time,
                        columns.end.description);
}

py::array_t<std::uint8_t> still(const coinroll::Scene& scene, double time) {
  coinroll::Image image =
      interruptible([&](const std::atomic<bool>* cancel) { return coinroll::renderStill(scene, time, cancel); });
  return arrayOwning(std::move(image.rgba), {image.height, image.width, 4});
}

void render(const coinroll::Scene& scene, const std::filesystem::path& output) {
  interruptible([&](const std::atomic<bool>* cancel) { coinroll::renderVideo(scene, output, cancel); });
}

py::dict steady(const coinroll::Scene& scene) {
  const coinroll::SteadyState s = coinroll::steady(scene);
  const py::dict initial("theta"_a = s.theta, "phi"_a = s.phi, "psi"_a = s.psi, "omega_X"_a = s.omega_X,
                         "omega_Y"_a = s.omega_Y, "omega_Z"_a = s.omega_Z, "x"_a = s.x, "z"_a = s.z);
  return py::dict("mass"_a = s.mass, "radius"_a = s.radius, "gravity"_a = s.gravity, "inertia_X"_a = s.inertiaX,
                  "inertia_Z"_a = s.inertiaZ, "thickness"_a = s.thickness, "edge_radius"_a = s.edgeRadius,
                  "natural_rate"_a = s.naturalRate, "critical_spin"_a = s.criticalSpin, "initial"_a = initial,
                  "precession_rate"_a = s.precessionRate, "spin_rate"_a = s.spinRate,
                  "centre_of_mass_radius"_a = s.centreOfMassRadius, "contact_radius"_a = s.contactRadius,
                  "normal_force"_a = s.normalForce, "friction_force"_a = s.frictionForce, "K"_a = s.stiffness,
                  "stability"_a = s.stability);
}

py::tuple sweep(const coinroll::Scene& scene, const std::vector<std::string>& axes, int threads) {
  coinroll::SweepTable table =
      interruptible([&](const std::atomic<bool>* cancel) { return coinroll::sweep(scene, axes, threads, cancel); });
  return py::make_tuple(table.columns.names, arraysOwning(std::move(table.columns.values)), table.end, table.gridPoints,
                        table.digest);
}

// The Python keyword of each argument the C++ API names in an ArgumentError, so a message names
// what a Python user types (sample_dt, not sampleDt).
std::string pythonSpelling(const std::string& argument) {
  if (argument == "sampleDt") return "sample_dt";
  if (argument == "time") return "t";
  if (argument == "output") return "path";
  return argument;
}

}  // namespace

PYBIND11_MODULE(_coinroll, module) {
  module.doc() = "coinroll's C++ API; use the coinroll package, which documents it";
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const coinroll::ArgumentError& e) {
      PyErr_SetString(PyExc_ValueError, e.naming(pythonSpelling(e.argument())).c_str());
    }
  });
  module.def("version", &coinroll::version);

  py::class_<coinroll::Scene>(module, "Scene")
      .def_static("from_file", &coinroll::Scene::fromFile, "file"_a, "overrides"_a)
      .def_static("from_json", &coinroll::Scene::fromJson, "json"_a, "overrides"_a)
      .def_static("built_in_default", &coinroll::Scene::builtInDefault, "overrides"_a)
      .def_property_readonly("name", &coinroll::Scene::name)
      .def_property_readonly("duration", &coinroll::Scene::duration);

  module.def("simulate", &simulate, "scene"_a, "sample_dt"_a);
  module.def("still", &still, "scene"_a, "t"_a);
  module.def("render", &render, "scene"_a, "path"_a);
  module.def("steady", &steady, "scene"_a);
  module.def("sweep", &sweep, "scene"_a, "axes"_a, "threads"_a);
}
