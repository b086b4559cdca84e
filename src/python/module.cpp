// The Python API (docs/python.md): pcsim's scenes, runs, statics and modes
// from Python, on the run pipeline (simulation/run.hpp) that `pcsim run`
// uses. Importing the module starts PETSc/SLEPc (on MPI_COMM_WORLD: with
// mpi4py imported first, under mpirun, every rank runs the same calls).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <slepcsys.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "pcsim/core/blas_kernels.hpp"
#include "pcsim/core/error.hpp"
#include "pcsim/core/vec_root.hpp"
#include "pcsim/core/version.hpp"
#include "pcsim/output/output_dir.hpp"
#include "pcsim/output/provenance.hpp"
#include "pcsim/output/run_results.hpp"
#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/run_scene.hpp"
#include "pcsim/simulation/accuracy_pilot.hpp"
#include "pcsim/simulation/run.hpp"
#include "pcsim/simulation/run_checkpoint.hpp"
#include "pcsim/simulation/run_session.hpp"
#include "pcsim/simulation/statics.hpp"
#include "pcsim/simulation/stepper.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;
using namespace pcsim;

namespace {

// A scene as its file (or text) and overrides give it, composed and checked.
struct Scene {
  std::string path;                    // the file ("" for a scene given as text)
  std::vector<std::string> overrides;  // KEY=VALUE, in order
  scene::InputNode composed;
  std::string name;
};

std::string override_text(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  return py::str(value).cast<std::string>();
}

Scene make_scene(const std::string& path, const std::string& text, const py::dict& set) {
  std::vector<std::string> overrides;
  std::vector<scene::InputOverride> parsed;
  for (const auto& [key, value] : set) {
    overrides.push_back(py::str(key).cast<std::string>() + "=" + override_text(value));
    parsed.push_back(
        scene::parse_override(overrides.back(), {"", "pcsim.Scene set " + overrides.back()}));
  }
  scene::InputNode composed = text.empty() ? scene::load_composed(path, parsed)
                                           : scene::load_composed_text(text, path, parsed);
  scene::load_run_scene(composed);  // every check of `pcsim run`: InputError
  std::string name =
      composed.has("name") ? composed.get_string("name") : fs::path(path).stem().string();
  return {path, overrides, composed, name.empty() ? "scene" : name};
}

simulation::Context context(bool quiet) {
  auto ctx = simulation::Context::of(PETSC_COMM_WORLD);
  ctx.quiet = quiet;
  return ctx;
}

// The provenance of a result made through the API (output/provenance.hpp).
nlohmann::json provenance(const Scene& s, int ranks) {
  output::ProvenanceInputs in;
  in.command = "run";
  in.arguments = {"python", "pcsim.run"};
  in.scene_file = s.path;
  in.overrides = s.overrides;
  in.ranks = ranks;
  simulation::record_inputs(in, "run ", s.path, s.composed);  // as `pcsim run` records them
  return output::make_provenance(in);
}

// Every record of the run, kept in memory (rank 0's are complete).
struct Recorder : simulation::RunObserver {
  std::vector<contact::StepRecord> records;
  void on_record(const contact::StepRecord& r) override { records.push_back(r); }
};

py::object to_python(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

py::array_t<double> array(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

// The time series of one pantograph and of the supports, as numpy arrays
// (rank 0: the records of the other ranks are not complete; they get none).
py::dict series(const Recorder& rec, const output::RunSettings& settings, int rank) {
  if (rank != 0) return series(Recorder(), settings, 0);
  std::vector<double> t;
  for (const auto& r : rec.records) t.push_back(r.t);
  py::dict pantographs;
  for (std::size_t p = 0; p < settings.pantograph_names.size(); ++p) {
    std::vector<double> x, f, z;
    for (const auto& r : rec.records) {
      x.push_back(r.contact_x.at(p));  // every record has every pantograph
      f.push_back(r.contact_force.at(p));
      z.push_back(r.head_z.empty() ? 0.0 : r.head_z.at(p));
    }
    py::dict d;
    d["position"] = array(x);
    d["contact_force"] = array(f);
    d["contact_force_filtered"] = array(output::filter_uniformly_sampled(t, f, settings.cutoff_hz));
    d["head_z"] = array(z);
    pantographs[py::str(settings.pantograph_names[p])] = d;
  }
  const std::size_t supports = rec.records.empty() ? 0 : rec.records.front().support_z.size();
  py::array_t<double> support_z(
      {static_cast<py::ssize_t>(t.size()), static_cast<py::ssize_t>(supports)});
  auto z = support_z.mutable_unchecked<2>();
  for (std::size_t k = 0; k < t.size(); ++k)
    for (std::size_t s = 0; s < supports; ++s) z(k, s) = rec.records[k].support_z[s];
  py::dict out;
  out["time"] = array(t);
  out["pantographs"] = pantographs;
  out["support_z"] = support_z;
  if (!rec.records.empty() && !rec.records.front().dropper_force.empty()) {
    const std::size_t n = rec.records.front().dropper_force.size();
    py::array_t<double> droppers({static_cast<py::ssize_t>(t.size()), static_cast<py::ssize_t>(n)});
    auto d = droppers.mutable_unchecked<2>();
    for (std::size_t k = 0; k < t.size(); ++k)
      for (std::size_t i = 0; i < n; ++i) d(k, i) = rec.records[k].dropper_force[i];
    out["dropper_force"] = droppers;
  }
  return out;
}

// A folder of our own for a run without 'output' (removed after the run).
std::string scratch_folder(const simulation::Context& ctx) {
  std::string dir;
  if (ctx.rank == 0) {
    std::random_device rd;
    dir = (fs::temp_directory_path() / ("pcsim-py-" + std::to_string(rd()))).string();
  }
  return broadcast_text(ctx.comm, dir);
}

// The accuracy pilot as `pcsim run` runs it (-pcsim_accuracy_pilot: auto, a
// modal run's, whose cut-off it chooses): its estimate, or null where none is
// wanted or a pilot run failed (then a RuntimeWarning, and the run goes on
// without it, as `pcsim run` does).
nlohmann::json accuracy_pilot(const Scene& s, const simulation::Context& ctx,
                              scene::RunScene& run_scene) {
  if (!simulation::wants_accuracy_pilot(simulation::accuracy_pilot_choice(), run_scene)) return {};
  const simulation::SceneSource source{s.path, s.overrides, s.composed, provenance(s, ctx.size)};
  try {
    const auto pilot = simulation::run_accuracy_pilot(ctx, source, run_scene);
    simulation::print_pilot(ctx, pilot);
    return pilot.json();
  } catch (const SolverError& e) {
    const std::string text = std::string("pcsim: no accuracy pilot: ") + e.what() +
                             "; the run goes on with the calibrated estimate";
    if (PyErr_WarnEx(PyExc_RuntimeWarning, text.c_str(), 1) != 0) throw py::error_already_set();
    return {};
  } catch (const simulation::FailedOnOtherRank& e) {  // the other ranks of rank 0's SolverError
    if (e.status() != simulation::kExitSolver) throw;
    return {};  // (rank 0 warns)
  }
}

py::dict run(const Scene& s, const std::string& output, const std::string& options, bool quiet,
             bool overwrite) {
  if (!options.empty()) PCSIM_PETSC(PetscOptionsInsertString(nullptr, options.c_str()));
  const auto ctx = context(quiet);
  auto run_scene = scene::load_run_scene(s.composed);
  const nlohmann::json pilot = accuracy_pilot(s, ctx, run_scene);
  const std::string dir = output.empty() ? scratch_folder(ctx) : output;
  output::OutputRequest request{
      dir, "pcsim.run", "output", "run", s.path, s.name, provenance(s, ctx.size)};
  request.overwrite = overwrite;
  Recorder recorder;
  simulation::RunRequest what;
  what.name = s.name;
  what.scene_path = s.path;
  what.inputs = simulation::run_input_files(s.path, s.composed);
  what.stop_on_signal = false;
  what.accuracy_pilot = pilot;
  simulation::RunOutcome outcome;
  {
    output::OutputDir out(ctx.comm, request);
    outcome = simulation::run(ctx, run_scene, what, out, &recorder);
    if (outcome.complete) out.commit();
  }
  if (output.empty() && ctx.rank == 0) fs::remove_all(dir);
  py::dict result = series(recorder, outcome.settings, ctx.rank);
  result["complete"] = outcome.complete;
  result["facts"] = to_python(outcome.facts);
  result["en50318"] = to_python(outcome.facts.value("en50318", nlohmann::json::object()));
  result["assessment"] = to_python(outcome.facts.value("assessment", nlohmann::json::object()));
  result["folder"] = output.empty() ? py::none() : py::cast(dir);
  return result;
}

py::dict modes(const Scene& s, int count, double max_frequency_hz) {
  const auto run_scene = scene::load_run_scene(s.composed);
  const auto statics = simulation::static_configuration(PETSC_COMM_WORLD, run_scene.catenary.mesh,
                                                        run_scene.catenary.form_finding, "static_");
  const auto m =
      simulation::catenary_modes(PETSC_COMM_WORLD, statics, count, max_frequency_hz, false);
  py::dict out;
  out["frequencies_hz"] = array(m.frequencies_hz);
  out["static_iterations"] = statics.result.snes_iterations;
  out["unknowns"] = static_cast<long>(statics.catenary_dofs);
  return out;
}

// A run advanced step by step (simulation/stepper.hpp): the scene lives as
// long as the stepper that refers to it.
// Simulations alive at exit are ended before PETSc, in the order they were
// made (the same on every rank: their PETSc objects are destroyed
// collectively).
struct Simulation;
std::map<long, Simulation*>& live_simulations() {
  static std::map<long, Simulation*> live;
  return live;
}

struct Simulation {
  scene::RunScene run_scene;
  std::unique_ptr<simulation::Stepper> stepper;
  long serial;
  Simulation() {
    static long made = 0;
    serial = made++;
    live_simulations()[serial] = this;
  }
  ~Simulation() { live_simulations().erase(serial); }
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;
  std::size_t index(const py::object& pantograph) const {
    if (py::isinstance<py::int_>(pantograph)) return pantograph.cast<std::size_t>();
    const auto name = pantograph.cast<std::string>();
    const auto names = stepper->pantograph_names();
    for (std::size_t p = 0; p < names.size(); ++p)
      if (names[p] == name) return p;
    throw InputError("step-wise run", "pantograph", "no pantograph named '" + name + "'");
  }
};

std::unique_ptr<Simulation> start_simulation(const Scene& s, const std::string& options,
                                             bool quiet) {
  if (!options.empty()) PCSIM_PETSC(PetscOptionsInsertString(nullptr, options.c_str()));
  auto sim = std::make_unique<Simulation>();
  sim->run_scene = scene::load_run_scene(s.composed);
  const auto ctx = context(quiet);
  accuracy_pilot(s, ctx, sim->run_scene);  // a modal run's cut-off, as `pcsim run` chooses it
  sim->stepper = std::make_unique<simulation::Stepper>(ctx, sim->run_scene);
  return sim;
}

void bind_simulation(py::module_& m) {
  using simulation::StepReading;
  auto reading = [](std::vector<double> StepReading::*field) {
    return [field](const Simulation& sim) { return array(sim.stepper->reading().*field); };
  };
  py::class_<Simulation>(m, "Simulation",
                         "A run advanced step by step (co-simulation, hardware in the loop)")
      .def(py::init(&start_simulation), py::arg("scene"), py::arg("options") = "",
           py::arg("quiet") = true,
           "Sets the scene's run up as `pcsim run` does (static configuration, static start) "
           "and stops before the first step; 'options': PETSc options")
      .def(
          "advance", [](Simulation& sim, long steps) { return sim.stepper->advance(steps); },
          py::arg("steps") = 1, "Up to 'steps' time steps (fewer at the end); the steps taken")
      .def_property_readonly("time", [](const Simulation& s) { return s.stepper->reading().t; })
      .def_property_readonly("step", [](const Simulation& s) { return s.stepper->reading().step; })
      .def_property_readonly("end_time", [](const Simulation& s) { return s.stepper->end_time(); })
      .def_property_readonly("finished", [](const Simulation& s) { return s.stepper->finished(); })
      .def_property_readonly("pantographs",
                             [](const Simulation& s) { return s.stepper->pantograph_names(); })
      .def("contact_force", reading(&StepReading::contact_force),
           "Contact force on each pantograph's head now [N]")
      .def("contact_position", reading(&StepReading::contact_x),
           "Station of each pantograph's contact point now [m]")
      .def("head_height", reading(&StepReading::head_z),
           "Height of each pantograph's contact point now [m]")
      .def(
          "set_head_force",
          [](Simulation& sim, const py::object& p, double f) {
            sim.stepper->set_head_force(sim.index(p), f);
          },
          py::arg("pantograph"), py::arg("force"),
          "A vertical force [N, upwards] on a pantograph's head (index or name) from the next "
          "step on")
      .def(
          "head_force",
          [](const Simulation& sim, const py::object& p) {
            return sim.stepper->head_force(sim.index(p));
          },
          py::arg("pantograph"), "The force set on a pantograph's head [N]")
      .def(
          "set_base_motion",
          [](Simulation& sim, const py::object& p, double z, double v, const py::object& a) {
            sim.stepper->set_base_motion(
                sim.index(p), z, v,
                a.is_none() ? std::numeric_limits<double>::quiet_NaN() : a.cast<double>());
          },
          py::arg("pantograph"), py::arg("displacement"), py::arg("velocity") = 0.0,
          py::arg("acceleration") = py::none(),
          "A pantograph's base (the vehicle roof) at 'displacement' [m, upwards] moving at "
          "'velocity' [m/s] with 'acceleration' [m/s^2] from the next step on, held until set "
          "again (lumped models read the first two; the DSA-380 models need the acceleration)");
}

void initialize() {
  PetscBool started = PETSC_FALSE;
  PetscInitialized(&started);
  if (started) return;
  int argc = 0;
  char** argv = nullptr;
  setenv("HWLOC_COMPONENTS", "-gl", 0);  // no X display probing (src/app/main.cpp)
  // Before pcsim's first BLAS call (core/blas_kernels.hpp); numpy imported
  // first has started BLIS already: then a warning says how to choose.
  const bool numpy_first = py::module_::import("sys").attr("modules").contains("numpy");
  pcsim::select_blas_kernels(numpy_first);
  if (!pcsim::blas_kernels().too_late.empty())
    PyErr_WarnEx(PyExc_RuntimeWarning, ("pcsim: BLAS: " + pcsim::blas_kernels().text()).c_str(), 1);
  if (SlepcInitialize(&argc, &argv, nullptr, nullptr) != 0)
    throw std::runtime_error("pcsim: PETSc/SLEPc could not start");
  pcsim::simulation::count_node_processes(PETSC_COMM_WORLD);  // collective, as the start is
  py::module_::import("atexit").attr("register")(py::cpp_function([] {
    for (auto& [serial, sim] : live_simulations()) sim->stepper.reset();  // PETSc objects first
    SlepcFinalize();
  }));
}

}  // namespace

PYBIND11_MODULE(pcsim, m) {
  m.doc() = "pcsim: pantograph-catenary dynamic interaction (docs/python.md)";
  initialize();
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<SolverError> solver_error(m, "SolverError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      py::object error = py::handle(input_error.ptr())(e.what());
      error.attr("file") = e.file();
      error.attr("key") = e.key();
      error.attr("reason") = e.reason();
      PyErr_SetObject(input_error.ptr(), error.ptr());
    } catch (const SolverError& e) {
      solver_error(e.what());
    }
  });
  m.attr("__version__") = version();
  // The BLAS and its kernels (core/blas_kernels.hpp).
  m.attr("blas") = pcsim::blas_kernels().text();
  py::class_<Scene>(m, "Scene", "A run scene, composed and checked as `pcsim check` does")
      .def(py::init([](const std::string& path, const py::dict& set) {
             return make_scene(path, "", set);
           }),
           py::arg("path"), py::arg("set") = py::dict(),
           "The scene file with keys set by path ({'simulation.speed_kmh': 250}); InputError "
           "(file, key, reason) if it cannot run")
      .def_static(
          "from_dict",
          [](const py::dict& scene, const std::string& base_dir, const py::dict& set) {
            const std::string text =
                py::module_::import("json").attr("dumps")(scene).cast<std::string>();
            return make_scene((fs::path(base_dir) / "scene.yaml").string(), text, set);
          },
          py::arg("scene"), py::arg("base_dir") = ".", py::arg("set") = py::dict(),
          "A scene from a dict (paths in it relative to base_dir)")
      .def_readonly("name", &Scene::name)
      .def_readonly("path", &Scene::path)
      .def_readonly("overrides", &Scene::overrides)
      .def(
          "yaml", [](const Scene& s) { return scene::to_yaml(s.composed); }, "the composed scene");
  m.def("run", &run, py::arg("scene"), py::arg("output") = "", py::arg("options") = "",
        py::arg("quiet") = true, py::arg("overwrite") = false,
        "Runs the scene through the run pipeline (as `pcsim run`, a modal scene after its "
        "accuracy pilot: -pcsim_accuracy_pilot); returns a dict: time, "
        "pantographs (name -> position, contact_force, contact_force_filtered, head_z), "
        "support_z, dropper_force (when the scene records them), en50318, assessment, facts, "
        "complete, "
        "folder. 'output': a results folder to keep (none: nothing is kept); 'options': "
        "PETSc options, e.g. '-ts_dt 0.002' (they stay in the options database)");
  bind_simulation(m);
  m.def("modes", &modes, py::arg("scene"), py::arg("count") = 20, py::arg("max_frequency_hz") = 0.0,
        "The catenary's first 'count' modes (or every mode below max_frequency_hz > 0) about its "
        "static configuration: a dict with frequencies_hz");
}
