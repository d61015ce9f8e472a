// rotgen — the motion in 3D in a browser: one self-contained HTML page (three.js inlined, the
// run's data inline, no network request of any kind) that plays a run's attitude.
//
// The page shows the body as a solid whose shape follows its inertia (a uniform box whose
// principal moments are in the body's proportions, along the principal axes; a rod for a linear
// rotor), its body axes, a gyrostat's wheels (a disc on each wheel's axis), the fixed point,
// gravity's direction, the angular momentum L in space, and the trace of the figure axis's tip
// (body axis 3) on the unit sphere. Attitudes between samples are interpolated by quaternion slerp.
// Conventions: the attitude is the unit quaternion q = (q0, q1, q2, q3), scalar first, rotating
// body axes into space axes (R(q) = A^T, A the passive z-x-z matrix of (5.25)); space z is up.
#pragma once

#include "scene/scene.hpp"
#include "support/atomic_file.hpp"

#include <array>
#include <string>
#include <vector>

namespace rotgen {

struct view_body {
    std::string kind = "box";               // "box" | "rod" (a linear rotor)
    std::array<double, 3> size{};           // full edge lengths along the principal axes (rod: z)
    std::array<double, 3> centre{};         // the solid's centre in body axes (the centre of mass)
    std::array<double, 4> axes{1, 0, 0, 0}; // principal frame in body axes, as a quaternion
    bool gravity = false;                   // the model has uniform gravity (drawn along -z)
    // A gyrostat's wheels (drawn as discs on their axes): names and unit axes in body axes.
    std::vector<std::string> wheel_names;
    std::vector<std::array<double, 3>> wheel_axes;
};

struct view_data {
    std::string title, source;        // the page's title; where its data came from
    std::vector<double> t;            // sample times, in run order
    std::vector<double> q;            // 4 per sample: the attitude
    std::vector<double> L;            // 3 per sample (space axes), or empty
    std::vector<std::string> columns; // recorded columns shown in the read-out
    std::vector<double> values;       // columns.size() per sample
    view_body body;
};

// The body's solid, from the scene's model at the scene's parameter values.
view_body view_body_of(const scene_spec& scene);

// The attitude of every row from the columns a run recorded: q0..q3 when present, otherwise the
// Euler angles phi, theta, psi (a linear rotor: phi, theta). `columns` are those after t; each
// row is t then the columns. Throws user_error at `where` naming the missing columns.
view_data view_of_rows(const scene_spec& scene, const std::vector<std::string>& columns,
                       const std::vector<std::vector<double>>& rows, const source_location& where);

// The page: the template filled with three.js, OrbitControls and the data (user_error when
// three.js is not installed).
std::string view_page(const view_data& data);

// Writes the page atomically to `path` (never over one of `inputs`); given `outputs`, it appears
// with them (support/atomic_file.hpp's output_set).
void write_view(const std::string& path, const view_data& data,
                const std::vector<std::string>& inputs, output_set* outputs = nullptr);

// A CSV that `rotgen simulate` wrote: its provenance line (run/provenance.hpp; empty when the file
// has none: lines starting with '#' before the header are skipped), its header (after t) and its
// rows. Throws user_error located at the file, line and column of what is wrong.
struct csv_table {
    std::string provenance;
    int header_line = 1;
    std::vector<std::string> columns;
    std::vector<std::vector<double>> rows;
};
csv_table read_run_csv(const std::string& path);

} // namespace rotgen

namespace rotgen {

struct run_result; // run/engine.hpp

// `simulate --view`: the scene with the attitude (q0..q3; a linear rotor: phi, theta) and the
// space-axes L added to what it records, for the page (user_error for a form without the
// attitude: the reduced form); the page's data from a run of that scene; and the run with only
// the scene's own records, as the CSV and the summary show them.
scene_spec scene_for_view(const scene_spec& scene, const std::string& option);
view_data view_of_run(const scene_spec& viewed, const run_result& r);
run_result only_scene_records(run_result r, const scene_spec& scene);

} // namespace rotgen
