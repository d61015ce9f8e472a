#include "view/view.hpp"

#include "emit/emit.hpp"
#include "expr/symbols.hpp"
#include "run/angle_chart.hpp"
#include "support/atomic_file.hpp"
#include "support/format.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace rotgen {

namespace {

double value_at(const GiNaC::ex& e, const scene_spec& scene) {
    GiNaC::exmap values;
    for (std::size_t i = 0; i < scene.model.parameters.size(); ++i)
        values[scene.model.parameters[i].symbol] = GiNaC::numeric(scene.parameters[i]);
    const GiNaC::ex v = GiNaC::evalf(e.subs(values));
    return GiNaC::is_a<GiNaC::numeric>(v) ? GiNaC::ex_to<GiNaC::numeric>(v).to_double() : 0.0;
}

// The centre of mass in body axes (gravity's `com`), or 0 without gravity.
Eigen::Vector3d centre_of_mass(const scene_spec& scene) {
    Eigen::Vector3d com = Eigen::Vector3d::Zero();
    if (scene.model.gravity)
        for (int i = 0; i < 3; ++i)
            com[i] = value_at(scene.model.gravity->com[i], scene);
    return com;
}

// A uniform box has I_a = m (b^2 + c^2) / 12 about its axes, so its edges are in the proportions
// a^2 ~ I_b + I_c - I_a. Scaled to fit inside the unit sphere (a half-diagonal of 0.75, or 0.45
// beside an off-centre centre of mass); a flat lamina keeps a thin edge.
std::array<double, 3> box_size(const Eigen::Vector3d& moments, bool off_centre) {
    Eigen::Vector3d edge;
    for (int i = 0; i < 3; ++i)
        edge[i] = std::sqrt(std::max(0.0, moments.sum() - 2 * moments[i]));
    const double largest = edge.maxCoeff() > 0 ? edge.maxCoeff() : 1.0;
    edge = edge.cwiseMax(0.04 * largest);
    edge *= (off_centre ? 0.9 : 1.5) / edge.norm();
    return {edge[0], edge[1], edge[2]};
}

Eigen::Matrix3d tensor_at(const scene_spec& scene) {
    Eigen::Matrix3d tensor;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            tensor(i, j) = value_at(scene.model.inertia[i][j], scene);
    return tensor;
}

} // namespace

view_body view_body_of(const scene_spec& scene) {
    view_body b;
    b.gravity = scene.model.gravity.has_value();
    const Eigen::Vector3d com = centre_of_mass(scene);
    const bool off_centre = com.norm() > 0;
    const Eigen::Vector3d centre = off_centre ? Eigen::Vector3d(0.5 * com / com.norm()) : com;
    b.centre = {centre[0], centre[1], centre[2]};
    for (const wheel_spec& w : scene.model.wheels) {
        Eigen::Vector3d a(value_at(w.axis[0], scene), value_at(w.axis[1], scene),
                          value_at(w.axis[2], scene));
        a.normalize();
        b.wheel_names.push_back(w.name);
        b.wheel_axes.push_back({a[0], a[1], a[2]});
    }
    if (scene.model.rotor) { // the line is body axis 3
        b.kind = "rod";
        b.size = {0.06, 0.06, off_centre ? 1.0 : 1.6};
        return b;
    }
    const Eigen::Matrix3d tensor = tensor_at(scene);
    Eigen::Vector3d moments = tensor.diagonal();
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
    if (!tensor.isDiagonal(0.0)) { // principal axes, as a right-handed frame
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(tensor);
        moments = solver.eigenvalues();
        axes = solver.eigenvectors();
        if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
    }
    b.size = box_size(moments, off_centre);
    const Eigen::Quaterniond frame(axes);
    b.axes = {frame.w(), frame.x(), frame.y(), frame.z()};
    return b;
}

namespace {

int column_of(const std::vector<std::string>& columns, const std::string& name) {
    const auto it = std::find(columns.begin(), columns.end(), name);
    return it == columns.end() ? -1 : static_cast<int>(it - columns.begin()) + 1;
}

// q = q_z(phi) (x) q_x(theta) (x) q_z(psi): R(q) = Rz(phi) Rx(theta) Rz(psi) = A^T (5.25); any
// other sequence by runtime/euler_sequence.hpp.
std::array<double, 4> quaternion_of_angles(const angle_convention& c, double phi, double theta,
                                           double psi) {
    if (!c.is_zxz()) {
        const Eigen::Quaterniond q = sequence_quaternion<double>(sequence_of(c), {phi, theta, psi});
        return {q.w(), q.x(), q.y(), q.z()};
    }
    const double cp = std::cos(phi / 2), sp = std::sin(phi / 2);
    const double ct = std::cos(theta / 2), st = std::sin(theta / 2);
    const double cs = std::cos(psi / 2), ss = std::sin(psi / 2);
    return {cp * ct * cs - sp * ct * ss, cp * st * cs + sp * st * ss, sp * st * cs - cp * st * ss,
            cp * ct * ss + sp * ct * cs};
}

} // namespace

view_data view_of_rows(const scene_spec& scene, const std::vector<std::string>& columns,
                       const std::vector<std::vector<double>>& rows, const source_location& where) {
    std::array<int, 4> q{};
    for (int k = 0; k < 4; ++k)
        q[k] = column_of(columns, "q" + std::to_string(k));
    const bool quaternion = *std::min_element(q.begin(), q.end()) > 0;
    const auto& names = scene.model.angles.names;
    const std::array<int, 3> angles{column_of(columns, names[0]), column_of(columns, names[1]),
                                    column_of(columns, names[2])};
    const bool rotor = scene.model.rotor;
    if (!quaternion && (angles[0] < 0 || angles[1] < 0 || (!rotor && angles[2] < 0)))
        throw user_error(where, std::string("no attitude to show: the view needs the columns ") +
                                    (rotor ? "phi, theta"
                                           : "q0, q1, q2, q3 or " + names[0] + ", " + names[1] +
                                                 ", " + names[2]) +
                                    " (add them to the scene's record)");
    const std::array<int, 3> L{column_of(columns, "Lx"), column_of(columns, "Ly"),
                               column_of(columns, "Lz")};
    const std::array<int, 3> w{column_of(columns, "omega1"), column_of(columns, "omega2"),
                               column_of(columns, "omega3")};
    const bool has_L = *std::min_element(L.begin(), L.end()) > 0;
    // L in space from omega: R(q) I omega, which leaves out a wheel's momentum (a model with
    // wheels shows L only where the run recorded Lx..Lz, as `--view` does)
    const bool has_w =
        !rotor && scene.model.wheels.empty() && *std::min_element(w.begin(), w.end()) > 0;
    const Eigen::Matrix3d tensor = has_w ? tensor_at(scene) : Eigen::Matrix3d::Zero();
    view_data d;
    d.columns = columns;
    d.body = view_body_of(scene);
    for (const auto& row : rows) {
        d.t.push_back(row[0]);
        const auto a = quaternion
                           ? std::array<double, 4>{row[q[0]], row[q[1]], row[q[2]], row[q[3]]}
                           : quaternion_of_angles(scene.model.angles, row[angles[0]],
                                                  row[angles[1]], rotor ? 0.0 : row[angles[2]]);
        d.q.insert(d.q.end(), a.begin(), a.end());
        if (has_L)
            for (int k : L)
                d.L.push_back(row[k]);
        else if (has_w) { // L in space = R(q) I omega
            const Eigen::Quaterniond r(a[0], a[1], a[2], a[3]);
            const Eigen::Vector3d l =
                r * (tensor * Eigen::Vector3d(row[w[0]], row[w[1]], row[w[2]]));
            d.L.insert(d.L.end(), {l[0], l[1], l[2]});
        }
        d.values.insert(d.values.end(), row.begin() + 1, row.end());
    }
    return d;
}

namespace {

std::string json_string(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\')
            out += std::string("\\") + c;
        else if (c == '<')
            out += "\\u003c"; // never "</script>" inside the page's script
        else if (static_cast<unsigned char>(c) < 0x20)
            out += ' ';
        else
            out += c;
    }
    return out + "\"";
}

// Numbers to 17 significant digits (every double round-trips), or `digits` (the read-out shows 8);
// null where not finite.
template <class Range> std::string json_numbers(const Range& values, int digits = 17) {
    std::string out = "[";
    bool first = true;
    for (double v : values) {
        out += first ? "" : ",";
        out += !std::isfinite(v) ? "null"
               : digits == 17    ? format_number(v)
                                 : short_number(v, digits);
        first = false;
    }
    return out + "]";
}

std::string json_strings(const std::vector<std::string>& names) {
    std::string out = "[";
    for (std::size_t i = 0; i < names.size(); ++i)
        out += (i ? "," : "") + json_string(names[i]);
    return out + "]";
}

std::string json_of(const view_data& d) {
    const view_body& b = d.body;
    std::ostringstream os;
    os << "{\"title\":" << json_string(d.title) << ",\"t\":" << json_numbers(d.t)
       << ",\"q\":" << json_numbers(d.q) << ",\"L\":" << (d.L.empty() ? "null" : json_numbers(d.L))
       << ",\"columns\":" << json_strings(d.columns) << ",\"values\":" << json_numbers(d.values, 9)
       << ",\"speed\":1,\"gravity\":" << (b.gravity ? "true" : "false")
       << ",\"body\":{\"kind\":" << json_string(b.kind) << ",\"size\":" << json_numbers(b.size)
       << ",\"centre\":" << json_numbers(b.centre) << ",\"axes\":" << json_numbers(b.axes)
       << ",\"wheels\":[";
    for (std::size_t k = 0; k < b.wheel_axes.size(); ++k)
        os << (k ? "," : "") << "{\"name\":" << json_string(b.wheel_names[k])
           << ",\"axis\":" << json_numbers(b.wheel_axes[k]) << "}";
    os << "]}}";
    return os.str();
}

std::string html_text(const std::string& s) {
    std::string out;
    for (char c : s)
        out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
    return out;
}

std::string read_library(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw user_error({path}, "the viewer needs three.js r111 (Debian: libjs-three), which "
                                 "is not installed here");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

} // namespace

std::string view_page(const view_data& d) {
    const std::string dir = ROTGEN_THREE_JS_DIR;
    std::string stamp = "written by rotgen " ROTGEN_VERSION " from " + d.source +
                        "; three.js r111 (MIT licence) and its OrbitControls are inlined";
    for (std::size_t at; (at = stamp.find("--")) != std::string::npos;)
        stamp.replace(at, 2, "- -"); // never "--" inside an HTML comment
    return fill_template(
        "viewer.html.in",
        {{"stamp", stamp},
         {"title", html_text(d.title)},
         {"three", read_library(dir + "/three.min.js")},
         {"orbit_controls", read_library(dir + "/examples/js/controls/OrbitControls.js")},
         {"data", json_of(d)}});
}

void write_view(const std::string& path, const view_data& data,
                const std::vector<std::string>& inputs, output_set* outputs) {
    const std::string page = view_page(data);
    atomic_file out(path, inputs);
    out.stream() << page;
    if (outputs)
        out.commit(*outputs); // appears with the command's other outputs
    else
        out.commit();
}

} // namespace rotgen
