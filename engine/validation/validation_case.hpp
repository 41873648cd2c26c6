#pragma once
// A published case the project claims to reproduce, as kept in validation/<case>/case.json (the format
// is validation/README.md): the runs that make our numbers (example specs with changes, each at the
// "full" level and, where the docs show it gives the same answer, reduced at the "quick" level), the
// quantities compared (ours read from a run's summary or series; the reference as a value, a range or
// the points of a published curve, with its citation, how it was read and a tolerance), the figure
// that shows both, and the documented reason of a quantity known to miss its reference.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rupture::validation {

/// A level of the suite: "quick" (reduced where the docs show the answer is the same) or "full".
bool isLevel(const std::string& level);

/// One run of a case: a spec (an example file with changes) and, optionally, one field it varies
/// over several runs (sample seeds) whose quantities are then averaged.
struct CaseRun {
  std::string name;
  nlohmann::json spec;                    ///< full level: the example, its "remove" keys dropped, "changes" applied
  nlohmann::json quickChanges;            ///< dotted path -> value, applied on top at the quick level
  std::string varyPath;                   ///< dotted path varied over the runs ("" for one run)
  std::vector<nlohmann::json> varyValues, quickVaryValues;
  bool inQuick = true;                    ///< false: this run (and what reads it) is full level only
};

/// Where a number comes from: a run's summary scalar (its mean over a varied run's members) times a
/// factor, or a run's series y(x) interpolated at x (both scaled).
struct ValueSource {
  std::string run;
  std::string summary;                    ///< summary key; empty for a series
  std::string seriesX, seriesY;
  double factor = 1;                      ///< summary: value × factor; series: y × factor
  double xFactor = 1;                     ///< series: x × xFactor is compared with the point's x
  /// Series: instead of y at one x, the largest y over x × xFactor in [first, second] (a first peak).
  std::optional<std::pair<double, double>> maxOver;
  /// Series: instead of y at one x, the first x × xFactor at which y × factor reaches this level,
  /// interpolated between rows (the arrival of a wave front: a time of flight).
  std::optional<double> firstReaching;
  /// Summary sources: divided by another run's summary scalar (a ratio between runs: a trend).
  std::optional<std::pair<std::string, std::string>> per;  ///< (run, summary key)
};

/// The reference: a value, a range [low, high] (a measured spread; either end may be open), or a
/// value computed from a run's own inputs (ρ0 c0 V from its summary).
struct Reference {
  std::optional<double> value, low, high;
  std::optional<ValueSource> fromRun;
  double uncertainty = 0;                 ///< of the reading (digitised points), reported only
};

struct Tolerance {
  double relative = 0;                    ///< of the reference value (of the violated bound for a range)
  double absolute = 0;                    ///< in the quantity's unit
};

struct Quantity {
  std::string name, label, unit;
  ValueSource ours;
  Reference reference;
  Tolerance tolerance;
  std::optional<double> at;               ///< series quantities without max_over: the x at which ours is read
  std::string knownFailure;               ///< documented reason it misses its reference ("" if none)
  bool inQuick = true;
};

/// Our curve over the reference: a run's series (scaled), the published points (x, y, uncertainty),
/// horizontal lines at reference quantities read on y and vertical ones at those read on x (an
/// arrival time).
struct CaseFigure {
  std::string run, x, y;
  double xFactor = 1, yFactor = 1;
  std::string xLabel, yLabel;
  std::vector<std::array<double, 3>> points;
  std::string pointsLabel;
  std::vector<std::string> lineQuantities;
  std::vector<std::string> verticalLineQuantities;  ///< reference values × xFactor, drawn at that x
};

struct ValidationCase {
  std::string id, title, paper, citation, howRead, comparison;
  bool inQuick = true;                    ///< false: the case runs at the full level only
  std::string quickNote;                  ///< why the quick level stands in for the full one (or why absent)
  std::vector<CaseRun> runs;
  std::vector<Quantity> quantities;
  std::optional<CaseFigure> figure;
};

/// Every case embedded in this build (validation/*/case.json), in id order; parsed once.
const std::vector<ValidationCase>& validationCases();

/// The case of that id, or nullptr.
const ValidationCase* findValidationCase(const std::string& id);

/// Parses one case file's JSON (`id`: its folder name); throws std::runtime_error naming the
/// case, the field and what is allowed.
ValidationCase parseValidationCase(const std::string& id, const nlohmann::json& text);

/// The specs a case runs at a level: run name -> its member specs (one, or one per varied value).
std::vector<std::pair<std::string, std::vector<nlohmann::json>>> caseSpecs(const ValidationCase& c,
                                                                            const std::string& level);

/// What the runs of a case gave: per run name, per member, the summary and the series it needs.
struct RunData {
  nlohmann::json summary;
  std::vector<std::pair<std::string, std::vector<double>>> series;
  const std::vector<double>* findSeries(const std::string& name) const;
};
using CaseRunData = std::vector<std::pair<std::string, std::vector<RunData>>>;

/// The series names a case reads from a run (quantities and figure).
std::vector<std::string> seriesNeeded(const ValidationCase& c, const std::string& run);

/// Compares: the case's result as JSON (the layout docs/validation.md gives: quantities with ours,
/// reference, tolerance, deviation and verdict; the figure's curves; the case's verdict).
nlohmann::json evaluateCase(const ValidationCase& c, const std::string& level, const CaseRunData& data);

}  // namespace rupture::validation
