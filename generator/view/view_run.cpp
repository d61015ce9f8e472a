#include "run/engine.hpp"
#include "view/view.hpp"

#include <algorithm>

namespace rotgen {

scene_spec scene_for_view(const scene_spec& scene, const std::string& option) {
    if (scene.form == form_kind::reduced)
        throw user_error({option}, "the view needs the attitude, which the reduced form does "
                                   "not keep (its ignored angles): use another form");
    if (scene.model.rotor) return with_records(scene, {"phi", "theta"});
    // a body with wheels: L from the run's own record, which holds the wheels' momenta (the view
    // cannot compute it from omega alone)
    if (!scene.model.wheels.empty())
        return with_records(scene, {"q0", "q1", "q2", "q3", "Lx", "Ly", "Lz"});
    return with_records(scene, {"q0", "q1", "q2", "q3"});
}

view_data view_of_run(const scene_spec& viewed, const run_result& r) {
    return view_of_rows(viewed, r.columns, r.rows, viewed.where);
}

namespace {

// Each row's t and the values of `keep` (indices into the columns after t).
void keep_columns(std::vector<std::vector<double>>& rows, const std::vector<std::size_t>& keep) {
    for (auto& row : rows) {
        std::vector<double> kept{row[0]};
        for (std::size_t k : keep)
            kept.push_back(row[k + 1]);
        row = std::move(kept);
    }
}

} // namespace

run_result only_scene_records(run_result r, const scene_spec& scene) {
    std::vector<std::string> columns;
    for (const auto& name : scene.record)
        for (const auto& c : record_columns(name))
            columns.push_back(c);
    std::vector<std::string> kept;
    std::vector<std::size_t> keep;
    for (const auto& c : columns)
        if (const auto it = std::find(r.columns.begin(), r.columns.end(), c);
            it != r.columns.end()) {
            keep.push_back(static_cast<std::size_t>(it - r.columns.begin()));
            kept.push_back(c);
        }
    keep_columns(r.rows, keep);
    keep_columns(r.event_rows, keep);
    r.columns = kept;
    r.record = scene.record;
    return r;
}

} // namespace rotgen
