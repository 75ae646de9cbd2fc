#pragma once
// The common accuracy CSV: one record format for every sweep of an approximation (a "knob"), so that
// one report can set what each setting costs in time beside the error it makes. One line per knob
// setting and error metric:
//
//   knob,value,off,metric,error,unit,better,ms,ms_phase,memory_bytes,scene,camera,actors
//
// `off` is 1 on the setting that switches the approximation off (its error must be zero or at the
// metric's floor), `better` says which way the metric improves ("lower" or "higher"), `ms` is the
// time of the phase `ms_phase` that the knob changes. docs/reference/accuracy-csv.md lists the
// metrics in use.

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace throng::sim {

/// One error metric of a knob setting.
struct AccuracyMetric {
    std::string name;          ///< e.g. "psnr", "ssim", "pixels_off_8", "joint_error_mean"
    double value = 0;          ///< the error measured (finite)
    std::string unit;          ///< e.g. "dB", "1", "share", "mm", "m", "1/s"
    bool lowerIsBetter = true; ///< false for PSNR, SSIM, NCC
};

/// One knob setting measured: its metrics, the time of the phase it changes, its memory.
struct AccuracyRecord {
    std::string knob;                   ///< the approximation, e.g. "lod scale"
    std::string value;                  ///< its setting, as a user would write it
    bool off = false;                   ///< true on the setting that switches the approximation off
    std::vector<AccuracyMetric> metrics;///< at least one
    double ms = 0;                      ///< milliseconds of `msPhase` per frame (or per step, per cell)
    std::string msPhase;                ///< which time: "app_cull", "draw", "frame", "step", ...
    double memoryBytes = 0;             ///< memory the setting holds (0 when none is attributable)
    std::string scene;                  ///< scene file name (no directories)
    std::string camera;                 ///< "street", "overview", "path" or "none"
    std::int64_t actors = 0;            ///< actors (or agents) measured
};

/// One line of an accuracy CSV as read back.
struct AccuracyRow {
    std::string knob;        ///< the approximation, as in AccuracyRecord::knob
    std::string value;       ///< its setting
    bool off = false;        ///< the setting that switches the approximation off
    AccuracyMetric metric;   ///< the one metric of this line
    double ms = 0;           ///< milliseconds of msPhase
    std::string msPhase;     ///< which time ms is
    double memoryBytes = 0;  ///< memory the setting holds
    std::string scene;       ///< scene file name
    std::string camera;      ///< "street", "overview", "path" or "none"
    std::int64_t actors = 0; ///< actors (or agents) measured
    std::string file;        ///< the file it came from
    int line = 0;            ///< its line in that file (1: the header)
};

/// Writes accuracy records to a CSV file, header first. Every add() is checked before anything is
/// written, so a bad record (empty knob or metric, non-finite number, negative time) throws
/// std::invalid_argument naming the knob, value and field, and leaves the file without it.
class AccuracyCsv {
public:
    /// Opens (truncates) `path` and writes the header. Throws std::runtime_error if it cannot.
    explicit AccuracyCsv(const std::string& path);
    /// Appends one line per metric of `record`.
    void add(const AccuracyRecord& record);
    /// The header line (without newline).
    static const char* header();

private:
    std::string path_;
    std::ofstream out_;
};

/// Reads every line of an accuracy CSV. Throws std::runtime_error naming the file, line and column
/// on a missing file, a header that is not the common one, a wrong field count or a bad number.
std::vector<AccuracyRow> readAccuracyCsv(const std::string& path);

/// The file name of a scene path, for the `scene` column.
std::string sceneName(const std::string& scenePath);

}  // namespace throng::sim
