// One virtual experiment in one place: its name, its [experiment] case keys and their reader, how
// it runs, its outcome (values with units, series, and how the run ended, as data), the files and
// JSON `repose experiment` writes, and what `repose diagnose` fits and simulates with it. The
// registry (experiments/registry.h) lists them; the case loader, `repose experiment`, `calibrate`,
// `diagnose` and `synth-data` reach experiments only through it.
//
// Adding an experiment: a class derived from Experiment in its own file (drop.cpp is a complete
// example, drop_on_bed.cpp a variant of it) and one line in registry.cpp.
#pragma once
#include <functional>
#include <memory>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "case/case_spec.h"
#include "case/toml_section.h"
#include "experiments/run_options.h"
#include "stats/free_parameter.h"

namespace repose {

using OrderedJson = nlohmann::ordered_json;

// How a run ended. Anything but Measured is a reading the rig could not take; a strict run
// (`repose experiment`, `calibrate`) reports it as an error, a tolerant one (a diagnosis search,
// which meets such models on its way) returns it as data with the values the experiment puts in
// its place.
enum class OutcomeStatus {
  Measured,
  NoRebound,     // drop: the body never left the plate within max_time
  DidNotMove,    // tilt: the body held on up to max_angle (or max_time)
  NoSlope,       // repose: the heap shows no measurable slope
  StillRolling,  // roll: still rolling at max_time (the distance so far)
  DidNotRoll,    // roll: the body rests on the incline
  NotSettled,    // repose: something still moved at max_time
  Failed,        // the run stopped on an error (its text is the problem)
};

// A file of `repose experiment` besides ID.json: its name in the output folder and its writer.
struct OutputFile {
  std::string name;
  std::function<void(const std::string& path)> write;  // writes the whole file at `path`
};

// A text file (a CSV) written through a stream, atomically.
OutputFile text_file(std::string name, std::function<void(std::ostream&)> write);

// One run of an experiment, as data.
struct ExperimentOutcome {
  OutcomeStatus status = OutcomeStatus::Measured;
  std::string problem;                   // not Measured: what happened, in words
  std::map<std::string, double> values;  // the responses (Experiment::responses), SI units, angles in deg
  std::vector<std::pair<double, double>> trajectory;  // a camera track (t, height of the lowest point)
  OrderedJson json;                      // `repose experiment` writes it as TYPE.json
  std::vector<OutputFile> files;         // and these beside it
  std::vector<std::string> lines;        // and prints these (then "wrote DIR/ID.json, FILE, ...")
};

// How to run it.
struct ExperimentRun : ExperimentRunOptions {
  bool strict = true;        // false: a reading the rig cannot take comes back as a status
  int replicates = 1;        // `repose experiment --replicates N` (seeds seed ... seed+N-1)
  std::string picture_path;  // non-empty: save the experiment's picture there (a heap's PNG)
};

// A quantity a diagnosis compares with measured data: its name in measured-data files, whether it
// is a time series (rows with t), and its unit ("m", "deg", "1").
struct MeasureInfo {
  std::string name;
  bool series = false;
  std::string unit;
};

// What tells two candidate extensions apart when this experiment's data cannot (an ambiguous
// diagnosis): the camera's track of the drop, a wider range of the condition, or the packing.
enum class SeparatingMeasurement { CameraTrack, WiderCondition, Packing };

// What `repose diagnose` and `repose synth-data` need to know of an experiment they simulate.
struct DiagnosisRole {
  std::vector<MeasureInfo> measures;        // what measured-data rows of its cases may measure
  std::vector<std::string> synthetic;       // the scalar measures synth-data writes, in row order
  FreeParameter baseline;                   // the baseline's free parameter and its search range,
  double Interaction::*baseline_field = nullptr;  // a field of the tested contact (tested_contact)
  std::string baseline_model;               // for reports: "Hertz-Mindlin, constant restitution"
  std::string condition;                    // the case key synthetic data vary by default
  std::string truth_option;                 // synth-data's option that sets the baseline's truth
  SeparatingMeasurement separating = SeparatingMeasurement::WiderCondition;
  bool expensive = false;                   // a run costs ~1000 drops (a heap): fits spend less
};

// A run for the diagnosis: the value of each measure (names of DiagnosisRole::measures) and the
// camera track where the experiment has one.
struct DiagnosticOutcome {
  std::map<std::string, double> values;
  std::vector<std::pair<double, double>> trajectory;
};

class Experiment {
 public:
  virtual ~Experiment() = default;

  // --- What it is.
  virtual std::string id() const = 0;  // unique: "drop", "roll_tilt"
  virtual std::string type() const { return id(); }  // the [experiment] type its cases give
  virtual std::string description() const = 0;       // "drop (restitution)"
  // Whether it runs a case of its type (roll: by method; a variant: by what the case holds); the
  // type itself is not compared.
  virtual bool handles(const CaseSpec&) const { return true; }

  // --- Its case keys: the [experiment] keys besides type and max_time, those of them whose value
  // names a [[wall]] (the loader checks the wall exists), and their reader, which returns the
  // experiment's settings (ExperimentSpec::settings, settings_of below) with located errors.
  // Experiments of one type share their keys and reader.
  virtual std::vector<std::string> keys() const = 0;
  virtual std::vector<std::string> wall_keys() const { return {}; }
  virtual std::shared_ptr<const ExperimentSettings> read_keys(const Section& s) const = 0;

  // --- Running: the names of the values an outcome holds (what a calibration can fit), and a run.
  // A strict run throws std::runtime_error naming the case where the rig cannot take a reading.
  virtual std::vector<std::string> responses() const = 0;
  virtual ExperimentOutcome run(const CaseSpec& spec, const ExperimentRun& run) const = 0;
  // What a case must hold that no key alone says (a repose rig's max_time after its lift), checked
  // with the command line's settings applied and before anything is written: throws CaseError.
  virtual void check_case(const CaseSpec&) const {}

  // --- The diagnosis (nullptr: diagnose does not simulate it).
  virtual const DiagnosisRole* diagnosis() const { return nullptr; }
  // The contact the test calibrates, whose restitution or friction is the baseline's free
  // parameter and which contact-model extensions act on. Throws naming the case when absent.
  virtual Interaction& tested_contact(CaseSpec& spec) const;
  // Why diagnose cannot simulate this case ("" when it can).
  virtual std::string diagnosis_problem(const CaseSpec&) const { return ""; }
  // Once per loaded condition: what the diagnosis redoes per model (a heap drops its spheres and
  // refills them per replicate).
  virtual void prepare_for_diagnosis(CaseSpec&) const {}
  // Replicate r of a model (common random numbers: replicate r has the same draws in every
  // evaluation), and the replicate with an absolute seed (synthetic data's own draws).
  virtual void replicate(CaseSpec& spec, int r) const { spec.seed += uint64_t(r); }
  virtual void reseed(CaseSpec& spec, uint64_t seed) const { spec.seed = seed; }
  // Whether the result depends on the replicate's seed (a clump at a random orientation, a fill).
  virtual bool stochastic(const CaseSpec&) const { return false; }
  // Whether `repose experiment --replicates N` applies (its run() honours ExperimentRun::replicates).
  virtual bool takes_replicates() const { return false; }
  // Whether its runs stop and go on (experiments/experiment_checkpoint.h: checkpoints every
  // [output] checkpoint_interval and on SIGINT/SIGTERM, `repose experiment --restart`): its run()
  // honours ExperimentRunOptions::checkpoint_dir and restart.
  virtual bool resumable() const { return false; }
  // The measures `wanted` of one model; `strict` false: a model far from the data (met while
  // searching) gives the values that move the search away instead of an error.
  virtual DiagnosticOutcome simulate_for_diagnosis(CaseSpec spec, const std::vector<std::string>& wanted,
                                                   bool strict) const;
  // A measured value that cannot be right for this case, in words ("" when plausible): lengths a
  // thousand times the rig's size are millimetres written as metres.
  virtual std::string implausible(const MeasureInfo&, double, const CaseSpec&) const { return ""; }
};

// An experiment's settings of type T as its reader left them in a case, or T's defaults when the
// case holds none (a case built in code; a plan's base case without [experiment]).
// A T is also what a type derived from T holds (a roll case's settings are a tilt's and more).
template <class T>
const T& settings_of(const ExperimentSpec& ex) {
  static const T defaults{};
  const T* s = dynamic_cast<const T*>(ex.settings.get());
  return s ? *s : defaults;
}
// The same to change (tests, a diagnosis): the case gets a copy of its settings (T's defaults when
// it holds none), which this returns; other copies of the case keep theirs.
template <class T>
T& edit_settings(ExperimentSpec& ex) {
  auto copy = std::make_shared<T>(settings_of<T>(ex));
  ex.settings = copy;
  return *copy;
}

// The responses of an outcome as a strict run must have them: throws its problem when the rig
// could not take the reading.
const ExperimentOutcome& measured_or_throw(const ExperimentOutcome& outcome);

// The outcome's JSON led by its status: "measured", or "failed" with the reason (the problem).
OrderedJson with_status(const ExperimentOutcome& outcome);

// Writes every file, then ID.json (each whole or not at all; the JSON last, so a failed file leaves
// no result beside it), and returns the lines to print (the outcome's and "wrote ...", naming each).
std::vector<std::string> write_outcome(const ExperimentOutcome& outcome, const std::string& json_name,
                                       const std::string& dir);

// A number as printf("%.Ng") writes it, for the lines experiments print.
std::string printf_text(const char* format, ...);

}  // namespace repose
